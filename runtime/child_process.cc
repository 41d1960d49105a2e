// posix_spawn with an argument vector, see child_process.h.
#include "runtime/child_process.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

namespace beamslider
{
  namespace
  {
    // posix_spawn(p) of argv with default SIGXFSZ/SIGPIPE dispositions (this
    // process ignores both: interruption.h, and writes check their errors);
    // `input` >= 0 becomes the child's standard input; `own_group` puts the
    // child in a process group of its own. Returns 0 or an errno value.
    int spawn(const std::vector<std::string> &argv, const int input, const bool own_group, pid_t &pid,
              const ChildEnvironment environment = ChildEnvironment::inherited)
    {
      // The child's environment: this one's (without an MPI launch's
      // variables if asked), and the run's process id, so that a chart
      // knows which process it belongs to (scripts/plot_common.py dies
      // with it).
      std::vector<char *> envp;
      for (char **e = environ; *e; ++e)
        if (environment == ChildEnvironment::inherited || !is_mpi_launch_variable(*e))
          if (std::string_view(*e).rfind("BEAMSLIDER_PARENT_PID=", 0) != 0)
            envp.push_back(*e);
      std::string parent = "BEAMSLIDER_PARENT_PID=" + std::to_string(::getpid());
      envp.push_back(parent.data());
      envp.push_back(nullptr);
      char **const child_environment = envp.data();

      std::vector<char *> args;
      for (const auto &a : argv)
        args.push_back(const_cast<char *>(a.c_str()));
      args.push_back(nullptr);

      posix_spawnattr_t attributes;
      posix_spawnattr_init(&attributes);
      sigset_t defaults;
      sigemptyset(&defaults);
      sigaddset(&defaults, SIGXFSZ);
      sigaddset(&defaults, SIGPIPE);
      posix_spawnattr_setsigdefault(&attributes, &defaults);
      short flags = POSIX_SPAWN_SETSIGDEF;
      if (own_group)
        {
          flags |= POSIX_SPAWN_SETPGROUP;
          posix_spawnattr_setpgroup(&attributes, 0);
          // The child joins its own group only once it runs: a Ctrl-C sent
          // to the terminal's group just before that still reaches it (with
          // the default action, as the spawn resets handlers) and ends the
          // chart. Started with SIGINT blocked, it keeps such a signal
          // pending and never acts on it; the run itself has it too.
          sigset_t blocked;
          pthread_sigmask(SIG_BLOCK, nullptr, &blocked);
          sigaddset(&blocked, SIGINT);
          posix_spawnattr_setsigmask(&attributes, &blocked);
          flags |= POSIX_SPAWN_SETSIGMASK;
        }
      posix_spawnattr_setflags(&attributes, flags);
      posix_spawn_file_actions_t actions;
      posix_spawn_file_actions_init(&actions);
      if (input >= 0)
        posix_spawn_file_actions_adddup2(&actions, input, STDIN_FILENO);

      const int status = argv[0].find('/') == std::string::npos
                           ? posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), child_environment)
                           : posix_spawn(&pid, args[0], &actions, &attributes, args.data(), child_environment);
      posix_spawn_file_actions_destroy(&actions);
      posix_spawnattr_destroy(&attributes);
      return status;
    }

    void wait_for(const pid_t pid, const std::string &program, ChildResult &result)
    {
      int wait_status = 0;
      while (waitpid(pid, &wait_status, 0) < 0)
        if (errno != EINTR)
          {
            result.error = "waiting for '" + program + "' failed: " + std::strerror(errno);
            return;
          }
      if (WIFEXITED(wait_status))
        {
          result.exit_code = WEXITSTATUS(wait_status);
          if (result.exit_code != 0)
            result.error = "'" + program + "' exited with status " + std::to_string(result.exit_code);
        }
      else if (WIFSIGNALED(wait_status))
        {
          result.signal = WTERMSIG(wait_status);
          result.error  = "'" + program + "' was ended by signal " + std::to_string(result.signal);
        }
    }
  } // namespace

  bool is_mpi_launch_variable(const std::string_view entry)
  {
    if (entry.rfind("OMPI_ALLOW_RUN_AS_ROOT", 0) == 0) // the user's opt-in, not the launch's
      return false;
    return entry.rfind("OMPI_", 0) == 0 || entry.rfind("PMIX_", 0) == 0 || entry.rfind("PMI_", 0) == 0;
  }

  ChildResult run_child(const std::vector<std::string> &argv, const ChildEnvironment environment,
                        const ChildGroup group)
  {
    ChildResult result;
    if (argv.empty())
      {
        result.error = "no program given";
        return result;
      }
    pid_t pid        = 0;
    const int status = spawn(argv, -1, group == ChildGroup::own, pid, environment);
    if (status != 0)
      {
        result.error = "cannot start '" + argv[0] + "': " + std::strerror(status);
        return result;
      }
    result.started = true;
    wait_for(pid, argv[0], result);
    return result;
  }

  EarlyChild::EarlyChild(const std::vector<std::string> &argv)
  {
    if (argv.empty())
      {
        start_.error = "no program given";
        return;
      }
    program_ = argv[0];
    // Both ends close on exec: the child gets the read end as its standard
    // input through dup2 (which clears the flag on fd 0), and no other child
    // started meanwhile holds the write end open.
    int ends[2];
    if (pipe2(ends, O_CLOEXEC) != 0)
      {
        start_.error = std::string("cannot create a pipe for '") + program_ + "': " + std::strerror(errno);
        return;
      }
    pid_t pid        = 0;
    const int status = spawn(argv, ends[0], true, pid);
    close(ends[0]);
    if (status != 0)
      {
        close(ends[1]);
        start_.error = "cannot start '" + program_ + "': " + std::strerror(status);
        return;
      }
    start_.started = true;
    pid_           = pid;
    input_         = ends[1];
  }

  ChildResult EarlyChild::wait()
  {
    ChildResult result = start_;
    if (input_ >= 0)
      {
        close(input_);
        input_ = -1;
      }
    if (pid_ > 0)
      {
        wait_for(pid_, program_, result);
        pid_ = -1;
      }
    return result;
  }

  ChildResult EarlyChild::finish(const std::vector<std::string> &arguments)
  {
    if (!start_.started || input_ < 0)
      return wait();
    std::string message;
    for (const auto &a : arguments)
      message.append(a).push_back('\0');
    // A child that died early (say, no matplotlib) makes the write fail with
    // EPIPE (SIGPIPE is ignored); wait() then reports how it ended.
    for (std::size_t done = 0; done < message.size();)
      {
        const ssize_t n = write(input_, message.data() + done, message.size() - done);
        if (n < 0 && errno == EINTR)
          continue;
        if (n <= 0)
          break;
        done += n;
      }
    return wait();
  }

  EarlyChild::~EarlyChild() { wait(); }
} // namespace beamslider
