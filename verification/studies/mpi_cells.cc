// Manager–worker distribution of cells over MPI, see mpi_cells.h.
#include "verification/studies/mpi_cells.h"

#include "meshes/scene.h"
#include "verification/studies/parallel_for.h"

#include "numerics/kept_signal_dispositions.h"

#include <deal.II/base/mpi.h>

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>

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
  }

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

  struct MpiSession::Impl
  {
    int argc            = 1;
    char name[16]       = "beamslider";
    char *argv_store[2] = {name, nullptr};
    char **argv         = argv_store;
    std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
  };

  MpiSession::MpiSession(const bool use_mpi)
  {
    if (!use_mpi)
      return;
    impl_ = std::make_unique<Impl>();
    {
      const KeptSignalDispositions kept; // MPI and PETSc would take SIGTERM and SIGINT
      impl_->mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(impl_->argc, impl_->argv, 1);
    }
    int rank = 0, size = 1, provided = MPI_THREAD_SINGLE;
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
    check(MPI_Query_thread(&provided), "MPI_Query_thread");
    rank_       = rank;
    size_       = size;
    serialized_ = provided >= MPI_THREAD_SERIALIZED;
    active_session = this;
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

      // The next cell to hand out, or npos when all are out or we stop.
      std::size_t take()
      {
        if (stop())
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
      unsigned int active = mpi.size() - 1;
      std::vector<char> buffer;
      while (active > 0)
        {
          int flag = 0;
          MPI_Status status;
          check(MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
          if (!flag)
            {
              // Sleeping, not spinning: the manager shares a core with rank 0's work.
              std::this_thread::sleep_for(std::chrono::milliseconds(2));
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
              --active;
            }
        }
    }

    // Rank 0: the manager on a second thread while this one computes cells,
    // or the manager alone if MPI's thread support does not allow that.
    void distribute_as_manager(const MpiSession &mpi, Distribution &d)
    {
      if (mpi.manager_can_work())
        {
          std::thread manager([&] { manage_workers(mpi, d); });
          d.work_through();
          manager.join();
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
          check(MPI_Send(message.data(), message.size(), MPI_CHAR, 0, tag_result, MPI_COMM_WORLD), "MPI_Send");
          // Waiting by probing and sleeping, not in a blocking receive (which
          // Open MPI spins in): the answer may be long in coming when rank 0
          // does other work first (verify's sections before the ladder), and
          // the core is rank 0's meanwhile.
          MPI_Status status;
          for (int flag = 0; !flag;)
            {
              check(MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status), "MPI_Iprobe");
              if (!flag)
                std::this_thread::sleep_for(std::chrono::milliseconds(2));
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
        check(MPI_Bcast(&mask, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
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
