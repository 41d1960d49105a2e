// Ctrl-C and kill without losing finished work.
//
// install_interruption_handlers() makes SIGINT and SIGTERM set a flag instead
// of killing the process. Long loops (AdaptationRun's time stepping, the
// studies built on it) poll interruption_requested() once per step, finish
// the step they are in, and stop with status `interrupted`; the command then
// writes complete rows and its summary and exits with 128 + the signal
// (130 for SIGINT, 143 for SIGTERM), as a shell expects. A second signal of
// the same kind while the first is being handled is ignored: the run is
// already stopping.
//
// It also ignores SIGXFSZ, so that a file-size limit makes a write fail (and
// OutputFile report it) instead of killing the process with a half-written
// row, and SIGPIPE, so that writing to a chart process that died makes the
// write fail rather than the run.
#pragma once

#include <stdexcept>

namespace beamslider
{
  // Thrown where a computation that has no step of its own to finish (an
  // eigensolver, a Newton iteration, a continuation) stops for a signal.
  // The command layer turns it into 128 + the signal, as an interrupted
  // time-stepping run that ends with status `interrupted`.
  class Interrupted : public std::runtime_error
  {
  public:
    explicit Interrupted(int signal);
    int signal() const { return signal_; }

  private:
    int signal_;
  };

  // Throws Interrupted if SIGINT or SIGTERM arrived. Single-process code
  // only: under MPI every rank must decide together (fem/mpi_interruption.h).
  void stop_if_interrupted();

  void install_interruption_handlers();

  // True once SIGINT or SIGTERM arrived (cheap: one relaxed atomic load).
  bool interruption_requested();

  // The signal that arrived (0 if none).
  int interruption_signal();

  // 128 + the signal, the exit status of an interrupted command.
  int interruption_exit_code();

  // As if `signal` had arrived: a caller in another thread (the Python
  // module's interrupt()) stops the run at its next step. The first signal
  // is kept, as with real ones.
  void request_interruption(int signal);

  // Forgets a signal that arrived: a new command starts in the same process.
  void clear_interruption();

  // For tests: pretend that `signal` arrived (0 clears the flag).
  void set_interruption_for_testing(int signal);
} // namespace beamslider
