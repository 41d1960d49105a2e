// One failure for all ranks. Work that is not collective (rank 0 writing a
// CSV file, each rank its .vtu piece) can fail on some ranks only; the ranks
// that went on would then wait in the next collective for one that left, and
// the ranks would exit with different statuses. fail_together() runs such
// work on every rank and then lets all of them learn how it ended: if it
// failed anywhere, every rank throws the lowest failing rank's error, of the
// same kind (InputError, FolderInUseError, OutputError,
// std::invalid_argument, else std::runtime_error) with the same message, so
// that rank 0 prints it once and all exit with its status.
#pragma once

#include <mpi.h>

#include <functional>

namespace beamslider
{
  // Collective over `comm` (every rank calls it, `work` may do nothing on
  // some). Without MPI, or on one rank, it is `work()`.
  void fail_together(MPI_Comm comm, const std::function<void()> &work);
} // namespace beamslider
