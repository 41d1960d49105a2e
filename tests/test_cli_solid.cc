// The solid scenes end to end: `beamslider modes` on the 3D strip on one
// process and on two MPI ranks (the same modes: the partition changes only
// the order of round-off), and the solid's input checks.
#include "tests/clean_mpi_program.h"
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace beamslider::testing;

namespace
{
  // modes.csv as rows of cells.
  std::vector<std::vector<std::string>> csv_rows(const fs::path &file)
  {
    std::ifstream in(file);
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

  std::vector<std::string> modes_command(const fs::path &dir)
  {
    return {BEAMSLIDER_EXECUTABLE, "modes", "mueller2023-ideal-solid", "--modes", "4", "--output", dir.string(), "-q"};
  }
} // namespace

// One rank and two: the same modes in the same order and classes, the
// frequencies within 1e-8. (The floor is round-off, not the eigensolver: the
// thin strip's stiffness entries are ~1e7 times its lowest eigenvalue, and
// summing them in another order moves ω₁ by ~3e-9.)
TEST(SolidModesCommand, TwoRanksGiveTheModesOfOne)
{
  const fs::path one = fresh_folder("solid_modes_one"), two = fresh_folder("solid_modes_two");
  ASSERT_EQ(run_clean_mpi_program(modes_command(one)), 0);
  std::vector<std::string> args = {"mpirun", "-np", "2", "--oversubscribe"};
  const auto command = modes_command(two);
  args.insert(args.end(), command.begin(), command.end());
  ASSERT_EQ(run_clean_mpi_program(args), 0);

  const auto a = csv_rows(one / "modes.csv"), b = csv_rows(two / "modes.csv");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 6u) << "header, four bending modes and the torsion mode between modes 3 and 4";
  EXPECT_EQ(a[0][1], "frequency_hz");
  EXPECT_EQ(a[0][2], "shape");
  for (std::size_t r = 1; r < a.size(); ++r)
    {
      EXPECT_EQ(a[r][2], b[r][2]) << "mode " << r;
      EXPECT_EQ(a[r][3], b[r][3]) << "mode " << r;
      EXPECT_NEAR(std::stod(b[r][1]) / std::stod(a[r][1]), 1., 1e-8) << "mode " << r;
    }
  // Both ranks wrote their piece of the ParaView output.
  EXPECT_TRUE(fs::exists(two / "modes_0001.vtu"));
  EXPECT_NE(read_file(two / "modes.pvtu").find("modes_0001.vtu"), std::string::npos);
  fs::remove_all(one);
  fs::remove_all(two);
}

TEST(SolidModesCommand, BadSolidSettingsAreRefusedNamingTheParameter)
{
  const fs::path dir = fresh_folder("solid_bad");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
    {{"--set", "Solid/Poisson's ratio=0.5"}, "Poisson's ratio"},
    {{"--set", "Solid/Continuum=2d"}, "Continuum"},
    {{"--set", "Supports/Type=elastic"}, "Supports/Type"},
    {{"--set", "Solid/Degree=0"}, "Degree"},
    {{"--slider-at", "0.3"}, "--slider-at"},
  };
  for (const auto &[extra, name] : cases)
    {
      std::vector<std::string> args = {"modes", "mueller2023-ideal-solid", "--output", dir.string()};
      args.insert(args.end(), extra.begin(), extra.end());
      const CliRun run = run_beamslider(args);
      EXPECT_EQ(run.exit_code, 2) << extra.back();
      EXPECT_NE(run.err.find(name), std::string::npos) << run.err;
      EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << "one line: " << run.err;
    }
  fs::remove_all(dir);
}
