#include "fem/mpi_interruption.h"

#include "numerics/stop_request.h"
#include "fem/petsc_session.h"

namespace beamslider
{
  int agreed_interruption_signal(const MPI_Comm comm)
  {
    int signal = interruption_signal();
    if (!mpi_started())
      return signal;
    int any = 0;
    MPI_Allreduce(&signal, &any, 1, MPI_INT, MPI_MAX, comm);
    if (any != 0 && signal == 0)
      request_interruption(any);
    return any;
  }

  void stop_if_interrupted(const MPI_Comm comm)
  {
    if (const int signal = agreed_interruption_signal(comm))
      throw Interrupted(signal);
  }
} // namespace beamslider
