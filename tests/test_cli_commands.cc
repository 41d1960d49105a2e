// Every sub-command end to end, as the README documents it: exit code 0 on
// the default scene (the scene argument may be left out), the CSV columns
// the README names, and determinism (two runs, the same bytes).
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace beamslider::testing;

namespace
{
  std::string first_line(const fs::path &file)
  {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    return line;
  }

  // Rows after the header.
  std::vector<std::vector<double>> numeric_rows(const fs::path &file)
  {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line))
      {
        std::vector<double> row;
        std::stringstream cells(line);
        std::string cell;
        while (std::getline(cells, cell, ','))
          row.push_back(std::strtod(cell.c_str(), nullptr));
        rows.push_back(row);
      }
    return rows;
  }

  bool starts_with(const std::string &text, const std::string &prefix) { return text.rfind(prefix, 0) == 0; }
} // namespace

TEST(Commands, ModesWithoutSceneArgumentUsesTheDefaultScene)
{
  const fs::path dir = fresh_folder("cmd_modes");
  const CliRun run   = run_beamslider({"modes", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(first_line(dir / "modes.csv"), "mode,frequency_hz");
  const auto rows = numeric_rows(dir / "modes.csv");
  ASSERT_EQ(rows.size(), 7u);
  for (std::size_t i = 1; i < rows.size(); ++i)
    EXPECT_GT(rows[i][1], rows[i - 1][1]) << "frequencies must increase with the mode number";
  fs::remove_all(dir);
}

TEST(Commands, CoefficientsWritesTheDocumentedColumns)
{
  const fs::path dir = fresh_folder("cmd_coefficients");
  const CliRun run   = run_beamslider({"coefficients", "--method", "analytic", "--modes", "3", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(first_line(dir / "coefficients.csv"), "n,j,k,l,value");
  const auto rows = numeric_rows(dir / "coefficients.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0][0], 1);
  EXPECT_GT(rows[0][4], 0.) << "b_111 of a stretched beam is positive (hardening)";
  fs::remove_all(dir);
}

TEST(Commands, BackboneWritesTheDocumentedColumnsUpToTheAskedAmplitude)
{
  const fs::path dir = fresh_folder("cmd_backbone");
  const CliRun run   = run_beamslider({"backbone", "--model", "rom", "--max-amplitude", "1", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(first_line(dir / "backbone.csv"), "amplitude_over_h,frequency_hz,segment,branch,peak_over_h,relative_residual");
  EXPECT_EQ(first_line(dir / "eq4.csv"), "amplitude_over_h,frequency_hz");
  double largest = 0;
  for (const auto &row : numeric_rows(dir / "backbone.csv"))
    largest = std::max(largest, row[0]);
  EXPECT_NEAR(largest, 1., 0.05);
  fs::remove_all(dir);
}

TEST(Commands, SimulateWritesTheDocumentedColumnsAndIsDeterministic)
{
  const fs::path dir = fresh_folder("cmd_simulate");
  for (const char *name : {"a", "b"})
    {
      const CliRun run = run_beamslider({"simulate", "--end-time", "0.2", "--output", (dir / name).string()});
      ASSERT_EQ(run.exit_code, 0) << run.err;
    }
  EXPECT_EQ(first_line(dir / "a" / "trace.csv"),
            "t_s,slider_x_over_L,slider_z_m,slider_beta_rad,w_center_m,w_probe_m,amplitude_over_h");
  EXPECT_TRUE(starts_with(first_line(dir / "a" / "periods.csv"), "period,t_start_s,t_end_s,slider_x_over_L,amplitude_over_h"));
  EXPECT_EQ(numeric_rows(dir / "a" / "trace.csv").size(), 201u) << "1000 rows per second from t = 0";
  EXPECT_EQ(read_file(dir / "a" / "trace.csv"), read_file(dir / "b" / "trace.csv")) << "two runs differ";
  EXPECT_EQ(read_file(dir / "a" / "periods.csv"), read_file(dir / "b" / "periods.csv")) << "two runs differ";
  fs::remove_all(dir);
}

TEST(Commands, SweepWritesTheDocumentedColumns)
{
  const fs::path dir = fresh_folder("cmd_sweep");
  const CliRun run   = run_beamslider({"sweep", "--from", "0.30", "--to", "0.32", "--step", "0.01", "--settle-time", "0.05",
                                       "--average-time", "0.05", "--free-time", "0", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(starts_with(first_line(dir / "pcs.csv"), "x_over_L,direction,amplitude_over_h,mean_fx_N"))
    << first_line(dir / "pcs.csv");
  fs::remove_all(dir);
}

TEST(Commands, AnimateTakesACaseAndWritesOneDataSetPerPartAndFrame)
{
  const fs::path dir = fresh_folder("cmd_animate");
  const CliRun run   = run_beamslider({"animate", "--case", "signature-move", "--model", "rom", "--end-time", "0.01",
                                       "--frame-rate", "1000", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string pvd = read_file(dir / "animation.pvd");
  std::size_t n_sets = 0;
  for (auto at = pvd.find("<DataSet "); at != std::string::npos; at = pvd.find("<DataSet ", at + 1))
    ++n_sets;
  EXPECT_EQ(n_sets, 3u * 11u) << "beam, slider and contacts for the 11 frames at 0, 1, ..., 10 ms";
  fs::remove_all(dir);
}

// The template is itself a complete, valid scene.
TEST(Commands, SceneTemplateIsAValidScene)
{
  const fs::path dir = fresh_folder("cmd_template");
  CliRun run         = run_beamslider({"scene-template"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ofstream(dir / "template.prm") << run.out;
  run = run_beamslider({"simulate", (dir / "template.prm").string(), "--end-time", "0.01", "--output",
                        (dir / "out").string()});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  fs::remove_all(dir);
}
