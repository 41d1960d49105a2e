// Ensembles and the error ladder as persisted, distributed member runs
// (verification/studies/member_runs.h), end to end: a ladder killed with
// SIGKILL and started again ends with the files of an uninterrupted run; a
// members file cut short is resumed, its complete rows kept (not run
// again); a members file of other settings is not reused; two MPI ranks give
// the members of one process.
#include "tests/clean_mpi_program.h"
#include "tests/read_text_file.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using beamslider::testing::read_file;

namespace
{
  int run_program(const std::vector<std::string> &args, const std::function<bool()> &kill_when = {},
                  const int signal = SIGKILL)
  {
    return beamslider::testing::run_clean_mpi_program(args, kill_when, signal);
  }

  std::vector<std::string> lines(const fs::path &p)
  {
    std::vector<std::string> out;
    std::istringstream in(read_file(p));
    std::string l;
    while (std::getline(in, l))
      out.push_back(l);
    return out;
  }

  // The lines of a CSV file without the column `drop` (a wall-clock time,
  // which no two runs share); the other cells as written.
  std::vector<std::string> without_column(const fs::path &p, const std::string &drop)
  {
    std::vector<std::string> out;
    std::size_t column = std::string::npos;
    for (const std::string &line : lines(p))
      {
        std::vector<std::string> cells;
        std::stringstream row(line);
        std::string cell;
        while (std::getline(row, cell, ','))
          cells.push_back(cell);
        if (column == std::string::npos)
          for (std::size_t k = 0; k < cells.size(); ++k)
            if (cells[k] == drop)
              column = k;
        std::string kept;
        for (std::size_t k = 0; k < cells.size(); ++k)
          if (k != column)
            kept += cells[k] + ",";
        out.push_back(kept);
      }
    EXPECT_NE(column, std::string::npos) << drop << " in " << p;
    return out;
  }

