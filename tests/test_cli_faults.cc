// Faults end to end (issue 55, "nothing lost, nothing mixed, nothing
// hangs"): under mpirun an error is said once, by rank 0, and every rank
// exits with its status; a full disk (a file-size limit: the process ignores
// SIGXFSZ, so a write fails with EFBIG) ends a command with exit 1 and one
// line that names the file and the system's reason, and leaves no part of
// the file that failed, also when the solid's .vtu pieces of two ranks fail;
// a checkpoint whose recorded sizes exceed what it holds is refused (exit 2)
// before anything is sized by them; and a statics load step that cannot
// converge leaves the converged rows and no statics.vtu / statics.pvtu, on
// the beam and on the solid alike, and says so.
#include "io/checkpoint.h"
#include "io/output_file.h"
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <iostream>
#include <map>
#include <thread>
#include <cstring>
#include <fcntl.h>
#include <functional>
#include <sys/stat.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/file.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace beamslider;
using namespace beamslider::testing;

namespace
{
  // Two ranks, each of which must end by itself: mpirun does not stop the
  // others when one exits with an error (as it would by default, which would
  // hide a rank left waiting), and each rank's exit status is recorded in
  // `statuses`/rank_<r>. `before` goes before the program (e.g. prlimit).
  std::vector<std::string> two_ranks(const fs::path &statuses, const std::vector<std::string> &before = {})
  {
    std::vector<std::string> launcher = {
      "mpirun", "-np", "2", "--oversubscribe", "--mca", "orte_abort_on_non_zero_status", "0", "sh", "-c",
      "\"$@\"; status=$?; echo $status > '" + statuses.string() + "'/rank_$OMPI_COMM_WORLD_RANK; exit $status", "sh"};
    launcher.insert(launcher.end(), before.begin(), before.end());
    return launcher;
  }

  // Both ranks exited by themselves with `status`.
  void expect_ranks_exited_with(const fs::path &statuses, const int status)
  {
    for (const char *rank : {"rank_0", "rank_1"})
      EXPECT_EQ(read_file(statuses / rank), std::to_string(status) + "\n") << rank;
  }

  // The plane-stress strip on a coarse mesh: a solid scene that takes a
  // second, not minutes (its four modes' .vtu pieces on two ranks: 16 kB each).
  std::vector<std::string> small_solid(const std::vector<std::string> &command)
  {
    std::vector<std::string> args = command;
    for (const char *s : {"Solid/Continuum=plane stress", "Solid/Elements along length=100",
                          "Solid/Elements across width=1"})
      args.insert(args.end(), {"--set", s});
    return args;
  }

  std::size_t count(const std::string &text, const std::string &what)
  {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
      ++n;
    return n;
  }

  // The files in `dir` whose names contain `part` (hidden temporaries too).
  std::vector<std::string> files_with(const fs::path &dir, const std::string &part)
  {
    std::vector<std::string> found;
    for (const auto &entry : fs::directory_iterator(dir))
      if (entry.path().filename().string().find(part) != std::string::npos)
        found.push_back(entry.path().filename().string());
    return found;
  }

  // A run that a full disk stopped: exit 1 (unless `check_exit`, where the
  // ranks' statuses are checked instead), one line naming `file` and the
  // reason, no "Wrote" line, and nothing left of the files named `stem`
  // (result or temporary) in `dir`.
  void expect_refused_write(const CliRun &run, const fs::path &dir, const std::string &file, const std::string &stem,
                            const bool check_exit = true)
  {
    EXPECT_FALSE(run.timed_out) << "hangs";
    EXPECT_EQ(run.signal, 0) << run.err;
    if (check_exit)
      {
        EXPECT_EQ(run.exit_code, 1) << run.err;
      }
    EXPECT_EQ(count(run.err, "error: results not written: result file '"), 1u) << run.err;
    EXPECT_NE(run.err.find(file + "' could not be written: File too large"), std::string::npos) << run.err;
    EXPECT_EQ(run.out.find("Wrote"), std::string::npos) << run.out;
    EXPECT_EQ(files_with(dir, stem), std::vector<std::string>()) << "partial files left";
  }
} // namespace

