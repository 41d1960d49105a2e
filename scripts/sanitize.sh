#!/usr/bin/env bash
# Builds beamslider with AddressSanitizer and UndefinedBehaviorSanitizer in
# ./build-sanitize (CMake option BEAMSLIDER_SANITIZE) and runs the fast tests
# under them. CI runs it after the plain build and tests (.ci/run); a
# developer can run it alone. Extra arguments go to the CMake configure step.
# Compiled through ccache where it is installed (scripts/compiler_cache.sh).
#
# Only our code is instrumented: the installed deal.II, PETSc, SLEPc, VTK and
# Open MPI are not (their errors are not seen). Sanitizer settings are
# compiled into the programs (verification/cli/sanitizer_defaults.cc): leak
# checking off (Open MPI's unloaded components), exit code 86 on a report.
#
# The tests: what sanitizers find bugs in, our own arithmetic, indexing,
# memory and signal handling, not the long studies (issue 72: CI well inside
# its 90 min; the plain job runs every test).
#   test_contact_*, test_reduced_*  the Eigen-only numerics (contact
#       solver, Moreau stepper, ROM, harmonic balance): most of our own
#       arithmetic and indexing, cheap to build
#   test_io_*, test_runs_*  checked files and CSV, run statistics and trace
#       analysis
#   test_scene                           the scene reader
#   test_rom_explicit_modal_step         the ROM's own Moreau step against
#       the general one
#   test_parallel_for                    threads, and exceptions across them
#   test_cli_ of the fault suite         the built program end to end, itself
#       built with the sanitizers: bad files and folders (run_folders,
#       scene_files, hardening, fuzz, faults), checkpoint/resume, signals
#       and child processes (interrupt, child_process)
# Left out: test_fem_* and the other whole-program tests (commands, map,
# member_runs, mesh_beams, identify, solid, reference_check): their time is
# FE time stepping inside deal.II/PETSc or the solid's MUMPS solves, which
# are not instrumented, and the files and resumes they write are the code
# the fault suite runs here. Of the fault suite, the cases whose time is
# mostly the FE or the solid are left out too: the FE resume (2 s of FE
# time stepping), the kill -9 resume (a 60 s ROM run that under the
# sanitizers outlasts its 120 s limit), the FE case of test_cli_interrupt
# and its cases of `verify` sections 1-3 and 8, the ladder with its FE
# reference, and `statics`, `modes`, `coefficients` on the solid. Of the
# ROM's interrupt cases the simulate, ensemble and map cases run (the
# checkpoint, the member list, the MPI cells); sweep, backbone_rom and
# identify, 60-90 s each here, stop and resume through the same code.
#
# Built for the baseline instruction set (BEAMSLIDER_NATIVE=OFF), so that CI
# runs the tests on both builds: the plain job on the build for the machine
# (the default), this one on the portable build.
set -euo pipefail
cd "$(dirname "$0")/.."

targets=(beamslider test_scene test_parallel_for test_rom_explicit_modal_step
         test_cli_run_folders test_cli_scene_files test_cli_hardening test_cli_fuzz test_cli_faults
         test_cli_checkpoint test_cli_interrupt test_cli_child_process)
for source in tests/test_contact_*.cc tests/test_io_*.cc tests/test_runs_*.cc tests/test_reduced_*.cc; do
  name=$(basename "$source" .cc)
  case "$name" in
    test_reduced_backbone_timing) ;;
    *) targets+=("$name") ;;
  esac
done

start=$SECONDS
echo "== configuring ./build-sanitize (AddressSanitizer + UndefinedBehaviorSanitizer)"
source scripts/compiler_cache.sh
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DBEAMSLIDER_SANITIZE=ON -DBEAMSLIDER_NATIVE=OFF \
  "${compiler_cache[@]}" "$@" > build-sanitize.log 2>&1 ||
  { cat build-sanitize.log; exit 1; }
echo "== building ${targets[*]}"
cmake --build build-sanitize -j "$(nproc)" --target "${targets[@]}" >> build-sanitize.log 2>&1 ||
  { tail -80 build-sanitize.log; exit 1; }
echo "== built in $((SECONDS - start)) s; running the tests of those programs"
# Programs that were not built register a placeholder test <name>_NOT_BUILT.
ctest --test-dir build-sanitize --output-on-failure -j 2 \
  -E '_NOT_BUILT$|^Resume\.FiniteElementRunIsBitIdentical|^Resume\.AfterKillNine|^Commands/Interrupt\..*/(simulate_fe|verify|verify_backbones|ladder|backbone_fe|backbone_rom|sweep|identify|statics_solid|modes_solid|coefficients_solid_ice)( |$)'
echo "== sanitizer job passed in $((SECONDS - start)) s"
