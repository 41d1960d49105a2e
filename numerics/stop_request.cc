// The stop request as a polled flag, see stop_request.h.
#include "numerics/stop_request.h"

#include <atomic>
#include <string>

namespace beamslider
{
  namespace
  {
    // Lock-free, so it may be written from a signal handler.
    std::atomic<int> received_signal{0};
    static_assert(std::atomic<int>::is_always_lock_free);
  } // namespace

  Interrupted::Interrupted(const int signal)
    : std::runtime_error("interrupted by signal " + std::to_string(signal))
    , signal_(signal)
  {}

  void stop_if_interrupted()
  {
    if (const int signal = interruption_signal())
      throw Interrupted(signal);
  }

  bool interruption_requested() { return received_signal.load(std::memory_order_relaxed) != 0; }

  int interruption_signal() { return received_signal.load(std::memory_order_relaxed); }

  int interruption_exit_code() { return 128 + interruption_signal(); }

  void request_interruption(const int signal)
  {
    int expected = 0;
    received_signal.compare_exchange_strong(expected, signal, std::memory_order_relaxed);
  }

  void clear_interruption() { received_signal.store(0, std::memory_order_relaxed); }

  void set_interruption_for_testing(const int signal) { received_signal.store(signal, std::memory_order_relaxed); }
} // namespace beamslider