// A bad --set under mpirun: every rank reads the scene and refuses it, rank
// 0 alone says so (once, not "error: error: ..."), and mpirun exits 2.
TEST(FaultsUnderMpi, AnInputErrorIsSaidOnceByRankZero)
{
  const fs::path dir = fresh_folder("faults_mpi_input");
  for (const auto &args :
       {std::vector<std::string>{"modes", "mueller2023-ideal-solid", "--set", "Solid/Poisson's ratio=0.5", "--output",
                                 (dir / "solid").string()},
        std::vector<std::string>{"modes", "mueller2023", "--set", "Beam/Length=-1", "--output",
                                 (dir / "beam").string()}})
    {
      const fs::path statuses = dir / ("statuses_" + args[1]);
      fs::create_directories(statuses);
      const CliRun run = run_beamslider(args, CliLimits().timeout(60).launched_by(two_ranks(statuses)));
      EXPECT_FALSE(run.timed_out) << args[1];
      expect_ranks_exited_with(statuses, 2);
      EXPECT_EQ(count(run.err, "error: "), 1u) << args[1] << ": " << run.err;
    }
  fs::remove_all(dir);
}

// A SIGTERM to the ranks of an mpirun job (a scheduler's, or `kill` of the
// job's processes) ends it as it ends a single process: whole rows, exit
// 143 on every rank and run.txt's `ended:` line. Before, PETSc's handler
// (installed when MPI started) turned it into an abort with exit 1, and a
// rank that exited first made mpirun kill rank 0 before it wrote run.txt.
// The launcher records each rank's pid; the signal goes once the run's
// folder holds run.txt (the run is under way).
TEST(FaultsUnderMpi, ASigtermToTheRanksEndsTheJobWith143AndItsEndedLine)
{
  const fs::path dir = fresh_folder("faults_mpi_sigterm"), statuses = dir / "statuses", out = dir / "out";
  fs::create_directories(statuses);
  std::vector<std::string> launcher = two_ranks(statuses);
  launcher.insert(launcher.end(), {"sh", "-c", "echo $$ > '" + (dir / "pid_").string() + "'$OMPI_COMM_WORLD_RANK; exec \"$@\"",
                                   "sh"});
  std::thread killer([&] {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(300);
    while (std::chrono::steady_clock::now() < end &&
           !(fs::exists(dir / "pid_0") && fs::exists(dir / "pid_1") && fs::exists(out / "run.txt")))
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::this_thread::sleep_for(std::chrono::milliseconds(500)); // both ranks past their start-up
    for (const char *rank : {"pid_0", "pid_1"})
      {
        const std::string pid = read_file(dir / rank);
        if (!pid.empty())
          ::kill(std::stoi(pid), SIGTERM);
      }
  });
  const CliRun run = run_beamslider({"ensemble", "--members", "8", "--end-time", "300", "--quiet", "--output",
                                     out.string()},
                                    CliLimits().timeout(300).launched_by(launcher));
  killer.join();
  EXPECT_FALSE(run.timed_out);
  expect_ranks_exited_with(statuses, 143);
  const std::string record = read_file(out / "run.txt");
  EXPECT_NE(record.find("interrupted (exit 143): interrupted by signal 15"), std::string::npos) << record;
  fs::remove_all(dir);
}

