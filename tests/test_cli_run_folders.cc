// A run's folder belongs to one run (issue 55, item 1), end to end as the
// command line does it:
// - a second run into a folder that a live process holds exits 1 at once,
//   naming the process, and touches nothing; the lock dies with its holder
//   (kill -9 leaves none behind);
// - --resume refuses a checkpoint of another run than the folder's, naming
//   the first parameter that differs, and a trace cut short, changed or
//   replaced by a link (exit 2), never padding it with NUL bytes;
// - a new run removes the previous run's results first, so an interrupted
//   ensemble or ladder leaves no summary of the run before it;
// - results replace a symbolic link in the folder, never write through it;
// - a map into the folder of another map is refused before it writes.
#include "io/output_file.h"
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace beamslider::testing;

namespace
{
  const std::string scene = std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/mueller2023.prm";

  std::string first_line(const std::string &text) { return text.substr(0, text.find('\n')); }

  bool has_nul(const fs::path &file)
  {
    const std::string bytes = read_file(file);
    return bytes.find('\0') != std::string::npos;
  }

  void write(const fs::path &file, const std::string &text) { std::ofstream(file, std::ios::binary) << text; }

  // Holds `dir` as a run would, from a child process that waits until it is
  // killed: the lock file flock()ed, its process id written in it.
  pid_t hold_folder_in_child(const fs::path &dir)
  {
    int ready[2];
    if (pipe(ready) != 0)
      return -1;
    const pid_t pid = fork();
    if (pid == 0)
      {
        const int fd = open((dir / beamslider::output_folder_lock_name()).c_str(), O_RDWR | O_CREAT, 0644);
        if (fd < 0 || flock(fd, LOCK_EX) != 0)
          _exit(1);
        const std::string me = std::to_string(getpid()) + "\n";
        if (ftruncate(fd, 0) != 0 || ::write(fd, me.data(), me.size()) != static_cast<ssize_t>(me.size()))
          _exit(1);
        const char byte = 1;
        if (::write(ready[1], &byte, 1) != 1)
          _exit(1);
        while (true)
          pause();
      }
    close(ready[1]);
    char byte = 0;
    const bool locked = read(ready[0], &byte, 1) == 1;
    close(ready[0]);
    if (!locked)
      {
        waitpid(pid, nullptr, 0);
        return -1;
      }
    return pid;
  }
} // namespace

