// Checkpoint and resume (`simulate --checkpoint-every S`, `simulate --resume
// DIR`): a resumed run writes the same bytes as one that never stopped, for
// the ROM and for the FE model (whose modified Newton iteration reuses a
// factorisation, so the checkpoint must carry where it was made), also after
// a kill -9 in the middle of a piece; a checkpoint of another scene, another
// version or with a flipped byte is refused. A resume adds its record to
// the folder's run.txt.
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace beamslider::testing;

namespace
{
  const std::string scene = std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/mueller2023.prm";

  std::string first_line(const std::string &text) { return text.substr(0, text.find('\n')); }

  void expect_same_bytes(const fs::path &a, const fs::path &b)
  {
    const std::string x = read_file(a), y = read_file(b);
    ASSERT_FALSE(x.empty()) << a;
    EXPECT_EQ(x.size(), y.size()) << a << " vs " << b;
    EXPECT_TRUE(x == y) << a << " and " << b << " differ";
  }

  // Straight to 2 s against 1 s with a checkpoint, then --resume to 2 s.
  void check_resume_is_bit_identical(const std::string &model)
  {
    const fs::path dir = fresh_folder("resume_" + model);
    CliRun run = run_beamslider({"simulate", scene, "--model", model, "--end-time", "2", "--output",
                                 (dir / "straight").string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    run = run_beamslider({"simulate", scene, "--model", model, "--end-time", "1", "--checkpoint-every", "1",
                          "--output", (dir / "pieces").string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    ASSERT_TRUE(fs::exists(dir / "pieces" / "checkpoint.bin"));
    const std::string first_record = read_file(dir / "pieces" / "run.txt");
    run = run_beamslider({"simulate", "--resume", (dir / "pieces").string(), "--end-time", "2"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    expect_same_bytes(dir / "straight" / "trace.csv", dir / "pieces" / "trace.csv");
    expect_same_bytes(dir / "straight" / "periods.csv", dir / "pieces" / "periods.csv");
    // run.txt keeps the history: the first run's record, then the resume's.
    const std::string records = read_file(dir / "pieces" / "run.txt");
    ASSERT_EQ(records.compare(0, first_record.size(), first_record), 0) << records;
    const std::string added = records.substr(first_record.size());
    EXPECT_NE(added.find("command:"), std::string::npos) << added;
    EXPECT_NE(added.find("--resume"), std::string::npos) << added;
    EXPECT_EQ(first_record.find("--resume"), std::string::npos) << first_record;
    fs::remove_all(dir);
  }
} // namespace

TEST(Resume, ReducedModelRunIsBitIdenticalToAnUninterruptedOne) { check_resume_is_bit_identical("rom"); }

TEST(Resume, FiniteElementRunIsBitIdenticalToAnUninterruptedOne) { check_resume_is_bit_identical("fe"); }

// kill -9 leaves rows after the last checkpoint, possibly half a row; the
// resumed run cuts the files back to the checkpoint and writes them again.
TEST(Resume, AfterKillNineNothingIsLostAndNothingIsWrittenTwice)
{
  const fs::path dir = fresh_folder("resume_kill");
  CliRun run = run_beamslider({"simulate", scene, "--end-time", "60", "--output", (dir / "straight").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // kill -9 once the first checkpoint is on disk: 59 simulated seconds are
  // still to go then, so the kill lands mid-run on any machine.
  run = run_beamslider({"simulate", scene, "--end-time", "60", "--checkpoint-every", "1", "--output",
                        (dir / "killed").string()},
                       CliLimits().signal_when_file_exists(SIGKILL, (dir / "killed" / "checkpoint.bin").string()));
  ASSERT_EQ(run.signal, SIGKILL) << "the run ended before it was killed: " << run.out;
  ASSERT_TRUE(fs::exists(dir / "killed" / "checkpoint.bin")) << run.out;
  run = run_beamslider({"simulate", "--resume", (dir / "killed").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  expect_same_bytes(dir / "straight" / "trace.csv", dir / "killed" / "trace.csv");
  expect_same_bytes(dir / "straight" / "periods.csv", dir / "killed" / "periods.csv");
  fs::remove_all(dir);
}

TEST(Resume, CheckpointOfAnotherSceneVersionOrWithAFlippedByteIsRefused)
{
  const fs::path dir = fresh_folder("resume_refused");
  const fs::path own = dir / "own.prm";
  fs::copy_file(scene, own);
  const fs::path out = dir / "run";
  CliRun run = run_beamslider({"simulate", own.string(), "--end-time", "0.1", "--checkpoint-every", "0.1",
                               "--output", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string good = read_file(out / "checkpoint.bin");

  // The scene file changed since.
  std::ofstream(own, std::ios::app) << "# an edit\n";
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.2"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("another scene"), std::string::npos) << run.err;
  fs::copy_file(scene, own, fs::copy_options::overwrite_existing);

  // One byte of the state flipped.
  std::string bad = good;
  bad[bad.size() / 2] ^= 0x01;
  std::ofstream(out / "checkpoint.bin", std::ios::binary) << bad;
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.2"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("corrupt"), std::string::npos) << run.err;

  // Written by another version of the program.
  bad             = good;
  const auto at   = bad.find(BEAMSLIDER_VERSION_STRING);
  ASSERT_NE(at, std::string::npos);
  bad[at]         = bad[at] == '9' ? '8' : '9';
  std::ofstream(out / "checkpoint.bin", std::ios::binary) << bad;
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.2"});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("written by beamslider"), std::string::npos) << run.err;

  // The intact checkpoint still resumes.
  std::ofstream(out / "checkpoint.bin", std::ios::binary) << good;
  run = run_beamslider({"simulate", "--resume", out.string(), "--end-time", "0.2"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  fs::remove_all(dir);
}

// A checkpoint interval below the time step would checkpoint each step or
// never end: refused before the run starts (exit 2, no folder), naming the
// option, its value and the allowed range, by the model the run uses.
TEST(Resume, CheckpointIntervalBelowTheTimeStepIsRefusedBeforeWork)
{
  const fs::path dir = fresh_folder("checkpoint_below_step");
  CliRun run = run_beamslider({"simulate", scene, "--end-time", "1", "--checkpoint-every", "1e-6", "--output",
                               (dir / "rom").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(first_line(run.err).rfind("error: --checkpoint-every 1e-06 s is outside the allowed range [2e-05, inf)", 0),
            0u)
    << run.err;
  EXPECT_FALSE(fs::exists(dir / "rom" / "trace.csv"));
  // The FE's bound is its own FE time step (1e-5 s); 1.5e-5 s, above it, is
  // still below the ROM's 2e-5 s.
  run = run_beamslider({"simulate", scene, "--model", "fe", "--end-time", "1", "--checkpoint-every", "5e-6",
                        "--output", (dir / "fe").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_EQ(first_line(run.err).rfind("error: --checkpoint-every 5e-06 s is outside the allowed range [1e-05, inf)", 0),
            0u)
    << run.err;
  run = run_beamslider({"simulate", scene, "--end-time", "1", "--checkpoint-every", "1.5e-5", "--output",
                        (dir / "rom").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  fs::remove_all(dir);
}
