// Independent cells (of a map, an ensemble) spread over MPI ranks by a
// manager–worker loop: rank 0 hands out one cell at a time to whichever rank
// asks, so that cells of very different cost keep every rank busy, and
// receives each result as soon as it is done. Rank 0 computes cells too (on
// its main thread, while a second thread answers the other ranks), so two
// ranks on two cores are two workers. Without MPI the cells run in threads
// of the one process (parallel_for), taken in the order given.
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
    // The session of this process started with use_mpi (nullptr if none):
    // for a study deep inside a command (verify's ladder) to find the ranks.
    static const MpiSession *active();
    unsigned int rank() const { return rank_; }
    unsigned int size() const { return size_; }
    // Whether rank 0 may compute cells while its second thread talks to the
    // other ranks (MPI's thread support is at least "serialized").
    bool manager_can_work() const { return serialized_; }
    // How many distributions (distribute_cells) this process has taken
    // part in: a command with one distribution among other work (verify)
    // releases the other ranks if it ends without reaching it.
    unsigned int n_distributions() const { return n_distributions_; }
    // Whether rank 0 has told the other ranks that no further round of a
    // convergence check follows (share_round with 0, or end_rounds).
    bool rounds_ended() const { return rounds_ended_; }

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    unsigned int rank_ = 0, size_ = 1;
    bool serialized_   = true;
    mutable unsigned int n_distributions_ = 0;
    mutable bool rounds_ended_            = false;
    friend class DistributionCount;
    friend unsigned long share_round(const MpiSession &, unsigned long);
  };

  // Computes work(cell) for every cell of `todo`. On rank 0, `done(cell,
  // result, rank)` is called (one call at a time) as each finishes, in the
  // order they finish; an empty result (an interrupted cell) is not passed
  // on. `stop()` on rank 0 (e.g. after Ctrl-C) ends the handing-out. Every
  // rank returns when all cells are done or stopped. Cells are handed out in
  // the order of `todo` (longest first keeps the ranks busy to the end).
  // In a single process (no mpirun), `n_threads` threads compute cells
  // (0: one per core; the default 1 computes them one after another);
  // work() must then be safe to call from several threads at once.
  void distribute_cells(const MpiSession &mpi, const std::vector<std::size_t> &todo,
                        const std::function<std::string(std::size_t)> &work,
                        const std::function<void(std::size_t, const std::string &, unsigned int)> &done,
                        const std::function<bool()> &stop, unsigned int n_threads = 1);

  // Under MPI on rank 0: answers the other ranks' first request with `stop`
  // (a distribution of no cells), for a command whose other ranks wait for
  // a distribution that rank 0 did not reach. Nothing without MPI.
  void release_workers(const MpiSession &mpi);

  // The rounds of a convergence check (verification/studies/
  // convergence_check.h) after a distribution of members: rank 0 says which
  // checks go on (`mask`, 0: none, no further round) and every rank returns
  // rank 0's mask. Every rank calls it equally often; without MPI it returns
  // `mask`.
  unsigned long share_round(const MpiSession &mpi, unsigned long mask);

  // On rank 0, leaving a command whose other ranks compute its members
  // (an ensemble, a ladder) by any way, an error or a stop included: releases
  // them if it never handed out a member, then tells them that no further
  // round follows, unless it did. Nothing on the other ranks or without MPI.
  class WorkerRelease
  {
  public:
    explicit WorkerRelease(const MpiSession &mpi, bool workers_wait = true) : mpi_(mpi), waiting_(workers_wait) {}
    ~WorkerRelease();
    WorkerRelease(const WorkerRelease &) = delete;
    WorkerRelease &operator=(const WorkerRelease &) = delete;

  private:
    const MpiSession &mpi_;
    bool waiting_;
  };
} // namespace beamslider