// The holder is a process of the test's own (no race of two runs): while it
// holds the folder, simulate and simulate --resume exit 1 at once and write
// nothing; once it is killed with SIGKILL the folder is free.
TEST(RunFolder, ASecondRunIntoAHeldFolderExitsOneAndTouchesNothing)
{
  const fs::path dir = fresh_folder("folder_lock");
  CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.1", "--checkpoint-every", "0.1", "--output",
                               dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string trace = read_file(dir / "trace.csv"), record = read_file(dir / "run.txt");
  const auto trace_time   = fs::last_write_time(dir / "trace.csv");

  const pid_t holder = hold_folder_in_child(dir);
  ASSERT_GT(holder, 0);
  const std::string in_use =
    "error: output folder '" + dir.string() + "' is in use by process " + std::to_string(holder);
  run = run_beamslider({"simulate", scene, "--end-time", "0.2", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(first_line(run.err).rfind(in_use, 0), 0u) << run.err;
  run = run_beamslider({"simulate", "--resume", dir.string(), "--end-time", "0.2"});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_EQ(first_line(run.err).rfind(in_use, 0), 0u) << run.err;
  // Nothing touched: the first run's files as it left them.
  EXPECT_EQ(read_file(dir / "trace.csv"), trace);
  EXPECT_EQ(fs::last_write_time(dir / "trace.csv"), trace_time);
  EXPECT_EQ(read_file(dir / "run.txt"), record);

  // Its holder killed, the lock is gone with it.
  kill(holder, SIGKILL);
  waitpid(holder, nullptr, 0);
  run = run_beamslider({"simulate", "--resume", dir.string(), "--end-time", "0.2"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(has_nul(dir / "trace.csv"));
  fs::remove_all(dir);
}

// A checkpoint of a 124 Hz run in the folder of a 110 Hz run (left there,
// or copied in) is refused, naming the parameter; the folder stays the
// 110 Hz run's. A new run into a folder removes the checkpoint of the run
// before, so that this cannot happen by running twice into one folder.
TEST(RunFolder, ResumeRefusesTheCheckpointOfAnotherRun)
{
  const fs::path dir = fresh_folder("resume_identity");
  const fs::path a = dir / "a124", b = dir / "b110";
  CliRun run = run_beamslider({"simulate", scene, "--set", "Excitation/Frequency=124", "--end-time", "0.2",
                               "--checkpoint-every", "0.1", "--output", a.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The 110 Hz run into the 124 Hz run's folder: its checkpoint is gone.
  run = run_beamslider({"simulate", scene, "--set", "Excitation/Frequency=110", "--end-time", "0.1", "--output",
                        a.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(fs::exists(a / "checkpoint.bin"));
  run = run_beamslider({"simulate", "--resume", a.string(), "--end-time", "0.3"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(first_line(run.err).find("no readable checkpoint"), std::string::npos) << run.err;

  // A 124 Hz checkpoint copied into a 110 Hz run's folder.
  run = run_beamslider({"simulate", scene, "--set", "Excitation/Frequency=124", "--end-time", "0.2",
                        "--checkpoint-every", "0.1", "--output", (dir / "c124").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = run_beamslider({"simulate", scene, "--set", "Excitation/Frequency=110", "--end-time", "0.1", "--output",
                        b.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  fs::copy_file(dir / "c124" / "checkpoint.bin", b / "checkpoint.bin");
  const std::string trace = read_file(b / "trace.csv"), parameters = read_file(b / "parameters.prm");
  run = run_beamslider({"simulate", "--resume", b.string(), "--end-time", "0.3"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(first_line(run.err).find("is of another run than the folder's: 'Excitation/Frequency' is 110"),
            std::string::npos)
    << run.err;
  EXPECT_EQ(read_file(b / "trace.csv"), trace);
  EXPECT_EQ(read_file(b / "parameters.prm"), parameters);
  fs::remove_all(dir);
}

// trace.csv cut short (truncate -s), changed in place or replaced by a link
// after the checkpoint: --resume refuses it (exit 2) and leaves it as it is,
// never padded with NUL bytes; the intact trace resumes.
TEST(RunFolder, ResumeRefusesATraceCutShortChangedOrLinked)
{
  const fs::path dir = fresh_folder("resume_trace");
  const fs::path out = dir / "run";
  CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.4", "--checkpoint-every", "0.2", "--output",
                               out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string good = read_file(out / "trace.csv");
  ASSERT_GT(good.size(), 1000u);

  fs::resize_file(out / "trace.csv", good.size() / 2);
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.6"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(first_line(run.err).find("cut short"), std::string::npos) << run.err;
  EXPECT_EQ(fs::file_size(out / "trace.csv"), good.size() / 2);
  EXPECT_FALSE(has_nul(out / "trace.csv"));

  std::string changed = good;
  changed[good.size() / 2] = changed[good.size() / 2] == '1' ? '2' : '1';
  write(out / "trace.csv", changed);
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.6"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(first_line(run.err).find("are not those the checkpoint's run wrote"), std::string::npos) << run.err;
  EXPECT_EQ(read_file(out / "trace.csv"), changed);

  // A link to a copy of the right bytes is still not the file: refused, and
  // its target is not written.
  write(dir / "elsewhere.csv", good);
  fs::remove(out / "trace.csv");
  fs::create_symlink(dir / "elsewhere.csv", out / "trace.csv");
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.6"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(first_line(run.err).find("not a regular file"), std::string::npos) << run.err;
  EXPECT_EQ(read_file(dir / "elsewhere.csv"), good);

  fs::remove(out / "trace.csv");
  write(out / "trace.csv", good);
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.6"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::string resumed = read_file(out / "trace.csv");
  EXPECT_EQ(resumed.compare(0, good.size(), good), 0);
  EXPECT_GT(resumed.size(), good.size());
  EXPECT_FALSE(has_nul(out / "trace.csv"));
  fs::remove_all(dir);
}

// An ensemble of 2 members over 0.5 s, then one of 8 over 60 s into the same
// folder, stopped (SIGINT once it has moved the first one's member_runs.csv
// aside, i.e. once it has started): no summary, members or statistics of the
// first run are left beside the second one's command.prm.
TEST(RunFolder, AnInterruptedEnsembleLeavesNoResultsOfTheRunBefore)
{
  const fs::path dir = fresh_folder("stale_ensemble");
  CliRun run = run_beamslider({"ensemble", scene, "--members", "2", "--end-time", "0.5", "--quiet", "--output",
                               dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char *file : {"summary.md", "members.csv", "statistics.csv", "member_periods.csv"})
    ASSERT_TRUE(fs::exists(dir / file)) << file;
  run = run_beamslider({"ensemble", scene, "--members", "8", "--end-time", "60", "--quiet", "--output", dir.string()},
                       CliLimits().signal_when_file_exists(SIGINT, (dir / "member_runs.other.csv").string()));
  ASSERT_EQ(run.exit_code, 130) << run.err;
  for (const char *file : {"summary.md", "members.csv", "statistics.csv", "member_periods.csv", "ensemble.png"})
    EXPECT_FALSE(fs::exists(dir / file)) << file << " of the earlier run is still there";
  const std::string options = read_file(dir / "command.prm");
  const std::size_t members = options.find("set members ");
  ASSERT_NE(members, std::string::npos) << options;
  EXPECT_EQ(first_line(options.substr(members)).substr(first_line(options.substr(members)).find('=')), "= 8") << options;
  // The earlier members are moved aside, not lost.
  EXPECT_TRUE(fs::exists(dir / "member_runs.other.csv"));
  fs::remove_all(dir);
}

// The same for the error ladder: ladder.csv, ladder_members.csv,
// ladder_steps.csv and summary.md of a finished ladder are gone once
// another ladder has started in the folder and was stopped.
TEST(RunFolder, AnInterruptedLadderLeavesNoResultsOfTheRunBefore)
{
  const fs::path dir = fresh_folder("stale_ladder");
  CliRun run = run_beamslider({"ladder", scene, "--rung", "ROM N=10", "--members", "2", "--end-time", "0.2", "--quiet",
                               "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char *file : {"summary.md", "ladder.csv", "ladder_members.csv", "ladder_steps.csv"})
    ASSERT_TRUE(fs::exists(dir / file)) << file;
  run = run_beamslider({"ladder", scene, "--rung", "ROM N=10", "--members", "2", "--end-time", "60", "--quiet",
                        "--output", dir.string()},
                       CliLimits().signal_when_file_exists(SIGINT, (dir / "member_runs.other.csv").string()));
  ASSERT_EQ(run.exit_code, 130) << run.err;
  for (const char *file : {"summary.md", "ladder.csv", "ladder_members.csv", "ladder_steps.csv", "ladder.png"})
    EXPECT_FALSE(fs::exists(dir / file)) << file << " of the earlier run is still there";
  fs::remove_all(dir);
}

// Links in the folder where simulate and modes write their results (the
// trace, which grows during the run, among them): each is replaced by the
// run's own file; what the links pointed to is not written.
TEST(RunFolder, ResultsReplaceALinkAndNeverWriteThroughIt)
{
  const fs::path dir = fresh_folder("links");
  const fs::path out = dir / "out", target = dir / "precious.txt";
  fs::create_directories(out);
  write(target, "not a result\n");
  const std::vector<std::string> simulate_files = {"trace.csv", "periods.csv", "summary.md", "trace.png",
                                                   "parameters.prm", "command.prm", "run.txt"};
  for (const std::string &name : simulate_files)
    fs::create_symlink(target, out / name);
  CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.05", "--output", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_file(target), "not a result\n");
  for (const std::string &name : simulate_files)
    {
      EXPECT_FALSE(fs::is_symlink(out / name)) << name;
      EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
    }

  const fs::path modes = dir / "modes";
  fs::create_directories(modes);
  const std::vector<std::string> modes_files = {"modes.csv", "modes.vtu", "parameters.prm"};
  for (const std::string &name : modes_files)
    fs::create_symlink(target, modes / name);
  run = run_beamslider({"modes", scene, "--output", modes.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_file(target), "not a result\n");
  for (const std::string &name : modes_files)
    EXPECT_FALSE(fs::is_symlink(modes / name)) << name;
  // No temporary left beside the results.
  for (const auto &entry : fs::directory_iterator(modes))
    EXPECT_EQ(entry.path().extension() == ".tmp", false) << entry.path();
  fs::remove_all(dir);
}

// A map into the folder of a map of other settings is refused (exit 2)
// before it writes anything: the folder's command.prm and parameters.prm
// still describe the map that is there. The same map again continues it.
TEST(RunFolder, AMapOfOtherSettingsLeavesTheFolderOfAMapAsItIs)
{
  const fs::path dir = fresh_folder("map_settings");
  CliRun run = run_beamslider({"map", scene, "--frequency", "124", "--acceleration", "14", "--end-time", "0.3",
                               "--quiet", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string options = read_file(dir / "command.prm"), parameters = read_file(dir / "parameters.prm"),
                    rows    = read_file(dir / "map.csv");
  run = run_beamslider({"map", scene, "--frequency", "110", "--acceleration", "14", "--end-time", "0.3", "--quiet",
                        "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(first_line(run.err).find("holds a map with other settings"), std::string::npos) << run.err;
  EXPECT_EQ(read_file(dir / "command.prm"), options);
  EXPECT_EQ(read_file(dir / "parameters.prm"), parameters);
  EXPECT_EQ(read_file(dir / "map.csv"), rows);
  run = run_beamslider({"map", scene, "--frequency", "124", "--acceleration", "14", "--end-time", "0.3", "--quiet",
                        "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_file(dir / "map.csv"), rows);
  fs::remove_all(dir);
}
