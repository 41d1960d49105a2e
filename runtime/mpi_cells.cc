// Manager–worker distribution of cells over MPI, see mpi_cells.h.
#include "runtime/mpi_cells.h"

#include "scene/scene.h"
#include "runtime/parallel_for.h"

#include "fem/petsc_session.h"


#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unistd.h>
#include <vector>

namespace beamslider
{
  namespace
  {
    constexpr int tag_result = 1, tag_cell = 2, tag_stop = 3;

    void check(const int error, const char *what)
    {
      if (error != MPI_SUCCESS)
        throw std::runtime_error(std::string("MPI: ") + what + " failed (error code " + std::to_string(error) + ")");
    }
  } // namespace

  namespace
  {
    const MpiSession *active_session = nullptr; // MpiSession::active()

    // Each rank's host and process id, gathered when MPI starts, so that a
    // rank waiting for another can tell whether it still lives: mpirun told
    // not to end the job when a rank dies (orte_abort_on_non_zero_status 0)
    // would otherwise leave the survivors waiting forever.
    struct Peer
    {
      std::uint64_t host = 0;
      std::int64_t pid   = 0;
    };
    std::vector<Peer> peers;
    std::uint64_t own_host = 0; // this rank's, as gathered
    std::atomic<bool> rank_lost{false};

    std::uint64_t this_host()
    {
      char name[256] = {};
      ::gethostname(name, sizeof name - 1);
      return std::hash<std::string>()(name);
    }

    // Whether the process `pid` of this host has ended (or is a zombie its
    // launcher has not reaped yet).
    bool process_ended(const std::int64_t pid)
    {
      if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
        return true;
      std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
      std::string line;
      if (!std::getline(stat, line))
        return false;
      const std::size_t name_end = line.rfind(')');
      return name_end != std::string::npos && name_end + 2 < line.size() &&
             (line[name_end + 2] == 'Z' || line[name_end + 2] == 'X');
    }

    // Throws RankLost if `rank` is known to have died. A rank on another
    // host cannot be seen from here: it is taken to live (mpirun's default
    // ends the job when a rank dies there).
    void require_alive(const unsigned int rank)
    {
      if (rank >= peers.size() || peers[rank].host != own_host || !process_ended(peers[rank].pid))
        return;
      rank_lost = true;
      throw RankLost("rank " + std::to_string(rank) + " (process " + std::to_string(peers[rank].pid) +
                     ") ended in the middle of the run, so the job ends; the rows finished before are kept in the "
                     "output folder (run the command again to compute the rest)");
    }

    // A wait by probing and sleeping that looks, about once a second,
    // whether the ranks in `watched` still live.
    class PatientWait
    {
    public:
      void pause(const std::vector<unsigned int> &watched)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        if (++polls_ % 500 != 0)
          return;
        for (const unsigned int rank : watched)
          require_alive(rank);
      }

    private:
      unsigned long polls_ = 0;
    };

