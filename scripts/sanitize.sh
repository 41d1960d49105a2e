#!/usr/bin/env bash
# Builds beamslider with AddressSanitizer and UndefinedBehaviorSanitizer in
# ./build-sanitize (CMake option BEAMSLIDER_SANITIZE) and runs the fast tests
# under them. CI runs it after the plain build and tests (.ci/run); a
# developer can run it alone. Extra arguments go to the CMake configure step,
# e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache.
#
# Only our code is instrumented: the installed deal.II, PETSc, SLEPc, VTK and
# Open MPI are not (their errors are not seen). Sanitizer settings are
# compiled into the programs (verification/cli/sanitizer_defaults.cc): leak
# checking off (Open MPI's unloaded components), exit code 86 on a report.
#
# The tests: the programs below are built and every test in them runs.
#   test_contact_*, test_reduced_*  the Eigen-only numerics (contact
#       solver, Moreau stepper, ROM, harmonic balance): most of our own
#       arithmetic and indexing, cheap to build
#   test_io_*, test_runs_*  checked files and CSV, run statistics and trace
#       analysis
#   test_scene, test_simulation_cases    the scene reader and the cases
#   test_rom_explicit_modal_step         the ROM's own Moreau step against
#       the general one
#   test_parallel_for                    threads, and exceptions across them
#   test_cli_*                           the built program end to end
#       (hardening, checkpoint/resume, fuzzing of scene files and --set),
#       itself built with the sanitizers
# Left out: test_fem_* (their work is mostly inside the uninstrumented
# deal.II/PETSc; each adds a heavy compile), test_reduced_backbone_timing
# (a timing study, slow under the sanitizers); test_cli_solid and
# test_cli_reference_check, and the ladders of test_cli_member_runs and of
# test_cli_commands: nearly all their time is FE time stepping or the
# solid's MUMPS solves (2 to 4 min each here, 16 min of the job's test time
# in all), and the files and resumes they check are the ROM ensembles' and
# maps' code, which runs here; the plain job runs them all. Also two long
# runs of
# test_cli_checkpoint: the FE resume (2 s of FE time stepping, ~100 s here,
# nearly all inside deal.II/PETSc) and the kill -9 resume (a 60 s ROM run that
# under the sanitizers outlasts the test's 120 s limit); the ROM resume and
# the refusal of foreign checkpoints run. For the same reason the FE case of
# test_cli_interrupt (three runs of 1.5 s of FE time stepping) is left out;
# its ROM case runs. Of the other interrupt cases, those whose time is
# mostly the FE (`verify` of sections 1 and 2, of section 3 with the FE
# backbone, the ladder with its FE reference) or the solid's MUMPS solves
# (`statics`, `modes`, `coefficients` on the solid, and section 8 beside the
# others) are left out too: about 10 of the job's 33 min of test time (CPU)
# here, for code the ROM, ensemble, sweep and map cases run as well (the
# stop, the whole rows, the resume).
#
# Built for the baseline instruction set (BEAMSLIDER_NATIVE=OFF), so that CI
# runs the tests on both builds: the plain job on the build for the machine
# (the default), this one on the portable build.
set -euo pipefail
cd "$(dirname "$0")/.."

targets=(beamslider test_scene test_simulation_cases test_parallel_for test_rom_explicit_modal_step)
for source in tests/test_contact_*.cc tests/test_io_*.cc tests/test_runs_*.cc tests/test_reduced_*.cc tests/test_cli_*.cc; do
  name=$(basename "$source" .cc)
  case "$name" in
    test_reduced_backbone_timing | test_cli_solid | test_cli_reference_check) ;;
    *) targets+=("$name") ;;
  esac
done

start=$SECONDS
echo "== configuring ./build-sanitize (AddressSanitizer + UndefinedBehaviorSanitizer)"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DBEAMSLIDER_SANITIZE=ON -DBEAMSLIDER_NATIVE=OFF "$@" > build-sanitize.log 2>&1 ||
  { cat build-sanitize.log; exit 1; }
echo "== building ${targets[*]}"
cmake --build build-sanitize -j "$(nproc)" --target "${targets[@]}" >> build-sanitize.log 2>&1 ||
  { tail -80 build-sanitize.log; exit 1; }
echo "== built in $((SECONDS - start)) s; running the tests of those programs"
# Programs that were not built register a placeholder test <name>_NOT_BUILT.
ctest --test-dir build-sanitize --output-on-failure -j 2 \
  -E '_NOT_BUILT$|^Resume\.FiniteElementRunIsBitIdentical|^Resume\.AfterKillNine|^Commands/Interrupt\..*/(simulate_fe|verify|verify_backbones|ladder|statics_solid|modes_solid|coefficients_solid_ice)( |$)|^MemberRuns\.(LadderKilled|AMembersFileCutShort|TwoRanksUnderMpirun)|^Commands\.LadderWritesRungs|^Commands\.VerifyRunsSectionEightBeside'
echo "== sanitizer job passed in $((SECONDS - start)) s"
