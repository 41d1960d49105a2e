// `beamslider map` end to end: the grid parser, restart after a kill (the
// same rows as an uninterrupted run), and a 2-rank run under mpirun giving
// the same rows as one process.
#include "scene/scene.h"
#include "verification/report/map_files.h"
#include "verification/report/report.h"
#include "verification/studies/operating_map.h"

#include "tests/clean_mpi_program.h"
#include <csignal>
#include "tests/read_text_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace beamslider;
using beamslider::testing::read_file;

namespace
{
  int run_program(const std::vector<std::string> &args, const std::function<bool()> &kill_when = {})
  {
    return beamslider::testing::run_clean_mpi_program(args, kill_when);
  }

  // The lines of a file as a sorted list (map.csv's rows come in the order
  // cells finish).
  std::vector<std::string> sorted_lines(const std::filesystem::path &p)
  {
    std::vector<std::string> lines;
    std::istringstream in(read_file(p));
    std::string l;
    while (std::getline(in, l))
      lines.push_back(l);
    std::sort(lines.begin(), lines.end());
    return lines;
  }

  std::filesystem::path fresh(const std::string &name)
  {
    const auto dir = std::filesystem::temp_directory_path() / ("beamslider_map_" + name + "_" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    return dir;
  }

  // A small map: 2 frequencies × 2 accelerations, 2 members, 1.5 s of the ROM.
  std::vector<std::string> small_map(const std::filesystem::path &out)
  {
    return {BEAMSLIDER_EXECUTABLE, "map", "--frequency", "115:125:10", "--acceleration", "10:14:4", "--members", "2",
            "--end-time", "1.5", "--output", out.string()};
  }
} // namespace

TEST(MapGrid, RangesAxesAndCells)
{
  const std::vector<double> f = parse_grid_range("95:135:2.5", "--frequency");
  ASSERT_EQ(f.size(), 17u);
  EXPECT_EQ(f.front(), 95.);
  EXPECT_EQ(f.back(), 135.); // reached despite round-off in 16 × 2.5
  EXPECT_EQ(parse_grid_range("0.1:0.3:0.1", "--start").back(), 0.3);
  EXPECT_EQ(parse_grid_range("124", "--frequency"), std::vector<double>{124.});
  for (const char *bad : {"1:2", "2:1:0.5", "1:2:0", "1:2:-1", "nan", "1:x:1", "0:1:1e-6", ""})
    EXPECT_THROW(parse_grid_range(bad, "--frequency"), InputError) << bad;

  const MapAxis mu = parse_parameter_axis("Contact/Friction coefficient=0:0.4:0.1");
  EXPECT_EQ(mu.parameter, "Contact/Friction coefficient");
  EXPECT_EQ(mu.column, "contact_friction_coefficient");
  EXPECT_EQ(mu.values.size(), 5u);
  EXPECT_THROW(parse_parameter_axis("Friction=0:1:0.1"), InputError);

  // Row-major cells, the first axis slowest.
  MapGrid grid;
  grid.axes = {{"A/a", "a", {1, 2}}, {"B/b", "b", {10, 20, 30}}};
  ASSERT_EQ(grid.n_cells(), 6u);
  EXPECT_EQ(grid.cell_values(4), (std::vector<double>{2, 20}));
  EXPECT_EQ(map_cell_key(grid, 5), "2,30");
  EXPECT_EQ(map_row_cell_key("2,30,1,0,completed", 2), "2,30");
}

TEST(MapGrid, AxesAndTheMapsEndTimeReplaceTheUsersSetOfTheSameParameter)
{
  // verify --section 6 --set "Time stepping/End time=3" once failed with
  // "already set": the cell's scene took both the user's --set and the map's
  // own end time. The axis value and the map's end time win; other --set
  // entries pass through.
  MapGrid grid;
  grid.axes = {{"Excitation/Frequency", "frequency_hz", {110, 120}}};
  const std::vector<std::string> overrides = {"Time stepping/End time=3", "Excitation/Frequency=99",
                                              "Contact/Friction coefficient=0.125"};
  const Scene s = map_cell_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm", overrides, grid, 1, 2.5);
  EXPECT_EQ(s.time_stepping.end_time, 2.5);
  EXPECT_EQ(s.excitation.frequency_hz, 120.);
  EXPECT_EQ(s.contact.friction_coefficient, 0.125);
}

TEST(MapCommand, RestartAfterAKillKeepsFinishedCellsAndEndsWithTheSameRows)
{
  const auto full = fresh("full"), cut = fresh("cut");
  ASSERT_EQ(run_program(small_map(full)), 0);
  const std::vector<std::string> reference = sorted_lines(full / "map.csv");
  ASSERT_EQ(reference.size(), 1u + 4 * 2); // header, 4 cells × 2 members

  // What a kill -9 leaves: two complete cells, one cell with only one of its
  // two members, and a last line cut short.
  std::filesystem::create_directories(cut);
  std::filesystem::copy_file(full / "map_settings.txt", cut / "map_settings.txt");
  std::istringstream in(read_file(full / "map.csv"));
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> rows;
  while (std::getline(in, line))
    rows.push_back(line);
  std::sort(rows.begin(), rows.end()); // rows of a cell next to each other
  {
    std::ofstream out(cut / "map.csv");
    out << header << '\n' << rows[0] << '\n' << rows[1] << '\n' << rows[2] << '\n' << rows[3] << '\n' << rows[4]
        << '\n' << rows[6].substr(0, rows[6].size() / 2);
  }
  ASSERT_EQ(run_program(small_map(cut)), 0);
  EXPECT_EQ(sorted_lines(cut / "map.csv"), reference);
  // The two complete cells were kept, not computed again: timing.csv lists
  // only the two others.
  EXPECT_EQ(sorted_lines(cut / "timing.csv").size(), 1u + 2);

  // Another map into the same folder is refused, not mixed in.
  std::vector<std::string> other = small_map(cut);
  other[4]                       = "110:125:5";
  EXPECT_EQ(run_program(other), 2);
  std::filesystem::remove_all(full);
  std::filesystem::remove_all(cut);
}

TEST(MapCommand, TwoRanksUnderMpirunGiveTheRowsOfOneProcess)
{
  const auto one = fresh("one"), two = fresh("two");
  ASSERT_EQ(run_program(small_map(one)), 0);
  std::vector<std::string> args = {"mpirun", "-np", "2", "--oversubscribe"};
  const std::vector<std::string> map = small_map(two);
  args.insert(args.end(), map.begin(), map.end());
  // Root in a container (CI): Open MPI's opt-in.
  ASSERT_EQ(run_program(args), 0);
  EXPECT_EQ(sorted_lines(two / "map.csv"), sorted_lines(one / "map.csv"));
  // Both ranks computed cells.
  std::set<std::string> ranks;
  std::istringstream timing(read_file(two / "timing.csv"));
  std::string line;
  std::getline(timing, line);
  while (std::getline(timing, line))
    ranks.insert(line.substr(line.rfind(',', line.rfind(',') - 1) + 1, 1));
  EXPECT_EQ(ranks.size(), 2u);
  std::filesystem::remove_all(one);
  std::filesystem::remove_all(two);
}


namespace
{
  // The map the stop tests stop: 5 × 3 cells of 2 members over 10 s, about
  // 0.3 s a member.
  std::vector<std::string> stopped_map(const std::filesystem::path &out)
  {
    return {BEAMSLIDER_EXECUTABLE, "map", "--frequency", "115:125:2.5", "--acceleration", "10:14:2", "--members", "2",
            "--end-time", "10", "--output", out.string()};
  }

