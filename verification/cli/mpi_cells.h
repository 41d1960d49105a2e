// Independent cells (of a map, an ensemble) spread over MPI ranks by a
// manager–worker loop: rank 0 hands out one cell at a time to whichever rank
// asks, so that cells of very different cost keep every rank busy, and
// receives each result as soon as it is done. Rank 0 computes cells too (on
// its main thread, while a second thread answers the other ranks), so two
// ranks on two cores are two workers. Without MPI it is a plain loop.
//
// The MPI traffic: a worker sends its finished cell (tag `result`: the cell
// index as 8 bytes, then the result text; the first message carries no
// cell), the manager answers with the next cell index (tag `cell`) or `stop`.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace beamslider
{
  // Whether this process was started by mpirun/srun (their environment).
  bool launched_by_mpi_launcher();

  // MPI for the lifetime of the object (deal.II's MPI_InitFinalize, which
  // also starts PETSc/SLEPc), or nothing when `use_mpi` is false.
  class MpiSession
  {
  public:
    explicit MpiSession(bool use_mpi);
    ~MpiSession();
    unsigned int rank() const { return rank_; }
    unsigned int size() const { return size_; }
    // Whether rank 0 may compute cells while its second thread talks to the
    // other ranks (MPI's thread support is at least "serialized").
    bool manager_can_work() const { return serialized_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    unsigned int rank_ = 0, size_ = 1;
    bool serialized_   = true;
  };

  // Computes work(cell) for every cell of `todo`. On rank 0, `done(cell,
  // result, rank)` is called (one call at a time) as each finishes, in the
  // order they finish; an empty result (an interrupted cell) is not passed
  // on. `stop()` on rank 0 (e.g. after Ctrl-C) ends the handing-out. Every
  // rank returns when all cells are done or stopped.
  void distribute_cells(const MpiSession &mpi, const std::vector<std::size_t> &todo,
                        const std::function<std::string(std::size_t)> &work,
                        const std::function<void(std::size_t, const std::string &, unsigned int)> &done,
                        const std::function<bool()> &stop);
} // namespace beamslider