// A rank that dies in the middle of an mpirun job (kill -9, the OOM
// killer, a crash) with mpirun told not to end the job for it, as
// schedulers and these tests run it: the rank waiting for it sees, within
// about a second of its own wait, that its process is gone, says which rank
// died, and ends the job. Before, the survivor waited forever: rank 0 for
// the dead worker's cell, the worker for rank 0's next cell. When rank 1
// dies, rank 0 finishes its own member, records the failure in run.txt and
// keeps the finished rows.
TEST(FaultsUnderMpi, ARankThatDiesMidRunEndsTheJobWithAMessageNamingIt)
{
  for (const int victim : {1, 0})
    {
      const fs::path dir = fresh_folder("faults_mpi_dead_rank"), statuses = dir / "statuses", out = dir / "out";
      fs::create_directories(statuses);
      std::vector<std::string> launcher = two_ranks(statuses);
      launcher.insert(launcher.end(), {"sh", "-c",
                                       "echo $$ > '" + (dir / "pid_").string() + "'$OMPI_COMM_WORLD_RANK; exec \"$@\"",
                                       "sh"});
      const std::string victim_pid = "pid_" + std::to_string(victim);
      std::thread killer([&] {
        const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
        while (std::chrono::steady_clock::now() < end &&
               !(fs::exists(dir / "pid_0") && fs::exists(dir / "pid_1") && fs::exists(out / "run.txt")))
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        std::this_thread::sleep_for(std::chrono::milliseconds(1500)); // both ranks among their members
        const std::string pid = read_file(dir / victim_pid);
        if (!pid.empty())
          ::kill(std::stoi(pid), SIGKILL);
      });
      // Forty members of 20 s (about half a second each, five under the
      // sanitizers): ten seconds and more were the job left alone; the
      // survivor ends about a member after the kill.
      const auto start = std::chrono::steady_clock::now();
      const CliRun run = run_beamslider({"ensemble", "--members", "40", "--end-time", "20", "--quiet", "--output",
                                         out.string()},
                                        CliLimits().timeout(60).launched_by(launcher));
      std::cout << "rank " << victim << " killed: the job ended after "
                << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s" << std::endl;
      killer.join();
      EXPECT_FALSE(run.timed_out) << "rank " << victim << " killed: the other rank waits for it";
      const std::string said = "rank " + std::to_string(victim) + " (process ";
      EXPECT_NE(run.err.find(said), std::string::npos) << run.err;
      EXPECT_NE(run.err.find("ended in the middle of the run, so the job ends"), std::string::npos) << run.err;
      if (victim == 1)
        {
          const std::string record = read_file(out / "run.txt");
          EXPECT_NE(record.find("failed (exit 1): beamslider failed: " + said), std::string::npos) << record;
        }
      fs::remove_all(dir);
    }
}

