// What this process does on SIGINT, SIGTERM, SIGPIPE and SIGXFSZ, kept
// across a library's start-up that would change it.
//
// MPI_Init (Open MPI) and PetscInitialize, both inside deal.II's
// MPI_InitFinalize, install handlers of their own: PETSc's turns a SIGTERM
// into an error message and MPI_Abort, so an mpirun stopped by Ctrl-C or
// SIGTERM ended every rank with exit 1, without the run's orderly stop
// (whole rows, "interrupted", run.txt's `ended:` line, exit 130/143). Held
// around that start-up, this object puts back what the process had set
// (the command line's handlers, io/interruption.h, or Python's).
#pragma once

#include <array>
#include <csignal>

namespace beamslider
{
  class KeptSignalDispositions
  {
  public:
    KeptSignalDispositions()
    {
      for (std::size_t i = 0; i < signals.size(); ++i)
        sigaction(signals[i], nullptr, &saved_[i]);
    }
    ~KeptSignalDispositions()
    {
      for (std::size_t i = 0; i < signals.size(); ++i)
        sigaction(signals[i], &saved_[i], nullptr);
    }
    KeptSignalDispositions(const KeptSignalDispositions &)            = delete;
    KeptSignalDispositions &operator=(const KeptSignalDispositions &) = delete;

  private:
    static constexpr std::array<int, 4> signals{{SIGINT, SIGTERM, SIGPIPE, SIGXFSZ}};
    std::array<struct sigaction, 4> saved_{};
  };
} // namespace beamslider
