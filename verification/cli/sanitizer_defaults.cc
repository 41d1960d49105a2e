// Default options of the sanitizer runtimes, compiled into every executable
// of the sanitizer build only (CMake option BEAMSLIDER_SANITIZE, see
// scripts/sanitize.sh), so that ctest, the test discovery that runs each test
// program at build time, and a developer starting a program by hand all get
// the same settings. ASAN_OPTIONS / UBSAN_OPTIONS in the environment still
// override them.
//
// detect_leaks=0: Open MPI (MPI_Init, through deal.II's MPI_InitFinalize)
// loads its components with dlopen and unloads them in MPI_Finalize, leaving
// some thousand allocations that LeakSanitizer reports with the module
// "<unknown module>" and a stack one frame deep (those libraries have no
// frame pointers). A suppression by library name cannot match them, and a
// deep (slow) unwinder on every malloc would cost more than the job's budget,
// so leak checking is off; AddressSanitizer still checks every access of our
// code (out of bounds, use after free, double free).
//
// exitcode=86: a sanitizer report must not look like one of the program's
// own exit codes (1 run failure, 2 input error, 130/143 interrupted).
extern "C" const char *__asan_default_options()
{
  return "detect_leaks=0:exitcode=86:check_initialization_order=1:strict_string_checks=1";
}

extern "C" const char *__ubsan_default_options()
{
  return "print_stacktrace=1:halt_on_error=1:exitcode=86";
}
