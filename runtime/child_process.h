// Starting helper programs (the matplotlib scripts) without a shell.
//
// Paths and scene names come from the user; pasted into a shell command line
// they would be code (`--output "x';touch PWNED;'"`). A child is therefore
// started with posix_spawn and an argument vector: every argument reaches the
// program as one string, whatever characters it holds.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace beamslider
{
  struct ChildResult
  {
    bool started   = false; // the program could be started at all
    int exit_code  = -1;    // its exit status, when it exited normally
    int signal     = 0;     // the signal that ended it, else 0
    // Why it could not be started or did not succeed ("'prog' exited with
    // status 3", "... was ended by signal 9", "cannot start ..."): set
    // whenever succeeded() is false, so callers quote it as it is.
    std::string error;

    bool succeeded() const { return started && signal == 0 && exit_code == 0; }
  };

  // What a child inherits of this process's environment.
  enum class ChildEnvironment
  {
    inherited, // all of it
    // all but the variables an MPI launcher set for this process (OMPI_*,
    // PMIX_*, PMI_*; Open MPI's two run-as-root opt-ins are kept): a child
    // started by a process that itself runs under mpirun (a measurement
    // that starts `beamslider` or `mpirun` of its own) would otherwise take
    // them as its own launch and abort in MPI_Init.
    without_mpi_launch
  };

  // Whether `entry` ("NAME=value" of an environment) is one of those an MPI
  // launcher set for this process (see without_mpi_launch).
  bool is_mpi_launch_variable(std::string_view entry);

  // Whether a terminal's Ctrl-C (sent to the whole foreground process group)
  // reaches the child.
  enum class ChildGroup
  {
    shared, // yes: a beamslider of its own, which stops as this one does
    own     // no: a chart, which this run lets finish (about a second) and
            // then stops itself; Python would print a KeyboardInterrupt
            // traceback. It also starts with SIGINT blocked, for a Ctrl-C
            // that comes before it has left this process's group.
  };

  // Runs argv[0] (an absolute path, or a name looked up in PATH) with the
  // arguments argv[1...], waits for it, and says how it ended.
  ChildResult run_child(const std::vector<std::string> &argv,
                        ChildEnvironment environment = ChildEnvironment::inherited,
                        ChildGroup group             = ChildGroup::shared);

  // A child started before its input exists, so that its own start-up (for
  // the charts: Python importing matplotlib, ~0.35 s) overlaps the work
  // that produces the input. It waits on its standard input; finish() sends
  // it the rest of its arguments (NUL-separated, so that any character in a
  // path or a title is safe), closes the pipe and waits for it. Destroyed
  // without finish(), it gets an empty input and is expected to exit at
  // once without doing anything. The child runs in its own process group,
  // so that a Ctrl-C meant for the run does not kill it midway; the run
  // decides whether it draws.
  class EarlyChild
  {
  public:
    explicit EarlyChild(const std::vector<std::string> &argv);
    ~EarlyChild();
    EarlyChild(const EarlyChild &)            = delete;
    EarlyChild &operator=(const EarlyChild &) = delete;

    // Sends `arguments`, closes the input, waits. Call at most once.
    ChildResult finish(const std::vector<std::string> &arguments);

  private:
    ChildResult wait();
    std::string program_;
    int input_ = -1; // write end of the child's standard input
    int pid_   = -1;
    ChildResult start_; // started / why not
  };
} // namespace beamslider
