// beamslider: one executable, one sub-command per task. Every sub-command
// reads a scene (meshes/*.prm, or its name), accepts parameter overrides
// (--set "Section/Name=value"), and writes CSV + plots into an output folder
// (default reports/<scene>/<command>).
//
//   beamslider modes SCENE [--slider-at S]          linear bending modes (SLEPc)
//   beamslider coefficients SCENE --method M        modal cubic coefficients
//   beamslider backbone SCENE --model rom|fe        backbone curves (harmonic balance)
//   beamslider simulate SCENE --model rom|fe|auto   free-slider adaptation run
//   beamslider sweep SCENE                          prescribed slider position sweeps
//   beamslider animate SCENE --model fe|rom         ParaView time series (.pvd)
//   beamslider ensemble SCENE --model rom|fe        K perturbed runs: outcome statistics, --against DIR
//   beamslider map SCENE --frequency A:B:S ...      outcome maps over a parameter grid (MPI: mpirun -np P)
//   beamslider identify SCENE --axis "S/N=A:B:S"... System 1's unknowns by the seed's facts
//   beamslider verify [SCENE] [--full]              the verification report
//   beamslider scene-template                       every parameter with unit and range
//
// Exit status: 0 success (a run that reaches a support is a physical outcome);
// 1 a run or a solver failed, or results could not be written; 2 bad input
// (options, scene, parameters; the message names the parameter, its value and
// the allowed range); 128 + signal when interrupted (130 Ctrl-C, 143 SIGTERM).
#include "io/interruption.h"
#include "verification/cli/command_line.h"
#include "verification/cli/commands.h"

#include <deal.II/base/multithread_info.h>

#include <iostream>

int main(int argc, char **argv)
{
  // MPI, PETSc and SLEPc are started only if a large eigenproblem needs
  // them (fem/petsc_session.h): Open MPI's start-up alone is ~0.6 s. deal.II's
  // own task parallelism stays on one thread (runs parallelise by process).
  dealii::MultithreadInfo::set_thread_limit(1);
  beamslider::install_interruption_handlers();
  beamslider::record_command_line(argc, argv);
  return beamslider::run_beamslider(argc, argv, std::cerr);
}