// A failure in the middle of a run on two ranks: a load step of the solid
// that Newton cannot converge fails on both ranks; rank 0 says it once, both
// exit (none is left waiting), statics.csv keeps its header and the stopped
// line, and no statics.pvtu or piece is written.
TEST(FaultsUnderMpi, AFailedSolidLoadStepIsSaidOnceAndLeavesTheMarkedTableOnly)
{
  const fs::path dir = fresh_folder("faults_mpi_statics"), statuses = fresh_folder("faults_mpi_statics_ranks");
  const CliRun run =
    run_beamslider(small_solid({"statics", "mueller2023-ideal-solid", "--line-load", "1e12", "--steps", "4",
                                "--output", dir.string()}),
                   CliLimits().timeout(120).launched_by(two_ranks(statuses)));
  ASSERT_FALSE(run.timed_out) << "a rank was left waiting";
  expect_ranks_exited_with(statuses, 1);
  EXPECT_EQ(count(run.err, "beamslider failed: "), 1u) << run.err;
  EXPECT_NE(run.err.find("load step 1 of 4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("statics.csv holds the 0 converged steps before it; statics.pvtu not written"),
            std::string::npos)
    << run.err;
  const std::string table = read_file(dir / "statics.csv");
  EXPECT_EQ(table.rfind("line_load_n_per_m,w_mid_m,newton_iterations\n# stopped: load step 1 of 4", 0), 0u)
    << table;
  EXPECT_EQ(files_with(dir, "statics.pvtu"), std::vector<std::string>());
  EXPECT_EQ(files_with(dir, ".vtu"), std::vector<std::string>());
  fs::remove_all(dir);
  fs::remove_all(statuses);
}

// A failure of rank 0 alone: it cannot prepare the output folder (another
// process holds it), and the other rank, which waits for the folder's name
// from rank 0, learns of the failure instead and exits 1 too; said once.
// (Before fail_together, rank 1 spun in the broadcast until its CPU limit.)
TEST(FaultsUnderMpi, AFolderInUseOnRankZeroEndsEveryRank)
{
  const fs::path dir = fresh_folder("faults_mpi_held"), statuses = fresh_folder("faults_mpi_held_ranks");
  // Held as a run holds it: the lock file flock()ed (output_file.h).
  const int lock = open((dir / output_folder_lock_name()).c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_EQ(flock(lock, LOCK_EX), 0);
  const CliRun run =
    run_beamslider(small_solid({"modes", "mueller2023-ideal-solid", "--output", dir.string()}),
                   CliLimits().timeout(60).launched_by(two_ranks(statuses)));
  close(lock);
  ASSERT_FALSE(run.timed_out) << "a rank was left waiting";
  expect_ranks_exited_with(statuses, 1);
  EXPECT_EQ(count(run.err, "error: "), 1u) << run.err;
  EXPECT_NE(run.err.find("is in use by process"), std::string::npos) << run.err;
  fs::remove_all(dir);
  fs::remove_all(statuses);
}

// A command that runs on one process, started by mpirun on two: each rank
// would run it alone into the same folder. Refused on both ranks before the
// folder exists (exit 2, said once), for a command of its own and for the
// beam's branch of one that runs the solid on MPI.
TEST(FaultsUnderMpi, ACommandOfOneProcessIsRefusedOnSeveral)
{
  const fs::path dir = fresh_folder("faults_mpi_one");
  for (const auto &args : {std::vector<std::string>{"simulate", "--end-time", "0.01"},
                           std::vector<std::string>{"modes", "mueller2023"}})
    {
      const fs::path statuses = dir / ("statuses_" + args[0]), out = dir / args[0];
      fs::create_directories(statuses);
      std::vector<std::string> command = args;
      command.insert(command.end(), {"--output", out.string()});
      const CliRun run = run_beamslider(command, CliLimits().timeout(60).launched_by(two_ranks(statuses)));
      ASSERT_FALSE(run.timed_out) << args[0];
      expect_ranks_exited_with(statuses, 2);
      EXPECT_EQ(count(run.err, "error: "), 1u) << run.err;
      EXPECT_NE(run.err.find("error: '" + args[0] + "' runs on one process, and this launch started 2"),
                std::string::npos)
        << run.err;
      EXPECT_FALSE(fs::exists(out)) << args[0];
    }
  fs::remove_all(dir);
}

// The beam's statics alike: a failed step leaves the marked table, says that
// statics.vtu is not written, and no statics.vtu of an earlier run in the
// folder stays beside the new table.
TEST(FaultsStatics, AFailedBeamLoadStepLeavesTheMarkedTableAndNoVtu)
{
  const fs::path dir = fresh_folder("faults_beam_statics");
  ASSERT_EQ(run_beamslider({"statics", "mueller2023-ideal", "--line-load", "1", "--output", dir.string(), "-q"})
              .exit_code,
            0);
  ASSERT_TRUE(fs::exists(dir / "statics.vtu"));
  const CliRun run = run_beamslider(
    {"statics", "mueller2023-ideal", "--line-load", "1e12", "--steps", "4", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("statics.csv holds the 0 converged steps before it; statics.vtu not written"),
            std::string::npos)
    << run.err;
  EXPECT_NE(read_file(dir / "statics.csv").find("\n# stopped: load step 1 of 4"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "statics.vtu"));
  fs::remove_all(dir);
}

// A full disk at the beam's modes.vtu and statics.vtu: exit 1 naming the
// file, no part of it left. The limit lets the small files through (the
// folder's records, the CSV tables) and stops the .vtu.
TEST(FaultsFullDisk, TheBeamsVtuFilesFailNamingTheFileAndLeaveNoPart)
{
  const fs::path dir = fresh_folder("faults_disk_beam");
  CliRun run = run_beamslider({"modes", "mueller2023", "--output", (dir / "modes").string()},
                              CliLimits().file_size(16384));
  expect_refused_write(run, dir / "modes", (dir / "modes" / "modes.vtu").string(), "modes.vtu");
  run = run_beamslider({"statics", "mueller2023", "--line-load", "1", "--steps", "4", "--output",
                        (dir / "statics").string()},
                       CliLimits().file_size(16384));
  expect_refused_write(run, dir / "statics", (dir / "statics" / "statics.vtu").string(), "statics.vtu");
  fs::remove_all(dir);
}

// A full disk at a checkpoint (written atomically: a temporary renamed over
// the last one): exit 1 naming checkpoint.bin, not its hidden temporary, and
// no part of either left.
TEST(FaultsFullDisk, ACheckpointFailsNamingTheFileAndLeavesNoPart)
{
  const fs::path dir = fresh_folder("faults_disk_checkpoint");
  const CliRun run = run_beamslider(
    {"simulate", "--end-time", "0.02", "--checkpoint-every", "0.01", "--output", dir.string(), "-q"},
    CliLimits().file_size(12288)); // the checkpoint: 17 kB, the folder's records and the CSV files below
  expect_refused_write(run, dir, (dir / "checkpoint.bin").string(), "checkpoint");
  fs::remove_all(dir);
}

// A full disk at the solid's pieces on two ranks: every rank learns that a
// piece failed, removes its own, and exits 1; rank 0 says which file failed,
// once; neither the record nor a piece stays, and rank 0 writes nothing
// after it. The limit holds for the ranks only (prlimit): mpirun's own
// shared memory files are larger, and so are the files behind Open MPI's
// shared memory between the ranks, hence System V shared memory, which is no
// file.
TEST(FaultsFullDisk, TheSolidsPiecesFailOnEveryRankAndLeaveNoPart)
{
  const fs::path dir = fresh_folder("faults_disk_solid"), statuses = fresh_folder("faults_disk_solid_ranks");
  std::vector<std::string> launcher = two_ranks(statuses, {"prlimit", "--fsize=12288"});
  launcher.insert(launcher.begin() + 4, {"--mca", "shmem", "sysv"});
  const CliRun run =
    run_beamslider(small_solid({"modes", "mueller2023-ideal-solid", "--modes", "4", "--output", dir.string()}),
                   CliLimits().timeout(120).launched_by(launcher));
  expect_refused_write(run, dir, (dir / "modes_0000.vtu").string(), "modes", false);
  expect_ranks_exited_with(statuses, 1);
  EXPECT_FALSE(fs::exists(dir / "modes.csv")) << "rank 0 went on after the failed write";
  fs::remove_all(dir);
  fs::remove_all(statuses);
}

// A checkpoint whose count of overrides says more than its bytes can hold
// (checksum made to match, as a bug or a careless edit would): refused with
// exit 2 naming the file, before the count sizes anything (it used to end in
// std::vector's length error, exit 1).
TEST(FaultsCheckpoint, ARecordedCountBeyondTheFileIsRefusedNamingTheFile)
{
  const fs::path dir = fresh_folder("faults_checkpoint");
  const std::string scene = std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/mueller2023.prm";
  CliRun run = run_beamslider({"simulate", scene, "--end-time", "0.1", "--checkpoint-every", "0.1", "--output",
                               dir.string(), "-q"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const fs::path file = dir / "checkpoint.bin";
  std::string bytes   = read_file(file);
  // The layout of checkpoint.h: magic line, format, version, payload length,
  // payload, checksum; the payload starts with the scene file (length and
  // text), the scene's hash, then the count of overrides.
  const std::size_t magic = bytes.find('\n') + 1;
  std::uint64_t n         = 0;
  std::memcpy(&n, bytes.data() + magic + 8, 8);
  const std::size_t payload = magic + 8 + 8 + n + 8;
  std::memcpy(&n, bytes.data() + payload, 8);
  const std::size_t overrides = payload + 8 + n + 8;
  std::uint64_t length        = 0;
  std::memcpy(&length, bytes.data() + payload - 8, 8);
  ASSERT_EQ(bytes.size(), payload + length + 8);
  for (const std::uint64_t recorded : {std::uint64_t(1) << 62, std::uint64_t(1000000)})
    {
      std::memcpy(bytes.data() + overrides, &recorded, 8);
      const std::uint64_t checksum = fnv1a(bytes.substr(payload, length));
      std::memcpy(bytes.data() + payload + length, &checksum, 8);
      std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
      run = run_beamslider({"simulate", "--resume", dir.string(), "--end-time", "0.2"});
      EXPECT_EQ(run.exit_code, 2) << recorded << ": " << run.err;
      EXPECT_EQ(run.err.rfind("error: --resume: '" + file.string() + "': checkpoint records " +
                                std::to_string(recorded) + " entries",
                              0),
                0u)
        << run.err;
    }
  fs::remove_all(dir);
}

// Every file the program reads goes through one guarded reader
// (io/input_file.h): a FIFO or a device in a file's place is refused by its
// type before it is opened (no read that waits for a writer or never ends),
// and a file of random bytes or a sound file cut short (in the middle of a
// line, as a full disk or a killed writer leaves it) by its format. Each
// reader, each bad file: exit 2 and a message that names the file. A run
// that waited on the FIFO would use no CPU time and be ended by the
// wall-clock limit (timed_out).
TEST(FaultsReaders, EveryReaderRefusesAFifoADeviceRandomBytesAndACutFileNamingTheFile)
{
  const fs::path dir = fresh_folder("faults_readers");
  const std::string scene = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";
  // A finished run's parameters.prm, for the resume folders.
  CliRun run = run_beamslider({"simulate", "--end-time", "0.02", "--checkpoint-every", "0.01", "--quiet", "--output",
                                (dir / "done").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Sound files of each kind, to cut short.
  for (const std::vector<std::string> &made :
       {std::vector<std::string>{"ensemble", "--members", "2", "--end-time", "0.01", "--quiet", "--output",
                                 (dir / "sound_ensemble").string()},
        std::vector<std::string>{"sweep", "--from", "0.3", "--to", "0.31", "--free-time", "0", "--quiet", "--output",
                                 (dir / "sound_sweep").string()},
        std::vector<std::string>{"map", "--frequency", "124", "--acceleration", "14", "--start", "0.3", "--end-time",
                                 "0.01", "--members", "1", "--quiet", "--output", (dir / "sound_map").string()}})
    {
      run = run_beamslider(made);
      ASSERT_EQ(run.exit_code, 0) << made[0] << ": " << run.err;
    }
  const std::map<std::string, fs::path> sound = {{"scene.prm", BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm"},
                                                 {"uniform.msh", BEAMSLIDER_SOURCE_DIR "/meshes/uniform.msh"},
                                                 {"members.csv", dir / "sound_ensemble" / "members.csv"},
                                                 {"pcs.csv", dir / "sound_sweep" / "pcs.csv"},
                                                 {"checkpoint.bin", dir / "done" / "checkpoint.bin"},
                                                 {"map_settings.txt", dir / "sound_map" / "map_settings.txt"}};
  std::string random_bytes(4096, '\0');
  unsigned int state = 12345;
  for (char &c : random_bytes)
    c = static_cast<char>((state = state * 1103515245u + 12345u) >> 16);

  struct Reader
  {
    std::string name;      // the file's name in its folder
    bool input_format;     // random bytes are refused by its format (a store is recomputed instead)
    std::function<std::vector<std::string>(const fs::path &folder)> command;
  };
  const std::vector<Reader> readers = {
    {"scene.prm", true, [&](const fs::path &f) {
       return std::vector<std::string>{"simulate", (f / "scene.prm").string(), "--quiet", "--output", (f / "out").string()};
     }},
    {"uniform.msh", true, [&](const fs::path &f) {
       fs::copy_file(BEAMSLIDER_SOURCE_DIR "/meshes/uniform.prm", f / "uniform.prm");
       return std::vector<std::string>{"simulate", (f / "uniform.prm").string(), "--end-time", "0.01", "--quiet",
                                       "--output", (f / "out").string()};
     }},
    {"members.csv", true, [&](const fs::path &f) {
       return std::vector<std::string>{"ensemble", "--members", "2", "--end-time", "0.01", "--against", f.string(),
                                       "--quiet", "--output", (f / "out").string()};
     }},
    {"pcs.csv", true, [&](const fs::path &f) {
       return std::vector<std::string>{"sweep", "--from", "0.3", "--to", "0.31", "--free-time", "0", "--against",
                                       f.string(), "--quiet", "--output", (f / "out").string()};
     }},
    {"checkpoint.bin", true, [&](const fs::path &f) {
       fs::copy_file(dir / "done" / "parameters.prm", f / "parameters.prm");
       return std::vector<std::string>{"simulate", "--resume", f.string(), "--quiet"};
     }},
    {"map_settings.txt", true, [&](const fs::path &f) {
       return std::vector<std::string>{"map", "--frequency", "124", "--acceleration", "14", "--start", "0.3",
                                       "--end-time", "0.01", "--members", "1", "--quiet", "--output", f.string()};
     }},
    {"member_runs.csv", false, [&](const fs::path &f) {
       return std::vector<std::string>{"ensemble", "--members", "2", "--end-time", "0.01", "--quiet", "--output",
                                       f.string()};
     }}};

  unsigned int n = 0;
  for (const Reader &reader : readers)
    for (const std::string bad : {"fifo", "device", "random", "cut"})
      {
        if ((bad == "random" || bad == "cut") && !reader.input_format)
          continue;
        const fs::path folder = dir / (std::to_string(n++) + "-" + bad);
        fs::create_directories(folder);
        const std::vector<std::string> args = reader.command(folder);
        const fs::path file                 = folder / reader.name;
        if (bad == "fifo")
          ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0);
        else if (bad == "device")
          fs::create_symlink("/dev/zero", file);
        else if (bad == "random")
          std::ofstream(file, std::ios::binary) << random_bytes;
        else
          {
            // Cut at 60 % of its length, inside a line.
            std::string text = read_file(sound.at(reader.name));
            std::size_t at   = text.size() * 3 / 5;
            while (at > 0 && (text[at - 1] == '\n' || text[at] == '\n'))
              --at;
            std::ofstream(file, std::ios::binary) << text.substr(0, at);
          }
        run = run_beamslider(args, CliLimits().timeout(10));
        const std::string what = reader.name + " as " + bad;
        EXPECT_FALSE(run.timed_out) << what << ": hangs";
        EXPECT_EQ(run.exit_code, 2) << what << ": " << run.err;
        EXPECT_NE(run.err.find(reader.name), std::string::npos) << what << ": " << run.err;
        if (bad == "fifo" || bad == "device")
          EXPECT_NE(run.err.find("not a regular file"), std::string::npos) << what << ": " << run.err;
      }
  EXPECT_EQ(n, 26u);
  fs::remove_all(dir);
}