  // The lines of `dir`/map.csv so far (0 before it exists).
  std::size_t rows_of(const std::filesystem::path &dir)
  {
    return std::filesystem::exists(dir / "map.csv") ? sorted_lines(dir / "map.csv").size() : 0;
  }

  // After `args` (stopped_map into `two`) was stopped under mpirun:
  // run.txt says interrupted (143), map.csv holds whole cells but not all;
  // run again, it holds the `reference` rows of an uninterrupted run.
  void expect_stopped_then_completed(const std::vector<std::string> &args, const std::vector<std::string> &reference,
                                     const std::filesystem::path &two)
  {
    const std::string record = read_file(two / "run.txt");
    EXPECT_NE(record.find("interrupted (exit 143)"), std::string::npos) << record;
    EXPECT_LT(rows_of(two), reference.size()) << "the run ended before the signal";
    EXPECT_EQ((rows_of(two) - 1) % 2, 0u) << "a cell's rows are written together";
    ASSERT_EQ(run_program(args), 0);
    EXPECT_EQ(sorted_lines(two / "map.csv"), reference);
  }
} // namespace

// A map on two ranks stopped by SIGTERM to its ranks ends as interrupted
// (exit 143 in run.txt) with whole cells in map.csv; run again into its
// folder, it computes only the cells not done and ends with the rows of one
// uninterrupted process.
TEST(MapCommand, TwoRanksStoppedBySigtermAndRunAgainGiveTheRowsOfOneProcess)
{
  const auto one = fresh("stopped_one"), two = fresh("stopped_two"), pids = fresh("stopped_pids");
  ASSERT_EQ(run_program(stopped_map(one)), 0);
  const std::vector<std::string> reference = sorted_lines(one / "map.csv");
  ASSERT_EQ(reference.size(), 1u + 15 * 2);
  std::filesystem::create_directories(pids);
  const std::vector<std::string> args = beamslider::testing::two_ranks_recording_pids(pids.string(), stopped_map(two));
  // The signal once two cells are in map.csv, a second into a run of five.
  bool sent = false;
  const auto two_cells = [&] { return rows_of(two) >= 1 + 2 * 2; };
  EXPECT_EQ(run_program(args, beamslider::testing::signal_ranks_when(pids.string(), two_cells, SIGTERM, sent)), 143);
  ASSERT_TRUE(sent);
  expect_stopped_then_completed(args, reference, two);
  for (const auto &d : {one, two, pids})
    std::filesystem::remove_all(d);
}

// Ctrl-C to `mpirun` itself: Open MPI passes SIGTERM to the ranks and kills
// them a second later. run.txt still records the interruption (the ranks
// write it before MPI is finalised); mpirun's own status is the launcher's.
// Run again, the folder ends with the rows of one uninterrupted process.
TEST(MapCommand, MpirunStoppedByCtrlCRecordsTheInterruptionAndRunsAgainToTheRowsOfOneProcess)
{
  const auto one = fresh("launcher_one"), two = fresh("launcher_two");
  ASSERT_EQ(run_program(stopped_map(one)), 0);
  const std::vector<std::string> reference = sorted_lines(one / "map.csv");
  std::vector<std::string> args = {"mpirun", "-np", "2", "--oversubscribe"};
  const std::vector<std::string> program = stopped_map(two);
  args.insert(args.end(), program.begin(), program.end());
  const auto two_cells = [&] { return rows_of(two) >= 1 + 2 * 2; };
  EXPECT_NE(beamslider::testing::run_clean_mpi_program(args, two_cells, SIGINT), 0);
  expect_stopped_then_completed(args, reference, two);
  for (const auto &d : {one, two})
    std::filesystem::remove_all(d);
}
