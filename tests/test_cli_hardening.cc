// The built program under hostile-but-fair input (issue: hardening). Each
// test runs `beamslider` as its own process and checks one class of defect:
// no shell ever sees user text, no result is lost silently, bad input is
// exit 2 with the parameter named, a diverging run is exit 1 with its own
// status, and an interrupted run leaves complete rows and a summary.
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <regex>

namespace fs = std::filesystem;
using namespace beamslider::testing;

namespace
{
  const std::string scene = std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/mueller2023.prm";

  // Every line of a trace.csv is a complete row of 7 finite numbers (after
  // the header), and the file ends with a newline.
  void expect_complete_finite_rows(const fs::path &trace)
  {
    const std::string text = read_file(trace);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.back(), '\n') << "the last row is cut";
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "t_s,slider_x_over_L,slider_z_m,slider_beta_rad,w_center_m,w_probe_m,amplitude_over_h");
    unsigned int rows = 0;
    while (std::getline(in, line))
      {
        ++rows;
        EXPECT_EQ(std::count(line.begin(), line.end(), ','), 6) << "row " << rows << ": " << line;
        EXPECT_EQ(line.find("nan"), std::string::npos) << line;
        EXPECT_EQ(line.find("inf"), std::string::npos) << line;
      }
    EXPECT_GT(rows, 0u);
  }

  unsigned int count_lines(const std::string &text) { return std::count(text.begin(), text.end(), '\n'); }
} // namespace

// --- 1. No shell ------------------------------------------------------------

TEST(NoShell, OutputPathWithQuotesIsAPathNotACommand)
{
  const fs::path dir    = fresh_folder("injection_output");
  const fs::path output = dir / "o';touch PWNED;'";
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.02", "--output", output.string()},
                                    CliLimits().in_directory(dir.string()));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(fs::exists(dir / "PWNED")) << "the output path reached a shell";
  EXPECT_TRUE(fs::exists(output / "trace.png")) << "the chart was drawn with the path as one argument";
  fs::remove_all(dir);
}

TEST(NoShell, SceneNameWithQuotesIsANameNotACommand)
{
  const fs::path dir = fresh_folder("injection_scene");
  const fs::path odd = dir / "x';touch PWNED;'.prm";
  fs::copy_file(scene, odd);
  const CliRun run = run_beamslider({"simulate", odd.string(), "--end-time", "0.02", "--output", (dir / "out").string()},
                                    CliLimits().in_directory(dir.string()));
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(fs::exists(dir / "PWNED")) << "the scene name reached a shell";
  fs::remove_all(dir);
}

// --- 2. No silent success ----------------------------------------------------

// A link to /dev/full where the trace goes was this test's full disk; a
// result is never written through a link now (doc/cli.md, "A run's folder
// belongs to one run"), so the link is replaced by the run's own trace. A
// write that fails is FileSizeLimitCutsTheTraceAndIsExitOne below (EFBIG
// instead of ENOSPC: the same checked stream).
TEST(NoSilentSuccess, ALinkToAFullDiskWhereTheTraceGoesIsReplaced)
{
  const fs::path dir = fresh_folder("full_disk");
  fs::create_symlink("/dev/full", dir / "trace.csv");
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.05", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_FALSE(fs::is_symlink(dir / "trace.csv"));
  EXPECT_TRUE(fs::is_regular_file(dir / "trace.csv"));
  EXPECT_GT(fs::file_size(dir / "trace.csv"), 0u);
  fs::remove_all(dir);
}

TEST(NoSilentSuccess, FolderWhereTheTraceShouldBeIsExitOne)
{
  const fs::path dir = fresh_folder("folder_trace");
  fs::create_directories(dir / "trace.csv");
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.02", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("trace.csv"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

// As root a read-only folder is writable; a path under a regular file is
// not, for anybody.
TEST(NoSilentSuccess, OutputFolderThatCannotBeCreatedIsExitOne)
{
  const fs::path dir = fresh_folder("under_file");
  std::ofstream(dir / "plain") << "x";
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.02", "--output", (dir / "plain" / "out").string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("plain/out"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

TEST(NoSilentSuccess, FileSizeLimitCutsTheTraceAndIsExitOne)
{
  const fs::path dir = fresh_folder("fsize");
  // A row every step for 4 s is ~20 MB of trace; allow 16 MB (Open MPI's
  // start-up needs a few MB of files of its own).
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "4", "--set", "Time stepping/Output rate=50000",
                                     "--output", dir.string()},
                                    CliLimits().file_size(16l << 20));
  EXPECT_EQ(run.signal, 0) << "killed by signal " << run.signal << " (SIGXFSZ must be ignored)";
  EXPECT_EQ(run.exit_code, 1) << run.out << run.err;
  EXPECT_NE(run.err.find("File too large"), std::string::npos) << run.err;
  EXPECT_EQ(run.out.find("Status: completed"), std::string::npos) << run.out;
  fs::remove_all(dir);
}

// --- 3. Step count -----------------------------------------------------------

