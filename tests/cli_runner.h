// Runs the built `beamslider` executable as a user would, for end-to-end
// tests: its own process (fork + exec with an argument vector), stdout and
// stderr captured to files, an optional file-size limit, an optional signal
// sent once a file appears or the child has used so much CPU time, an
// optional launcher (mpirun), and a limit on the CPU time the child may use
// after which it is stopped (so a test that would hang fails instead).
// The limit is on CPU time, not on the wall clock: a loaded machine stretches
// a run's wall time (in one of five whole-suite runs beside two compiler
// processes, 2026-11-28, a 3 s run took over 120 s) but not the CPU time it needs, so
// the check cannot fail by chance. A child that blocks without computing is
// stopped by a wall-clock backstop of 20 times the limit.
#pragma once

#include "tests/fresh_folder.h"
#include "tests/read_text_file.h"
#include "runtime/child_process.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <fcntl.h>
#include <vector>

extern char **environ;

namespace beamslider::testing
{
  struct CliRun
  {
    int exit_code  = -1; // when it exited
    int signal     = 0;  // when a signal ended it
    bool timed_out = false;
    std::string out, err;
    // CPU seconds of the child with the processes it waited for (charts):
    // in all (its rusage), when the signal was sent (-1: not sent), and of
    // its own threads when last seen running (polled every 20 ms).
    double cpu_seconds       = 0;
    double cpu_at_signal     = -1;
    double own_cpu_at_signal = -1; // of its own threads alone
    double own_cpu_last_seen = 0;
    double own_cpu_at_watched_file = -1; // when CliLimits::watched_file first appeared (-1: never)
    // How long the child computed after the signal: the test of a prompt
    // stop, in CPU time because a loaded machine stretches the wall time.
    double cpu_after_signal() const { return cpu_seconds - cpu_at_signal; }
    // ... of which its own threads (not the charts it draws of what it
    // kept), up to when it was last seen running.
    double own_cpu_after_signal() const { return own_cpu_last_seen - own_cpu_at_signal; }
  };

  struct CliLimits
  {
    double timeout_seconds      = 120; // CPU seconds of the child (RLIMIT_CPU); 20× that of wall time
    long file_size_limit        = -1;  // bytes (RLIMIT_FSIZE), -1 = none
    // A signal sent once `signal_after_file` exists: tied to what the run
    // has done (its first checkpoint), it arrives at the same point of the
    // run however fast or loaded the machine is, where a delay would not.
    int send_signal = 0;
    std::string signal_after_file;
    // ... and once the child's own threads have used this much CPU time
    // (both conditions when both are given): a moment in the run's own
    // progress, whatever the load, e.g. a random fraction of a whole run's.
    double signal_after_cpu_seconds = -1;
    // The signal to the child's whole process group, as a terminal's Ctrl-C
    // reaches the run and the chart processes it started.
    bool signal_process_group = false;
    // A file whose first appearance is noted with the child's own CPU time
    // then (CliRun::own_cpu_at_watched_file), e.g. where a run's work ends.
    std::string watched_file;
    std::string working_directory; // "" = the test's
    // A launcher before the program, e.g. {"mpirun", "-np", "2",
    // "--oversubscribe"}: started with an environment without this test
    // process's MPI variables (its MPI is a singleton, clean_mpi_program.h)
    // and with Open MPI's opt-in for root. The limits hold for every rank.
    std::vector<std::string> launcher;

