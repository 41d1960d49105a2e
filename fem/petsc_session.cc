#include "fem/petsc_session.h"

#include "numerics/kept_signal_dispositions.h"

#include <deal.II/base/mpi.h>

#include <mpi.h>

namespace beamslider
{
  bool mpi_started()
  {
    int initialised = 0;
    MPI_Initialized(&initialised);
    return initialised != 0;
  }

  void require_petsc()
  {
    // A function-local static: constructed once, by whichever thread comes
    // first (the others wait), destroyed at exit after main() returns, which
    // finalises SLEPc, PETSc and MPI in that order.
    struct Session
    {
      int argc            = 1;
      char name[16]       = "beamslider";
      char *argv_store[2] = {name, nullptr};
      char **argv         = argv_store;
      std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
      Session()
      {
        if (!mpi_started())
          {
            const KeptSignalDispositions kept; // MPI and PETSc would take SIGTERM and SIGINT
            // One thread for deal.II's own task parallelism, as main() sets.
            mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc, argv, 1);
          }
      }
    };
    static Session session;
  }
} // namespace beamslider