TEST(StepCount, EndTimeWhoseStepCountDoesNotFitIsRefused)
{
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "1e300", "--output", fresh_folder("steps").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("End time"), std::string::npos) << run.err;
  EXPECT_EQ(run.out.find("-9223372036854775808"), std::string::npos) << run.out;
}

TEST(StepCount, EndTimeInTheSceneFileIsCheckedToo)
{
  const fs::path dir = fresh_folder("steps_scene");
  std::ofstream(dir / "long.prm") << "subsection Time stepping\n  set End time = 1e20\nend\n";
  const CliRun run = run_beamslider({"simulate", (dir / "long.prm").string(), "--output", (dir / "o").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("'Time stepping/End time' = 1e+20"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

TEST(StepCount, TraceLargerThanTheStatedLimitNeedsAnExplicitOption)
{
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "20", "--set", "Time stepping/Output rate=1e6",
                                     "--output", fresh_folder("rows").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("--allow-large-output"), std::string::npos) << run.err;
}

// An ensemble's member_periods.csv has a row per member and excitation
// period: 8 members over 1e6 s would be ~1e9 rows. Refused before any
// member runs, naming --end-time and the longest it allows (1e7 rows).
TEST(StepCount, AnEnsembleLongerThanItsRowLimitIsRefused)
{
  const fs::path dir = fresh_folder("ensemble_rows");
  CliRun run = run_beamslider({"ensemble", scene, "--end-time", "1e6", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("--end-time 1000000"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("at most 10080.6"), std::string::npos) << run.err; // 1e7 / (8 × 124 Hz)
  EXPECT_FALSE(fs::exists(dir / "member_periods.csv"));
  fs::remove_all(dir);
}

// --- 4. Divergence is a failure, not physics ----------------------------------

TEST(Divergence, AbsurdGravityIsAnUnphysicalStateWithExitOne)
{
  const fs::path dir = fresh_folder("gravity");
  const CliRun run   = run_beamslider({"simulate", scene, "--end-time", "0.05", "--set", "Contact/Gravity=1e30",
                                       "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("unphysical_state"), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("slider_at_support"), std::string::npos) << run.err;
  EXPECT_NE(read_file(dir / "summary.md").find("Status: unphysical_state"), std::string::npos);
  expect_complete_finite_rows(dir / "trace.csv");
  fs::remove_all(dir);
}

TEST(Divergence, AbsurdExcitationIsAnUnphysicalStateWithExitOne)
{
  const fs::path dir = fresh_folder("excitation");
  const CliRun run   = run_beamslider({"simulate", scene, "--end-time", "0.05", "--set",
                                       "Excitation/Acceleration amplitude=1e30", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("unphysical_state"), std::string::npos) << run.err;
  expect_complete_finite_rows(dir / "trace.csv");
  fs::remove_all(dir);
}

TEST(Divergence, NegligibleRotaryInertiaIsRefusedBeforeTheRun)
{
  const CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.05", "--set", "Slider/Rotary inertia=1e-15",
                                     "--output", fresh_folder("inertia").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("'Slider/Rotary inertia' = 1e-15"), std::string::npos) << run.err;
}

// The test runner's own guard against a hanging program (tests/cli_runner.h):
// a run that needs more CPU time than its limit is stopped and reported as
// timed out, however loaded the machine is. A 600 s simulation needs about
// 30 s of CPU time; its limit here is 1 s.
TEST(CliRunner, ARunOverItsCpuLimitIsStoppedAndReportedAsTimedOut)
{
  const fs::path dir = fresh_folder("cpu_limit");
  const CliRun run   = run_beamslider({"simulate", scene, "--end-time", "600", "--output", (dir / "o").string()},
                                      CliLimits().timeout(1));
  EXPECT_TRUE(run.timed_out) << "exit code " << run.exit_code << ", signal " << run.signal << "\n" << run.err;
  EXPECT_EQ(run.signal, 0);
  fs::remove_all(dir);
}

// --- 5. The scene reader -----------------------------------------------------

TEST(SceneReader, FolderEmptyFileAndFifoAreRefused)
{
  const fs::path dir = fresh_folder("reader");
  fs::create_directories(dir / "folder.prm");
  std::ofstream(dir / "empty.prm").close();
  ASSERT_EQ(mkfifo((dir / "pipe.prm").c_str(), 0644), 0);
  for (const auto &[file, words] : std::vector<std::pair<std::string, std::string>>{
         {"folder.prm", "is a folder"}, {"empty.prm", "is empty"}, {"pipe.prm", "not a regular file"}})
    {
      const CliRun run = run_beamslider({"simulate", (dir / file).string(), "--output", (dir / "o").string()},
                                        CliLimits().timeout(20));
      EXPECT_FALSE(run.timed_out) << file << " hangs";
      EXPECT_EQ(run.exit_code, 2) << file << ": " << run.err;
      EXPECT_NE(run.err.find(words), std::string::npos) << file << ": " << run.err;
    }
  fs::remove_all(dir);
}

TEST(SceneReader, ParameterSetTwiceIsRefusedWithBothLines)
{
  const fs::path dir = fresh_folder("duplicate");
  std::ofstream(dir / "twice.prm") << "subsection Slider\n  set Mass = 0.05\n  set Mass = 0.06\nend\n";
  CliRun run = run_beamslider({"simulate", (dir / "twice.prm").string(), "--output", (dir / "o").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("line 3: 'Slider/Mass' is set a second time (first on line 2)"), std::string::npos) << run.err;

  run = run_beamslider({"simulate", scene, "--set", "Slider/Mass=0.05", "--set", "Slider/Mass=0.06", "--output",
                        (dir / "o").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("already set"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

TEST(SceneReader, ChangingWhatACaseFixesIsReportedNotJudgedAsPublished)
{
  const fs::path dir = fresh_folder("modified_case");
  const CliRun run   = run_beamslider({"simulate", scene, "--case", "frictionless", "--set",
                                       "Contact/Friction coefficient=0.5", "--end-time", "0.05", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::string summary = read_file(dir / "summary.md");
  EXPECT_NE(summary.find("frictionless, modified: Contact/Friction coefficient=0.5 (the case sets 0)"),
            std::string::npos)
    << summary;
  EXPECT_EQ(summary.find("Against the published behaviour"), std::string::npos) << summary;
  fs::remove_all(dir);
}

// --- 6. Exit codes and messages ----------------------------------------------

TEST(ExitCodes, CommandLineErrorsAreExitTwoOnOneLine)
{
  const std::vector<std::vector<std::string>> bad = {
    {"simulate", scene, "--no-such-option"},
    {"simulate", scene, "--tolerance", "nan", "--model", "auto"},
    {"animate", scene, "--frame-rate", "nan"},
    {"sweep", scene, "--step", "inf"},
    {"backbone", scene, "--max-amplitude", "1e-9"},
    {"modes", scene, "--modes", "0"},
  };
  for (const auto &args : bad)
    {
      const CliRun run = run_beamslider(args);
      EXPECT_EQ(run.exit_code, 2) << args[2] << ": " << run.err;
      EXPECT_LE(count_lines(run.err), 2u) << run.err;
      EXPECT_EQ(run.err.find("179769313486231570"), std::string::npos) << "DBL_MAX printed: " << run.err;
    }
}

TEST(ExitCodes, MistypedCommandNamesTheClosestOne)
{
  const CliRun run = run_beamslider({"simulat", scene});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("did you mean 'simulate'"), std::string::npos) << run.err;
}

TEST(ExitCodes, ParametersOutsideTheirRangeAreExitTwoNamingTheParameter)
{
  const std::vector<std::pair<std::string, std::string>> bad = {
    {"Slider/Mass=0", "'Slider/Mass' = 0"},
    {"Slider/Rotary inertia=0", "'Slider/Rotary inertia' = 0"},
    {"Discretisation/Number of elements=2", "'Discretisation/Number of elements' = 2"},
    {"Time stepping/Time step=1e-4", "'Time stepping/Time step' = 0.0001"},   // above 2/omega_5 of the ROM
    {"Time stepping/Time step=1e-3", "'Time stepping/Time step' = 0.001"},    // above a twentieth of the period
    {"Beam/Young's modulus=1e-3", "Young's modulus"},
    {"Beam/Young's modulus=1e30", "Young's modulus"},
  };
  for (const auto &[assignment, named] : bad)
    {
      const CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.01", "--set", assignment, "--output",
                                         fresh_folder("range").string()});
      EXPECT_EQ(run.exit_code, 2) << assignment << ": " << run.err;
      EXPECT_NE(run.err.find(named), std::string::npos) << assignment << ": " << run.err;
      EXPECT_LE(count_lines(run.err), 3u) << "not one readable message: " << run.err;
      EXPECT_EQ(run.err.find("Stacktrace"), std::string::npos) << run.err;
      EXPECT_EQ(run.err.find("PETSC ERROR"), std::string::npos) << run.err;
    }
}

// --- 7. Interruption ---------------------------------------------------------

TEST(Interruption, CtrlCFinishesTheStepWritesCompleteRowsAndTheSummary)
{
  for (const auto &[signal, code] : std::vector<std::pair<int, int>>{{SIGINT, 130}, {SIGTERM, 143}})
    {
      const fs::path dir = fresh_folder("interrupt");
      // The signal once the run has written its first checkpoint (after 1 s
      // of simulated time, with rows in trace.csv): 599 s are still to go
      // then, so it arrives mid-run on any machine and under any load.
      const CliRun run =
        run_beamslider({"simulate", scene, "--end-time", "600", "--checkpoint-every", "1", "--output", dir.string()},
                       CliLimits().timeout(120).signal_when_file_exists(signal, (dir / "checkpoint.bin").string()));
      EXPECT_EQ(run.exit_code, code) << run.err;
      const std::string summary = read_file(dir / "summary.md");
      EXPECT_NE(summary.find("Status: interrupted"), std::string::npos) << summary;
      expect_complete_finite_rows(dir / "trace.csv");
      fs::remove_all(dir);
    }
}