    // Named settings for a call site, e.g. CliLimits().timeout(60)
    // (designated initializers would need C++20).
    CliLimits &timeout(const double seconds) { timeout_seconds = seconds; return *this; }
    CliLimits &file_size(const long bytes) { file_size_limit = bytes; return *this; }
    // The signal once `path` exists (checked every 20 ms while the run goes on).
    CliLimits &signal_when_file_exists(const int sig, const std::string &path)
    {
      send_signal       = sig;
      signal_after_file = path;
      return *this;
    }
    // The signal once the child's own CPU time reaches `seconds`.
    CliLimits &signal_after_cpu(const int sig, const double seconds)
    {
      send_signal              = sig;
      signal_after_cpu_seconds = seconds;
      return *this;
    }
    CliLimits &to_process_group() { signal_process_group = true; return *this; }
    CliLimits &watch_file(const std::string &path) { watched_file = path; return *this; }
    CliLimits &in_directory(const std::string &dir) { working_directory = dir; return *this; }
    CliLimits &launched_by(const std::vector<std::string> &command) { launcher = command; return *this; }
  };

  // CPU seconds of a running process from /proc/<pid>/stat: its own threads
  // (utime + stime), and with `waited_children` those of the children it has
  // waited for too (cutime + cstime), as wait4's rusage counts them. -1 when
  // it cannot be read (the process is gone).
  inline double process_cpu_seconds(const pid_t pid, const bool waited_children)
  {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string stat;
    if (!std::getline(in, stat))
      return -1;
    // The command name may hold spaces and parentheses: fields after the last ')'.
    std::istringstream fields(stat.substr(stat.rfind(')') + 2));
    std::string field;
    std::vector<std::string> f;
    while (fields >> field)
      f.push_back(field);
    if (f.size() < 15)
      return -1;
    // f[0] is field 3 (state): utime, stime, cutime, cstime are fields 14-17.
    double ticks = std::stod(f[11]) + std::stod(f[12]);
    if (waited_children)
      ticks += std::stod(f[13]) + std::stod(f[14]);
    return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
  }

  // A text's lines, without their line breaks.
  inline std::vector<std::string> split_lines(const std::string &text)
  {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      lines.push_back(line);
    return lines;
  }

