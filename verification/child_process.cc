// posix_spawn with an argument vector, see child_process.h.
#include "verification/child_process.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <spawn.h>
#include <sys/wait.h>

extern char **environ;

namespace beamslider
{
  ChildResult run_child(const std::vector<std::string> &argv)
  {
    ChildResult result;
    if (argv.empty())
      {
        result.error = "no program given";
        return result;
      }
    std::vector<char *> args;
    for (const auto &a : argv)
      args.push_back(const_cast<char *>(a.c_str()));
    args.push_back(nullptr);

    // The child starts with default signal dispositions: this process ignores
    // SIGXFSZ and catches SIGINT/SIGTERM (interruption.h), the child must not
    // inherit the former (handlers are reset by exec anyway).
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGXFSZ);
    sigaddset(&defaults, SIGPIPE);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);

    pid_t pid         = 0;
    const int status  = argv[0].find('/') == std::string::npos
                          ? posix_spawnp(&pid, args[0], nullptr, &attributes, args.data(), environ)
                          : posix_spawn(&pid, args[0], nullptr, &attributes, args.data(), environ);
    posix_spawnattr_destroy(&attributes);
    if (status != 0)
      {
        result.error = "cannot start '" + argv[0] + "': " + std::strerror(status);
        return result;
      }
    result.started = true;

    int wait_status = 0;
    while (waitpid(pid, &wait_status, 0) < 0)
      if (errno != EINTR)
        {
          result.error = std::string("waiting for '") + argv[0] + "' failed: " + std::strerror(errno);
          return result;
        }
    if (WIFEXITED(wait_status))
      {
        result.exit_code = WEXITSTATUS(wait_status);
        if (result.exit_code != 0)
          result.error = "'" + argv[0] + "' exited with status " + std::to_string(result.exit_code);
      }
    else if (WIFSIGNALED(wait_status))
      {
        result.signal = WTERMSIG(wait_status);
        result.error  = "'" + argv[0] + "' was ended by signal " + std::to_string(result.signal);
      }
    return result;
  }
} // namespace beamslider
