// A request to stop a long computation: Ctrl-C, kill, or the Python
// module's interrupt() from another thread.
//
// Long loops (runs/adaptation_run.h's time stepping, an eigensolver, a
// Newton iteration, a continuation) poll interruption_requested() or call
// stop_if_interrupted() between steps; they finish the step they are in and
// stop. The models only read this flag; what sets it is the command's
// business (io/interruption.h turns SIGINT and SIGTERM into a request).
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

  // True once a stop was requested (cheap: one relaxed atomic load).
  bool interruption_requested();

  // The signal that asked for the stop (0 if none).
  int interruption_signal();

  // 128 + the signal, the exit status of an interrupted command.
  int interruption_exit_code();

  // As if `signal` had arrived: a signal handler, or a caller in another
  // thread (the Python module's interrupt()), stops the run at its next
  // step. The first signal is kept; a second one changes nothing. Safe in a
  // signal handler (one lock-free atomic operation).
  void request_interruption(int signal);

  // Forgets a signal that arrived: a new command starts in the same process.
  void clear_interruption();

  // For tests: pretend that `signal` arrived (0 clears the flag).
  void set_interruption_for_testing(int signal);
} // namespace beamslider
