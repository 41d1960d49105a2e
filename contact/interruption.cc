// SIGINT/SIGTERM as a polled flag, see interruption.h.
#include "contact/interruption.h"

#include <atomic>
#include <csignal>
#include <string>

namespace beamslider
{
  namespace
  {
    // Lock-free, so it may be written from a signal handler.
    std::atomic<int> received_signal{0};
    static_assert(std::atomic<int>::is_always_lock_free);

    extern "C" void on_signal(const int signal)
    {
      int expected = 0;
      received_signal.compare_exchange_strong(expected, signal, std::memory_order_relaxed);
    }
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

  void install_interruption_handlers()
  {
    struct sigaction action = {};
    action.sa_handler       = on_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART; // a write or waitpid in progress completes
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
    std::signal(SIGXFSZ, SIG_IGN);
    // A chart process that died early must not kill the run when the run
    // writes its arguments to it (verification/studies/child_process.h): the write
    // fails with EPIPE instead, and the failure is reported.
    std::signal(SIGPIPE, SIG_IGN);
  }

  bool interruption_requested() { return received_signal.load(std::memory_order_relaxed) != 0; }

  int interruption_signal() { return received_signal.load(std::memory_order_relaxed); }

  int interruption_exit_code() { return 128 + interruption_signal(); }

  void request_interruption(const int signal) { on_signal(signal); }

  void clear_interruption() { received_signal.store(0, std::memory_order_relaxed); }

  void set_interruption_for_testing(const int signal) { received_signal.store(signal, std::memory_order_relaxed); }
} // namespace beamslider
