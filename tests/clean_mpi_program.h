// Starts a program for the MPI end-to-end tests (map, ensembles, the
// ladder): an argument vector (no shell), standard output to /dev/null, and
// an environment without this test process's MPI variables (its MPI is a
// singleton: a child must not take it for an mpirun launch), plus Open MPI's
// opt-in for root (CI runs as root in a container).
#pragma once

#include "runtime/child_process.h"

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <fstream>
#include <functional>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char **environ;

namespace beamslider::testing
{
  // Returns the exit status, or 128 + the signal that ended it. With
  // `kill_when`, `signal` is sent the first time it returns true (checked
  // every 20 ms while the program runs): a kill tied to what the run has
  // done, not to a clock. After a signal other than SIGKILL the program
  // has two minutes to end by itself, then it is killed.
  inline int run_clean_mpi_program(const std::vector<std::string> &args,
                                   const std::function<bool()> &kill_when = {}, const int signal = SIGKILL)
  {
    std::vector<std::string> env;
    for (char **e = environ; *e; ++e)
      if (!is_mpi_launch_variable(*e) && std::string_view(*e).rfind("OMPI_ALLOW_RUN_AS_ROOT", 0) != 0)
        env.push_back(*e);
    env.push_back("OMPI_ALLOW_RUN_AS_ROOT=1");
    env.push_back("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1");
    std::vector<char *> argv, envp;
    for (const auto &a : args)
      argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    for (const auto &v : env)
      envp.push_back(const_cast<char *>(v.c_str()));
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
      return -1;
    int status = 0;
    std::chrono::steady_clock::time_point deadline{};
    bool signalled = false;
    while (waitpid(pid, &status, WNOHANG) != pid)
      {
        if (kill_when && !signalled && kill_when())
          {
            kill(pid, signal);
            signalled = true;
            deadline  = std::chrono::steady_clock::now() + std::chrono::minutes(2);
          }
        if (signalled && (signal == SIGKILL || std::chrono::steady_clock::now() > deadline))
          {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            break;
          }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }

  // `program` on two ranks under mpirun, each rank writing its process id
  // into `pids`/<rank> (a folder that exists) before it becomes the program.
  inline std::vector<std::string> two_ranks_recording_pids(const std::string &pids,
                                                           const std::vector<std::string> &program)
  {
    std::vector<std::string> args = {"mpirun", "-np", "2", "--oversubscribe", "sh", "-c",
                                     "echo $$ > '" + pids + "'/$OMPI_COMM_WORLD_RANK; exec \"$@\"", "sh"};
    args.insert(args.end(), program.begin(), program.end());
    return args;
  }

  // A `kill_when` for run_clean_mpi_program that sends `signal` to both
  // ranks (their ids in `pids`) the first time `ready` holds, and never to
  // the launcher itself (it returns false); `sent` says whether it did.
  inline std::function<bool()> signal_ranks_when(const std::string &pids, const std::function<bool()> &ready,
                                                 const int signal, bool &sent)
  {
    return [pids, ready, signal, &sent] {
      const std::string ids[2] = {pids + "/0", pids + "/1"};
      if (sent || access(ids[0].c_str(), R_OK) != 0 || access(ids[1].c_str(), R_OK) != 0 || !ready())
        return false;
      for (const std::string &id : ids)
        {
          std::ifstream in(id);
          long pid = 0;
          if (in >> pid && pid > 0)
            ::kill(static_cast<pid_t>(pid), signal);
        }
      sent = true;
      return false;
    };
  }
} // namespace beamslider::testing
