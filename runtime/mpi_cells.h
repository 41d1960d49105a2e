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
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // A rank this one waited for has died (its process on this host ended):
  // the distribution or round it was part of cannot finish.
  class RankLost : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Whether this process saw another rank die (RankLost): the command then
  // ends the job instead of waiting for every rank at its end.
  bool a_rank_was_lost();

  // Whether this process was started by mpirun/srun (their environment).
  bool launched_by_mpi_launcher();

  // This process's rank in the launch, from the launcher's environment (0
  // without one): known before MPI starts and after it ends, for what only
  // rank 0 says (the error message of a command every rank runs).
  unsigned int launch_rank();

  // Under MPI: waits until every rank has come here, at most `seconds`;
  // true if they all did (and at once without MPI). A rank that exits with
  // a status other than 0 (an interruption's 130/143) makes mpirun end the
  // others at once, so the command line has every rank meet here after
  // rank 0 wrote run.txt's `ended:` line; a rank that died or hangs is
  // waited for no longer than the bound.
  bool all_ranks_meet(double seconds);

  // Refuses (InputError, exit 2 on every rank) a command that runs on one
  // process when mpirun/srun started several: each rank would run it alone,
  // into the same folder. Names the commands that use MPI.
  void require_one_process(const std::string &command);

  // The ranks of an MPI launch, or nothing when `use_mpi` is false. MPI (and
  // PETSc/SLEPc with it) is started once for the process (require_petsc) and
  // finalised at exit, not when the session ends: the run's `ended:` record is
  // written after the command returns, and MPI_Finalize under an mpirun that
  // is ending the job (a signal to mpirun) does not return.
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

  private:
    unsigned int rank_ = 0, size_ = 1;
    bool serialized_   = true;
    mutable unsigned int n_distributions_ = 0;
    // Rank 0's count of studies ended (share_round with 0), and of
    // distributions when the last one ended: a study whose distribution has
    // not started is one the other ranks wait for (WorkerRelease).
    mutable unsigned int studies_ended_ = 0, distributions_at_study_end_ = 0;
    friend class DistributionCount;
    friend unsigned long share_round(const MpiSession &, unsigned long);
    friend class WorkerRelease;
  };

  // Computes work(cell) for every cell of `todo`. On rank 0, `done(cell,
  // result, rank)` is called (one call at a time) as each finishes, in the
  // order they finish; an empty result (an interrupted cell) is not passed
  // on. `stop()` on rank 0 (e.g. after Ctrl-C) ends the handing-out. Every
  // rank returns when all cells are done or stopped. A rank that waits for
  // another (the manager for its workers, a worker for the manager) looks
  // about once a second whether it still lives, if it runs on this host,
  // and throws RankLost when it died (rank 0 after its own cell). Cells are handed out in
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

  // A study spread over the ranks (an ensemble, a ladder, the region) is
  // one distribution of members, then the rounds of its convergence checks
  // (verification/studies/convergence_check.h), each round a distribution:
  // before every round rank 0 says which checks go on (`mask`; 0: none,
  // the study ends) and every rank returns rank 0's mask. Every rank calls
  // it equally often; without MPI it returns `mask`.
  unsigned long share_round(const MpiSession &mpi, unsigned long mask);

  // On rank 0, leaving a command whose other ranks compute the members of
  // `n_studies` studies, by any way (an error or a stop included): for each
  // study not ended, releases the other ranks from its distribution if it
  // never started, then ends its rounds. Nothing on the other ranks or
  // without MPI.
  class WorkerRelease
  {
  public:
    explicit WorkerRelease(const MpiSession &mpi, unsigned int n_studies = 1) : mpi_(mpi), n_studies_(n_studies) {}
    ~WorkerRelease();
    WorkerRelease(const WorkerRelease &) = delete;
    WorkerRelease &operator=(const WorkerRelease &) = delete;

  private:
    const MpiSession &mpi_;
    unsigned int n_studies_;
  };
} // namespace beamslider
