// SIGINT/SIGTERM as a stop request, see interruption.h.
#include "io/interruption.h"

#include <csignal>

namespace beamslider
{
  namespace
  {
    extern "C" void on_signal(const int signal) { request_interruption(signal); }
  } // namespace

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
    // writes its arguments to it (runtime/child_process.h): the write
    // fails with EPIPE instead, and the failure is reported.
    std::signal(SIGPIPE, SIG_IGN);
  }
} // namespace beamslider