  fs::path fresh(const std::string &name)
  {
    const auto dir = fs::temp_directory_path() / ("beamslider_member_runs_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(dir);
    return dir;
  }

  // A small ladder: the ROM N=10 rung and the FE reference, 3 members each
  // over 0.3 s (37 periods: enough for the trace analysis), and beside them
  // the checks at half their step, the reference's (with its witness at
  // twice its step) and N=10's: 15 members in member_runs.csv.
  std::vector<std::string> small_ladder(const fs::path &out)
  {
    return {BEAMSLIDER_EXECUTABLE, "ladder", "--rung", "ROM N=10", "--members", "3", "--end-time", "0.3",
            "--output", out.string()};
  }

  std::vector<std::string> small_ensemble(const fs::path &out, const std::string &end_time = "1.5")
  {
    return {BEAMSLIDER_EXECUTABLE, "ensemble", "--members", "4", "--end-time", end_time, "--output", out.string()};
  }

  void expect_same_ladder(const fs::path &a, const fs::path &b)
  {
    EXPECT_EQ(without_column(b / "ladder.csv", "wall_s_per_member"), without_column(a / "ladder.csv", "wall_s_per_member"));
    EXPECT_EQ(without_column(b / "ladder_members.csv", "wall_s"), without_column(a / "ladder_members.csv", "wall_s"));
    EXPECT_EQ(read_file(b / "ladder_steps.csv"), read_file(a / "ladder_steps.csv"));
    // The reference's convergence evidence too (but the wall times).
    EXPECT_EQ(without_column(b / "convergence.csv", "wall_s_per_member"),
              without_column(a / "convergence.csv", "wall_s_per_member"));
  }

  // member_runs.csv's rows: the key line, the header, one row per member.
  const std::size_t head_lines = 2;
  const std::size_t ladder_members = 15; // 2 rungs, their Δt/2 and the reference's 2Δt, 3 members each
} // namespace

TEST(MemberRuns, LadderKilledAndStartedAgainEndsWithTheFilesOfAnUninterruptedRun)
{
  const fs::path whole = fresh("whole"), killed = fresh("killed");
  ASSERT_EQ(run_program(small_ladder(whole)), 0);
  ASSERT_EQ(lines(whole / "member_runs.csv").size(), head_lines + ladder_members);

  // kill -9 once the first member is persisted (fourteen still to run, the
  // longest first), then the same command again.
  const fs::path record = killed / "member_runs.csv";
  run_program(small_ladder(killed), [&] { return fs::exists(record) && lines(record).size() > head_lines; });
  ASSERT_EQ(run_program(small_ladder(killed)), 0);
  expect_same_ladder(whole, killed);
  EXPECT_EQ(lines(killed / "member_runs.csv").size(), head_lines + ladder_members);
  fs::remove_all(whole);
  fs::remove_all(killed);
}

TEST(MemberRuns, AMembersFileCutShortIsResumedKeepingItsCompleteRows)
{
  const fs::path whole = fresh("whole_cut"), cut = fresh("cut");
  ASSERT_EQ(run_program(small_ladder(whole)), 0);
  // What a kill leaves: the key, the header, two complete members and a row
  // cut in the middle. The wall time of the first kept member is set to a
  // mark: if it is read back (not run again), ladder_members.csv shows it.
  std::vector<std::string> rows = lines(whole / "member_runs.csv");
  ASSERT_EQ(rows.size(), head_lines + ladder_members);
  const std::string wall_mark = "4321"; // as ladder_members.csv writes it (4 digits)
  // The kept member must be a rung's (group 0 or 1), not one of the checks'
  // (groups 2 to 4; the reference's, the longest, is the first to finish),
  // to show in ladder_members.csv.
  std::size_t rung_row = head_lines;
  while (rung_row < rows.size() && !(rows[rung_row].rfind("0,", 0) == 0 || rows[rung_row].rfind("1,", 0) == 0))
    ++rung_row;
  ASSERT_LT(rung_row, rows.size());
  {
    std::string &kept = rows[rung_row];
    // wall_s is the 15th of 17 cells; the periods (last) hold no commas.
    std::size_t at = 0;
    for (int k = 0; k < 14; ++k)
      at = kept.find(',', at) + 1;
    kept.replace(at, kept.find(',', at) - at, wall_mark);
  }
  // Two complete members (the rung's and another) and one cut in the middle.
  const std::size_t other = rung_row == head_lines ? head_lines + 1 : head_lines;
  const std::size_t cut_row = std::max(rung_row, other) + 1;
  ASSERT_LT(cut_row, rows.size());
  fs::create_directories(cut);
  {
    std::ofstream out(cut / "member_runs.csv");
    out << rows[0] << '\n' << rows[1] << '\n' << rows[other] << '\n' << rows[rung_row] << '\n'
        << rows[cut_row].substr(0, rows[cut_row].size() / 2);
  }
  ASSERT_EQ(run_program(small_ladder(cut)), 0);
  expect_same_ladder(whole, cut);
  EXPECT_NE(read_file(cut / "ladder_members.csv").find(wall_mark), std::string::npos)
    << "the complete member was run again instead of read back";
  EXPECT_EQ(lines(cut / "member_runs.csv").size(), head_lines + ladder_members);
  fs::remove_all(whole);
  fs::remove_all(cut);
}

TEST(MemberRuns, AMembersFileOfOtherSettingsIsNotReused)
{
  const fs::path dir = fresh("other"), shorter = fresh("shorter");
  ASSERT_EQ(run_program(small_ensemble(dir)), 0);
  const std::string first_key = lines(dir / "member_runs.csv").front();
  // The same folder, another end time: the old members are moved aside and
  // every member runs afresh, to the numbers of a fresh folder.
  ASSERT_EQ(run_program(small_ensemble(dir, "1.0")), 0);
  EXPECT_EQ(lines(dir / "member_runs.other.csv").front(), first_key);
  EXPECT_NE(lines(dir / "member_runs.csv").front(), first_key);
  EXPECT_EQ(lines(dir / "member_runs.csv").size(), head_lines + 4);
  ASSERT_EQ(run_program(small_ensemble(shorter, "1.0")), 0);
  EXPECT_EQ(without_column(dir / "members.csv", "wall_s"), without_column(shorter / "members.csv", "wall_s"));
  EXPECT_EQ(read_file(dir / "statistics.csv"), read_file(shorter / "statistics.csv"));
  fs::remove_all(dir);
  fs::remove_all(shorter);
}

TEST(MemberRuns, TwoRanksUnderMpirunGiveTheMembersOfOneProcess)
{
  const fs::path one = fresh("one"), two = fresh("two"), ladder_one = fresh("ladder_one"),
                 ladder_two = fresh("ladder_two");
  const std::vector<std::string> mpirun = {"mpirun", "-np", "2", "--oversubscribe"};
  ASSERT_EQ(run_program(small_ensemble(one)), 0);
  std::vector<std::string> args = mpirun;
  for (const auto &a : small_ensemble(two))
    args.push_back(a);
  ASSERT_EQ(run_program(args), 0);
  EXPECT_EQ(without_column(two / "members.csv", "wall_s"), without_column(one / "members.csv", "wall_s"));
  EXPECT_EQ(read_file(two / "statistics.csv"), read_file(one / "statistics.csv"));

  ASSERT_EQ(run_program(small_ladder(ladder_one)), 0);
  args = mpirun;
  for (const auto &a : small_ladder(ladder_two))
    args.push_back(a);
  ASSERT_EQ(run_program(args), 0);
  expect_same_ladder(ladder_one, ladder_two);
  for (const auto &d : {one, two, ladder_one, ladder_two})
    fs::remove_all(d);
}

namespace
{
  // After `args` (a 12-member ensemble into `two`) was stopped by SIGTERM
  // under mpirun: run.txt says interrupted (143) and member_runs.csv keeps
  // some members but not all; run again, the folder ends with the members
  // of `one`, the same ensemble run by one process uninterrupted.
  void expect_stopped_then_completed(const std::vector<std::string> &args, const fs::path &one, const fs::path &two)
  {
    const std::string record = read_file(two / "run.txt");
    EXPECT_NE(record.find("interrupted (exit 143)"), std::string::npos) << record;
    const std::size_t kept = lines(two / "member_runs.csv").size() - 2;
    EXPECT_GE(kept, 2u);
    EXPECT_LT(kept, 12u) << "the run ended before the signal";
    ASSERT_EQ(run_program(args), 0);
    EXPECT_EQ(lines(two / "member_runs.csv").size() - 2, 12u);
    EXPECT_EQ(without_column(two / "members.csv", "wall_s"), without_column(one / "members.csv", "wall_s"));
    EXPECT_EQ(read_file(two / "statistics.csv"), read_file(one / "statistics.csv"));
  }
} // namespace

// An ensemble on two ranks stopped by SIGTERM to its ranks (a scheduler's
// stop, or `kill` of the job's processes) ends as interrupted, exit 143 in
// run.txt, keeping the members finished; run again into its folder, it
// computes only the rest and ends with the members of one uninterrupted
// process.
TEST(MemberRuns, TwoRanksStoppedBySigtermAndRunAgainGiveTheMembersOfOneProcess)
{
  const fs::path one = fresh("stopped_one"), two = fresh("stopped_two"), pids = fresh("stopped_pids");
  const auto ensemble = [](const fs::path &out) {
    return std::vector<std::string>{BEAMSLIDER_EXECUTABLE, "ensemble", "--members", "12", "--end-time", "20",
                                    "--output", out.string()};
  };
  ASSERT_EQ(run_program(ensemble(one)), 0);
  fs::create_directories(pids);
  const std::vector<std::string> args = beamslider::testing::two_ranks_recording_pids(pids.string(), ensemble(two));
  // The signal once two members are in member_runs.csv (after its key line
  // and header), about a second into a run of six.
  bool sent = false;
  const auto two_done = [&] { return fs::exists(two / "member_runs.csv") && lines(two / "member_runs.csv").size() >= 4; };
  EXPECT_EQ(run_program(args, beamslider::testing::signal_ranks_when(pids.string(), two_done, SIGTERM, sent)), 143);
  ASSERT_TRUE(sent);
  expect_stopped_then_completed(args, one, two);
  for (const auto &d : {one, two, pids})
    fs::remove_all(d);
}

// The same stop through the launcher: SIGTERM (or Ctrl-C) to `mpirun`
// itself, which passes SIGTERM to the ranks and kills them a second later.
// The ranks record the interruption before MPI is finalised (MPI_Finalize
// does not return while mpirun ends the job), so run.txt says so; mpirun's
// own status is its own (1 in Open MPI 4.1), not the ranks'. Run again, the
// folder ends with the members of one uninterrupted process.
TEST(MemberRuns, MpirunStoppedBySigtermRecordsTheInterruptionAndRunsAgainToTheMembersOfOneProcess)
{
  const fs::path one = fresh("launcher_one"), two = fresh("launcher_two");
  const auto ensemble = [](const fs::path &out) {
    return std::vector<std::string>{BEAMSLIDER_EXECUTABLE, "ensemble", "--members", "12", "--end-time", "20",
                                    "--output", out.string()};
  };
  ASSERT_EQ(run_program(ensemble(one)), 0);
  std::vector<std::string> args = {"mpirun", "-np", "2", "--oversubscribe"};
  const std::vector<std::string> program = ensemble(two);
  args.insert(args.end(), program.begin(), program.end());
  const auto two_done = [&] { return fs::exists(two / "member_runs.csv") && lines(two / "member_runs.csv").size() >= 4; };
  EXPECT_NE(run_program(args, two_done, SIGTERM), 0);
  expect_stopped_then_completed(args, one, two);
  for (const auto &d : {one, two})
    fs::remove_all(d);
}

// A folder holds the files of the command beside it: the check rounds'
// member files (member_runs.check-r.csv) of an earlier run that went
// further than this one are removed once this one ends; files of other
// names are left alone.
TEST(MemberRuns, AnEndedRunLeavesNoCheckFilesOfRoundsItDidNotReach)
{
  const fs::path dir = fresh("unreached_checks");
  fs::create_directories(dir);
  for (const char *name : {"member_runs.check-1.csv", "member_runs.check-12.csv", "member_runs.check-x.csv", "notes.txt"})
    std::ofstream(dir / name) << "an earlier run's\n";
  ASSERT_EQ(run_program(small_ensemble(dir)), 0); // the ROM: no check rounds
  EXPECT_FALSE(fs::exists(dir / "member_runs.check-1.csv"));
  EXPECT_FALSE(fs::exists(dir / "member_runs.check-12.csv"));
  EXPECT_TRUE(fs::exists(dir / "member_runs.check-x.csv"));
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_EQ(lines(dir / "member_runs.csv").size(), 2u + 4);
  fs::remove_all(dir);
}
