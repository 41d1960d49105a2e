// Independent work items on the machine's cores: body(i) for every i in
// [0, n), each once, on up to n_threads threads (0: one per core, never
// more threads than items). Items are taken in ascending order as threads
// become free, so items of very different cost keep every thread busy.
// Used by ensembles (members) and maps (cells) within one process; across
// processes a map uses MPI (runtime/mpi_cells.h).
//
// If an item throws, no further items are started, the items already running
// finish, every thread is joined, and the first exception is rethrown to the
// caller (an exception may not leave a thread, and a thread may not be
// destroyed unjoined: either would end the program with std::terminate and
// no message).
//
// Why plain threads and not TBB (deal.II's own task layer): TBB's threads
// can only be had with deal.II's thread limit above one, and deal.II 9.4
// then changes its arithmetic, not just its speed: FEValues stops reusing a
// translated cell's Jacobian when more than one thread is allowed, which
// moves the beam's stiffness matrix in the last bit (325 entries on
// mueller2023) and with it the modes, the coefficients and every trace.
// Keeping deal.II at one thread (main() and the Python module set the limit)
// while TBB had two would take writing deal.II's private thread count. A run
// is one thread's work from start to end, so these threads share nothing
// with deal.II's.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace beamslider
{
  template <typename Body>
  void parallel_for(const std::size_t n, const unsigned int n_threads, const Body &body)
  {
    std::atomic<std::size_t> next{0};
    std::exception_ptr       first_error;
    std::mutex               error_mutex;
    const auto               work = [&]() noexcept {
      for (std::size_t i = next++; i < n; i = next++)
        try
          {
            body(i);
          }
        catch (...)
          {
            const std::lock_guard<std::mutex> lock(error_mutex);
            if (!first_error)
              first_error = std::current_exception();
            next = n; // start nothing new
          }
    };
    const std::size_t wanted = n_threads ? n_threads : std::max(1u, std::thread::hardware_concurrency());
    const std::size_t count  = std::max<std::size_t>(1, std::min(wanted, n));
    std::vector<std::thread> pool;
    pool.reserve(count - 1);
    for (std::size_t t = 1; t < count; ++t)
      pool.emplace_back(work);
    work();
    for (auto &t : pool)
      t.join();
    if (first_error)
      std::rethrow_exception(first_error);
  }
} // namespace beamslider
