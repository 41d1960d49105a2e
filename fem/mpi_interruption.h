// Ctrl-C and kill under MPI: every rank stops at the same point.
//
// A signal reaches the ranks at different moments (mpirun forwards it to
// each, or a user signals one process), so a rank that stopped on its own
// would leave the others waiting in the next collective call. Here the
// ranks decide together: the check is itself a collective (one integer
// reduced over the communicator), called where every rank is at the same
// point (a Newton iteration, an eigensolver iteration, a load step).
#pragma once

#include <mpi.h>

namespace beamslider
{
  // The signal any rank of `comm` received (the largest, 0 if none); a rank
  // that had none takes it over, so that it ends with the same exit status.
  // Without MPI started, this process's own signal.
  int agreed_interruption_signal(MPI_Comm comm);

  // Throws Interrupted on every rank of `comm` if any rank received a signal.
  void stop_if_interrupted(MPI_Comm comm);
} // namespace beamslider