    // Completes `request` (an Isend, an Ibcast) by testing and sleeping,
    // watching that rank 0 still lives meanwhile.
    void wait_watching_rank_zero(MPI_Request &request)
    {
      PatientWait wait;
      for (int done = 0;;)
        {
          check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
          if (done)
            return;
          wait.pause({0});
        }
    }
  } // namespace

  bool a_rank_was_lost() { return rank_lost; }

  // distribute_cells counts itself on the session (MpiSession::n_distributions).
  class DistributionCount
  {
  public:
    static void add(const MpiSession &mpi) { ++mpi.n_distributions_; }
  };

  bool launched_by_mpi_launcher()
  {
    // Open MPI's mpirun, PMIx launchers (srun with PMIx), MPICH/Hydra's PMI.
    for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
      if (std::getenv(name))
        return true;
    return false;
  }

  unsigned int launch_rank()
  {
    for (const char *name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
      if (const char *rank = std::getenv(name))
        return static_cast<unsigned int>(std::strtoul(rank, nullptr, 10));
    return 0;
  }

  bool all_ranks_meet(const double seconds)
  {
    int started = 0, finished = 0;
    MPI_Initialized(&started);
    if (started)
      MPI_Finalized(&finished);
    if (!started || finished)
      return true;
    MPI_Request request;
    if (MPI_Ibarrier(MPI_COMM_WORLD, &request) != MPI_SUCCESS)
      return false;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int done       = 0;
    while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && !done)
      {
        if (std::chrono::steady_clock::now() > end)
          return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    return done != 0;
  }

  void require_one_process(const std::string &command)
  {
    // Open MPI and MPICH/Hydra say the launch's size; a PMIx launcher alone
    // does not (then nothing is refused).
    for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
      if (const char *size = std::getenv(name))
        if (std::strtoul(size, nullptr, 10) > 1)
          throw InputError("'" + command + "' runs on one process, and this launch started " + size +
                           " (mpirun -n " + size + "): run it without mpirun. On MPI run ensemble, ladder, map, "
                           "verify, and modes, statics and coefficients of a solid scene");
  }

  MpiSession::MpiSession(const bool use_mpi)
  {
    if (!use_mpi)
      return;
    require_petsc(); // keeps this process's SIGTERM and SIGINT handlers
    int rank = 0, size = 1, provided = MPI_THREAD_SINGLE;
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
    check(MPI_Query_thread(&provided), "MPI_Query_thread");
    rank_       = rank;
    size_       = size;
    serialized_ = provided >= MPI_THREAD_SERIALIZED;
    active_session = this;
    own_host = this_host();
    const Peer me{own_host, static_cast<std::int64_t>(::getpid())};
    peers.assign(size_, Peer{});
    check(MPI_Allgather(&me, sizeof(Peer), MPI_BYTE, peers.data(), sizeof(Peer), MPI_BYTE, MPI_COMM_WORLD),
          "MPI_Allgather");
  }

  const MpiSession *MpiSession::active() { return active_session; }

  MpiSession::~MpiSession()
  {
    if (active_session == this)
      active_session = nullptr;
  }

  namespace
  {
    // One distribution's cells and what is done with them: which cell is
    // next, and each result passed on, one at a time.
    struct Distribution
    {
      const std::vector<std::size_t> &todo;
      const std::function<std::string(std::size_t)> &work;
      const std::function<void(std::size_t, const std::string &, unsigned int)> &done;
      const std::function<bool()> &stop;
      std::atomic<std::size_t> next{0};
      std::mutex done_mutex{};
      std::atomic<bool> lost{false}; // a worker died: hand out no more

      // The next cell to hand out, or npos when all are out or we stop.
      std::size_t take()
      {
        if (lost || stop())
          return std::string::npos;
        const std::size_t k = next++;
        return k < todo.size() ? todo[k] : std::string::npos;
      }

      void finish(const std::size_t cell, const std::string &result, const unsigned int rank)
      {
        if (result.empty())
          return;
        const std::lock_guard<std::mutex> lock(done_mutex);
        done(cell, result, rank);
      }

      // Cells computed on this thread until none is left.
      void work_through()
      {
        for (std::size_t cell = take(); cell != std::string::npos; cell = take())
          finish(cell, work(cell), 0);
      }
    };

    // Without MPI: one cell after another, or threads that take the cells in
    // the order of `todo`, as the ranks would.
    void distribute_in_process(Distribution &d, const unsigned int n_threads)
    {
      if (n_threads == 1)
        {
          d.work_through();
          return;
        }
      parallel_for(d.todo.size(), n_threads, [&](std::size_t) {
        const std::size_t cell = d.take();
        if (cell != std::string::npos)
          d.finish(cell, d.work(cell), 0);
      });
    }

    // The manager on rank 0: answers every request until each worker has had
    // its stop.
    void manage_workers(const MpiSession &mpi, Distribution &d)
    {
      std::vector<unsigned int> active; // the workers not yet stopped
      for (unsigned int r = 1; r < mpi.size(); ++r)
        active.push_back(r);
      std::vector<char> buffer;
      PatientWait wait;
      while (!active.empty())
        {
          int flag = 0;
          MPI_Status status;
          check(MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
          if (!flag)
            {
              // Sleeping, not spinning: the manager shares a core with rank 0's work.
              wait.pause(active);
              continue;
            }
          int count = 0;
          check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
          buffer.resize(std::max(count, 1));
          check(MPI_Recv(buffer.data(), count, MPI_CHAR, status.MPI_SOURCE, tag_result, MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE),
                "MPI_Recv");
          if (count >= 8)
            {
              std::uint64_t cell = 0;
              std::memcpy(&cell, buffer.data(), 8);
              d.finish(cell, std::string(buffer.data() + 8, count - 8), status.MPI_SOURCE);
            }
          const std::size_t cell = d.take();
          if (cell != std::string::npos)
            {
              const std::uint64_t c = cell;
              check(MPI_Send(&c, 1, MPI_UINT64_T, status.MPI_SOURCE, tag_cell, MPI_COMM_WORLD), "MPI_Send");
            }
          else
            {
              check(MPI_Send(nullptr, 0, MPI_UINT64_T, status.MPI_SOURCE, tag_stop, MPI_COMM_WORLD), "MPI_Send");
              active.erase(std::find(active.begin(), active.end(), static_cast<unsigned int>(status.MPI_SOURCE)));
            }
        }
    }

    // Rank 0: the manager on a second thread while this one computes cells,
    // or the manager alone if MPI's thread support does not allow that.
    void distribute_as_manager(const MpiSession &mpi, Distribution &d)
    {
      if (mpi.manager_can_work())
        {
          // A dead worker ends the manager; rank 0 then hands itself no
          // more cells and says why once its own cell is done.
          std::exception_ptr failure;
          std::thread manager([&] {
            try
              {
                manage_workers(mpi, d);
              }
            catch (...)
              {
                failure = std::current_exception();
                d.lost  = true;
              }
          });
          d.work_through();
          manager.join();
          if (failure)
            std::rethrow_exception(failure);
        }
      else
        manage_workers(mpi, d);
    }

    // A worker: ask, compute, send back, until told to stop.
    void work_for_manager(const std::function<std::string(std::size_t)> &work)
    {
      std::vector<char> message;
      while (true)
        {
          // Sent without blocking: a result larger than MPI's eager limit
          // waits for rank 0 to take it, and rank 0 may have died.
          MPI_Request sent;
          check(MPI_Isend(message.data(), message.size(), MPI_CHAR, 0, tag_result, MPI_COMM_WORLD, &sent),
                "MPI_Isend");
          wait_watching_rank_zero(sent);
          // Waiting by probing and sleeping, not in a blocking receive (which
          // Open MPI spins in): the answer may be long in coming when rank 0
          // does other work first (verify's sections before the ladder), and
          // the core is rank 0's meanwhile.
          MPI_Status status;
          PatientWait wait;
          for (int flag = 0; !flag;)
            {
              check(MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
              if (!flag)
                wait.pause({0});
            }
          std::uint64_t cell = 0;
          check(MPI_Recv(&cell, 1, MPI_UINT64_T, 0, status.MPI_TAG, MPI_COMM_WORLD, &status), "MPI_Recv");
          if (status.MPI_TAG == tag_stop)
            return;
          const std::string result = work(cell);
          message.resize(8 + result.size());
          std::memcpy(message.data(), &cell, 8);
          std::memcpy(message.data() + 8, result.data(), result.size());
        }
    }
  } // namespace

  void distribute_cells(const MpiSession &mpi, const std::vector<std::size_t> &todo,
                        const std::function<std::string(std::size_t)> &work,
                        const std::function<void(std::size_t, const std::string &, unsigned int)> &done,
                        const std::function<bool()> &stop, const unsigned int n_threads)
  {
    DistributionCount::add(mpi);
    Distribution distribution{todo, work, done, stop};
    if (mpi.size() == 1)
      distribute_in_process(distribution, n_threads);
    else if (mpi.rank() == 0)
      distribute_as_manager(mpi, distribution);
    else
      work_for_manager(work);
  }

  void release_workers(const MpiSession &mpi)
  {
    if (mpi.size() > 1 && mpi.rank() == 0)
      distribute_cells(
        mpi, {}, [](std::size_t) { return std::string(); }, [](std::size_t, const std::string &, unsigned int) {},
        [] { return true; });
  }

  unsigned long share_round(const MpiSession &mpi, unsigned long mask)
  {
    if (mpi.size() > 1)
      {
        static_assert(sizeof(unsigned long) == 8, "the mask travels as 64 bits");
        // Waited for as the cells are, so that a dead rank 0 is seen.
        MPI_Request request;
        check(MPI_Ibcast(&mask, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request), "MPI_Ibcast");
        wait_watching_rank_zero(request);
      }
    if (mpi.rank() == 0 && mask == 0)
      {
        ++mpi.studies_ended_;
        mpi.distributions_at_study_end_ = mpi.n_distributions_;
      }
    return mask;
  }

  WorkerRelease::~WorkerRelease()
  {
    if (mpi_.size() == 1 || mpi_.rank() != 0)
      return;
    try
      {
        while (mpi_.studies_ended_ < n_studies_)
          {
            if (mpi_.n_distributions_ == mpi_.distributions_at_study_end_)
              release_workers(mpi_); // they wait for the study's members
            share_round(mpi_, 0);    // then for its rounds
          }
      }
    catch (...)
      {
        // Leaving anyway: an MPI failure here has nobody left to tell.
      }
  }
} // namespace beamslider