  // A CSV file as rows of text cells, the header row first.
  inline std::vector<std::vector<std::string>> read_csv_cells(const std::filesystem::path &path)
  {
    std::ifstream in(path);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(in, line);)
      {
        std::vector<std::string> cells;
        std::stringstream s(line);
        for (std::string c; std::getline(s, c, ',');)
          cells.push_back(c);
        rows.push_back(cells);
      }
    return rows;
  }

  inline CliRun run_beamslider(const std::vector<std::string> &args, const CliLimits &limits = {})
  {
    // One scratch folder per call, so that several runs may go at once
    // (from threads of one test).
    static std::atomic<unsigned int> n_runs{0};
    const auto scratch  = fresh_folder("cli_io_" + std::to_string(n_runs++));
    const auto out_file = scratch / "stdout", err_file = scratch / "stderr";
    std::vector<std::string> argv = limits.launcher;
    argv.push_back(BEAMSLIDER_EXECUTABLE);
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char *> c_argv;
    for (auto &a : argv)
      c_argv.push_back(a.data());
    c_argv.push_back(nullptr);
    std::vector<std::string> env;
    for (char **e = environ; *e; ++e)
      if (limits.launcher.empty() ||
          (!is_mpi_launch_variable(*e) && std::string_view(*e).rfind("OMPI_ALLOW_RUN_AS_ROOT", 0) != 0))
        env.push_back(*e);
    if (!limits.launcher.empty())
      for (const char *v : {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"})
        env.push_back(v);
    std::vector<char *> c_env;
    for (auto &v : env)
      c_env.push_back(v.data());
    c_env.push_back(nullptr);

    // The output files exist before the child does, whatever ends it; and
    // a pipe closed on exec tells when the child runs the program, so that
    // no signal of the test reaches the forked copy of the test itself (an
    // instrumented test process may use 0.02 s of CPU between fork and exec).
    const int o = open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    const int e = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    int exec_pipe[2];
    if (o < 0 || e < 0 || pipe2(exec_pipe, O_CLOEXEC) != 0)
      {
        ADD_FAILURE() << "cannot set up the outputs of a run in " << scratch;
        return {};
      }
    const pid_t pid = fork();
    if (pid == 0)
      {
        // The child: no shell, just exec with the vector.
        setpgid(0, 0);
        dup2(o, 1);
        dup2(e, 2);
        const int null_in = open("/dev/null", O_RDONLY);
        dup2(null_in, 0);
        if (!limits.working_directory.empty() && chdir(limits.working_directory.c_str()) != 0)
          _exit(126);
        if (limits.file_size_limit >= 0)
          {
            rlimit r{static_cast<rlim_t>(limits.file_size_limit), static_cast<rlim_t>(limits.file_size_limit)};
            setrlimit(RLIMIT_FSIZE, &r);
          }
        // SIGXCPU at the limit, SIGKILL a second later if that is ignored.
        const rlim_t cpu_seconds = static_cast<rlim_t>(std::ceil(limits.timeout_seconds));
        const rlimit cpu{cpu_seconds, cpu_seconds + 1};
        setrlimit(RLIMIT_CPU, &cpu);
        execvpe(c_argv[0], c_argv.data(), c_env.data());
        const char failed = 1;
        [[maybe_unused]] const auto n = write(exec_pipe[1], &failed, 1);
        _exit(127);
      }
    close(o);
    close(e);
    close(exec_pipe[1]);
    // End of file once the child has exec'd (or one byte if it could not).
    char exec_failed = 0;
    while (read(exec_pipe[0], &exec_failed, 1) < 0 && errno == EINTR)
      ;
    close(exec_pipe[0]);

    CliRun run;
    const auto start = std::chrono::steady_clock::now();
    bool signalled   = false;
    int status       = 0;
    rusage usage{};
    while (true)
      {
        const pid_t done = wait4(pid, &status, WNOHANG, &usage);
        if (done == pid)
          {
            // Stopped by its CPU limit: SIGXCPU, or SIGKILL after it.
            const double cpu = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
                               1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
            run.cpu_seconds = cpu;
            // Written in its last moments, between two looks: when last seen.
            if (!limits.watched_file.empty() && run.own_cpu_at_watched_file < 0 &&
                std::filesystem::exists(limits.watched_file))
              run.own_cpu_at_watched_file = run.own_cpu_last_seen;
            run.timed_out = WIFSIGNALED(status) && (WTERMSIG(status) == SIGXCPU ||
                                                    (WTERMSIG(status) == SIGKILL && cpu >= limits.timeout_seconds));
            break;
          }
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double own_cpu = process_cpu_seconds(pid, false);
        run.own_cpu_last_seen = std::max(run.own_cpu_last_seen, own_cpu);
        if (!limits.watched_file.empty() && run.own_cpu_at_watched_file < 0 &&
            std::filesystem::exists(limits.watched_file))
          run.own_cpu_at_watched_file = own_cpu;
        if (limits.send_signal && !signalled &&
            (limits.signal_after_file.empty() || std::filesystem::exists(limits.signal_after_file)) &&
            own_cpu >= limits.signal_after_cpu_seconds)
          {
            // Read before the signal, so that all the child does after it counts.
            run.cpu_at_signal     = process_cpu_seconds(pid, true);
            run.own_cpu_at_signal = own_cpu;
            kill(limits.signal_process_group ? -pid : pid, limits.send_signal);
            signalled = true;
          }
        if (elapsed > 20 * limits.timeout_seconds)
          {
            kill(-pid, SIGKILL);
            waitpid(pid, &status, 0);
            run.timed_out = true;
            break;
          }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    if (!run.timed_out)
      {
        if (WIFEXITED(status))
          run.exit_code = WEXITSTATUS(status);
        else if (WIFSIGNALED(status))
          run.signal = WTERMSIG(status);
      }
    run.out = read_file(out_file);
    run.err = read_file(err_file);
    std::filesystem::remove_all(scratch);
    return run;
  }
} // namespace beamslider::testing
