// Every sub-command end to end, as the README documents it: exit code 0 on
// the default scene (the scene argument may be left out), the CSV columns
// the README names, and determinism (two runs, the same bytes).
#include "tests/cli_runner.h"
#include "scene/scene.h"
#include "verification/cli/ladder_cache.h"
#include "verification/studies/model_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
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

  // Rows after the header, as text cells (for CSVs with names and empty cells).
  std::vector<std::vector<std::string>> text_rows(const fs::path &file)
  {
    auto rows = read_csv_cells(file);
    if (!rows.empty())
      rows.erase(rows.begin());
    return rows;
  }
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

  // With the scene's static corrections the tensor spans the ROM's basis:
  // the corrections are numbered after the modes, and the terms among the
  // modes alone are those of the modes alone (the analytic terms of each
  // quadruple of shapes do not see the other vectors).
  const fs::path enriched = fresh_folder("cmd_coefficients_corrected");
  const CliRun corrected  = run_beamslider({"coefficients", "--method", "analytic", "--modes", "3", "--set",
                                            "Discretisation/Static corrections=2", "--output", enriched.string()});
  ASSERT_EQ(corrected.exit_code, 0) << corrected.err;
  std::map<std::array<int, 4>, double> modes_only;
  for (const auto &r : rows)
    modes_only[{int(r[0]), int(r[1]), int(r[2]), int(r[3])}] = r[4];
  int largest_index = 0;
  std::size_t matched = 0;
  for (const auto &r : numeric_rows(enriched / "coefficients.csv"))
    {
      largest_index = std::max(largest_index, int(r[0]));
      const auto it = modes_only.find({int(r[0]), int(r[1]), int(r[2]), int(r[3])});
      if (it == modes_only.end())
        continue;
      EXPECT_NEAR(r[4], it->second, 1e-9 * std::abs(rows[0][4])) << r[0] << r[1] << r[2] << r[3];
      ++matched;
    }
  EXPECT_EQ(largest_index, 5) << "3 modes and 2 corrections";
  EXPECT_EQ(matched, modes_only.size());
  fs::remove_all(dir);
  fs::remove_all(enriched);
}

// statics: a small load is in the linear range, where the ideal-clamp strip
// deflects qL⁴/(384 EI) at mid-span (L = 0.14 m, E = 2.1e11 Pa, b = 14.04 mm,
// h = 1 mm in meshes/mueller2023-ideal.prm); each step's load is k/K of Q,
// downward (w_mid < 0). A zero load is refused naming the option.
TEST(Commands, StaticsWritesTheLoadPathAndMatchesTheLinearBeamAtSmallLoad)
{
  const fs::path dir = fresh_folder("cmd_statics");
  const CliRun run   = run_beamslider({"statics", "mueller2023-ideal", "--line-load", "0.5", "--steps", "4",
                                       "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(first_line(dir / "statics.csv"), "line_load_n_per_m,w_mid_m,newton_iterations");
  const auto rows = numeric_rows(dir / "statics.csv");
  ASSERT_EQ(rows.size(), 4u);
  const double EI = 2.1e11 * 0.01404 * std::pow(1e-3, 3) / 12, L = 0.14;
  for (std::size_t k = 0; k < rows.size(); ++k)
    {
      EXPECT_DOUBLE_EQ(rows[k][0], 0.5 * double(k + 1) / 4);
      EXPECT_NEAR(rows[k][1] / (-rows[k][0] * std::pow(L, 4) / (384 * EI)), 1., 1e-4);
    }
  fs::remove_all(dir);

  const CliRun zero = run_beamslider({"statics", "--line-load", "0", "--output", dir.string()});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--line-load"), std::string::npos) << zero.err;
}

// statics on a fine mesh converges (Newton stalled at its round-off floor
// on 56 elements and more, exit 1); a load step that cannot converge (1e12
// N/m, far past any beam) exits 1 and leaves statics.csv with the rows before
// it and a last line that says where it stopped.
TEST(Commands, StaticsConvergesOnFineMeshesAndAFailedStepLeavesAMarkedTable)
{
  const fs::path dir = fresh_folder("cmd_statics_fine");
  for (const std::string n : {"64", "256"})
    {
      const CliRun run = run_beamslider({"statics", "--line-load", "5000", "--steps", "2", "--set",
                                         "Discretisation/Number of elements=" + n, "--output", (dir / n).string()});
      ASSERT_EQ(run.exit_code, 0) << n << " elements: " << run.err;
      EXPECT_EQ(numeric_rows(dir / n / "statics.csv").size(), 2u) << n << " elements";
    }

  const CliRun run = run_beamslider({"statics", "mueller2023-ideal", "--line-load", "1e12", "--steps", "4",
                                     "--output", (dir / "failed").string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  EXPECT_NE(run.err.find("load step 1 of 4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("statics.csv holds the 0 converged steps"), std::string::npos) << run.err;
  std::ifstream in(dir / "failed" / "statics.csv");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u) << read_file(dir / "failed" / "statics.csv");
  EXPECT_EQ(lines[0], "line_load_n_per_m,w_mid_m,newton_iterations");
  EXPECT_EQ(lines[1].rfind("# stopped: load step 1 of 4 (load factor 0.250000): Newton's method", 0), 0u) << lines[1];
  fs::remove_all(dir);
}

// The backbone of the speed–accuracy front's pick, 6 modes and 4 static
// corrections (`Discretisation/Static corrections`): the ROM is built on the
// scene's whole basis, so it differs from plain N = 6, and it stays within
// 0.5 % of the FE beam's backbone up to ŵ = 2 h (issue 58's bound; measured
// 0.02-0.04 %).
TEST(Commands, TheBackboneOfSixModesAndFourCorrectionsIsTheFEsWithinHalfAPercent)
{
  const auto backbone = [](const std::vector<std::string> &extra) {
    const fs::path dir            = fresh_folder("cmd_backbone_basis");
    std::vector<std::string> args = {"backbone", "--max-amplitude", "2", "--quiet", "--output", dir.string(),
                                     "--set", "Discretisation/Number of modes=6"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun run = run_beamslider(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    // The first segment's backbone rows: (ŵ/h, f) in ascending ŵ.
    std::vector<std::pair<double, double>> curve;
    for (const auto &row : read_csv_cells(dir / "backbone.csv"))
      if (row.size() > 3 && row[2] == "0" && row[3] == "backbone")
        curve.emplace_back(std::stod(row[0]), std::stod(row[1]));
    fs::remove_all(dir);
    return curve;
  };
  const auto at = [](const std::vector<std::pair<double, double>> &curve, const double a) {
    for (std::size_t i = 0; i + 1 < curve.size(); ++i)
      if (curve[i].first <= a && a <= curve[i + 1].first)
        {
          const double t = (a - curve[i].first) / (curve[i + 1].first - curve[i].first);
          return curve[i].second + t * (curve[i + 1].second - curve[i].second);
        }
    ADD_FAILURE() << "the backbone does not reach ŵ/h = " << a;
    return std::nan("");
  };
  const auto corrected = backbone({"--model", "rom", "--set", "Discretisation/Static corrections=4"});
  const auto plain     = backbone({"--model", "rom"});
  const auto fe        = backbone({"--model", "fe"});
  for (const double a : {0.5, 1.0, 1.5, 2.0})
    EXPECT_LE(std::abs(at(corrected, a) / at(fe, a) - 1), 0.005) << "at ŵ/h = " << a;
  EXPECT_GT(std::abs(at(corrected, 2.0) - at(plain, 2.0)), 1e-3) << "the corrections changed nothing";
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

  // command.prm: every option with its effective value, the given ones and
  // the defaults alike (the number of harmonics is in no other file).
  const std::string settings = read_file(dir / "command.prm");
  const auto value_of        = [&settings](const std::string &name) {
    const std::string key = "\n  set " + name + " ";
    const auto at         = settings.find(key);
    if (at == std::string::npos)
      return std::string("(missing)");
    const auto begin = settings.find("= ", at) + 2;
    return settings.substr(begin, settings.find('\n', begin) - begin);
  };
  EXPECT_NE(settings.find("subsection backbone"), std::string::npos) << settings;
  EXPECT_EQ(value_of("max-amplitude"), "1");
  EXPECT_EQ(value_of("model"), "rom");
  EXPECT_EQ(value_of("harmonics"), "10"); // the default
  EXPECT_EQ(value_of("scene"), "mueller2023");
  EXPECT_EQ(value_of("output"), dir.string());
  EXPECT_EQ(value_of("help"), "(missing)");
  fs::remove_all(dir);
}

// Two runs, the second with --quiet: the same bytes in every result file,
// and nothing on standard output from the quiet one.
TEST(Commands, SimulateWritesTheDocumentedColumnsAndIsDeterministic)
{
  const fs::path dir = fresh_folder("cmd_simulate");
  for (const char *name : {"a", "b"})
    {
      std::vector<std::string> args = {"simulate", "--end-time", "0.2", "--output", (dir / name).string()};
      const bool quiet              = std::string(name) == "b";
      if (quiet)
        args.push_back("--quiet");
      const CliRun run = run_beamslider(args);
      ASSERT_EQ(run.exit_code, 0) << run.err;
      if (quiet)
        EXPECT_EQ(run.out, "") << "--quiet printed";
      else
        EXPECT_NE(run.out.find("simulate mueller2023"), std::string::npos) << run.out;
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
  // runs.csv: both branches reached all three positions.
  EXPECT_EQ(first_line(dir / "runs.csv"), "run,status,positions,positions_planned,t_end_s");
  const auto runs = text_rows(dir / "runs.csv");
  ASSERT_EQ(runs.size(), 2u);
  for (const auto &r : runs)
    EXPECT_EQ(std::vector<std::string>(r.begin(), r.begin() + 4),
              (std::vector<std::string>{r[0], "completed", "3", "3"}));

  // A range that is not a whole number of steps (0.30, 0.31 and the far end
  // 0.315): the planned count is the grid's, far end included.
  const CliRun odd = run_beamslider({"sweep", "--from", "0.30", "--to", "0.315", "--step", "0.01", "--settle-time",
                                     "0.05", "--average-time", "0.05", "--free-time", "0", "--output",
                                     (dir / "odd").string()});
  ASSERT_EQ(odd.exit_code, 0) << odd.err;
  for (const auto &r : text_rows(dir / "odd" / "runs.csv"))
    EXPECT_EQ(std::vector<std::string>(r.begin(), r.begin() + 4),
              (std::vector<std::string>{r[0], "completed", "3", "3"}));
  fs::remove_all(dir);
}

// A branch that stops early is a result, not only a console line (which
// --quiet silences): runs.csv and summary.md say so, and the exit status is 1.
TEST(Commands, SweepThatStopsEarlySaysSoInItsFiles)
{
  const fs::path dir = fresh_folder("cmd_sweep_stopped");
  const CliRun run   = run_beamslider({"sweep", "--from", "0.30", "--to", "0.32", "--step", "0.01", "--settle-time",
                                       "0.05", "--average-time", "0.05", "--free-time", "0", "--set",
                                       "Contact/Gravity=1e30", "--quiet", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 1) << run.err;
  const auto runs = text_rows(dir / "runs.csv");
  ASSERT_EQ(runs.size(), 2u);
  for (const auto &r : runs)
    {
      EXPECT_EQ(r[1], "unphysical_state") << r[0];
      EXPECT_LT(std::stoi(r[2]), 3) << r[0];
    }
  EXPECT_NE(read_file(dir / "summary.md").find("stopped early (unphysical_state)"), std::string::npos)
    << read_file(dir / "summary.md");
  fs::remove_all(dir);
}

// sweep --against: a ROM sweep compared with a second, identical ROM sweep
// (deterministic) must find no difference (amplitude difference at the
// 10-digit precision pcs.csv is read back with, overlapping F̄_x intervals, the same crossings); against a
// sweep over other positions it is an input error (exit 2) that names the
// mismatch, before any simulation.
TEST(Commands, SweepAgainstAnIdenticalSweepFindsNoDifference)
{
  const fs::path dir = fresh_folder("cmd_sweep_against");
  const std::vector<std::string> sweep = {"sweep", "--from", "0.30", "--to", "0.34", "--step", "0.01", "--settle-time",
                                          "0.1", "--average-time", "0.2", "--free-time", "0"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = sweep;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  CliRun run = run_beamslider(with({"--output", (dir / "a").string()}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  run = run_beamslider(with({"--output", (dir / "b").string(), "--against", (dir / "a").string()}));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(first_line(dir / "b" / "comparison.csv"),
            "direction,x_over_L,amplitude_over_h,other_amplitude_over_h,amplitude_relative_difference,mean_fx_N,"
            "mean_fx_ci95_N,other_mean_fx_N,other_mean_fx_ci95_N,fx_intervals_overlap");
  const auto rows = numeric_rows(dir / "b" / "comparison.csv");
  ASSERT_EQ(rows.size(), 10u); // 5 positions, two directions
  for (const auto &r : rows)
    {
      EXPECT_EQ(r[2], r[3]);  // amplitudes
      EXPECT_LT(r[4], 1e-9);  // their relative difference: the other side is read back at pcs.csv's 10 digits
      EXPECT_EQ(r[5], r[7]);  // F̄_x
      EXPECT_GT(r[6], 0.);    // a real interval
      EXPECT_EQ(r[9], 1.);    // overlapping
    }
  const std::string crossings = read_file(dir / "b" / "crossings.csv");
  EXPECT_TRUE(starts_with(crossings, "sweep,direction,x_over_L,x_low_over_L,x_high_over_L,stable,resolved")) << crossings;

  std::vector<std::string> shifted = sweep;
  shifted[2] = "0.305";
  shifted[4] = "0.345";
  shifted.insert(shifted.end(), {"--output", (dir / "c").string(), "--against", (dir / "a").string()});
  run = run_beamslider(shifted);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("x_C/L = 0.305"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "c" / "pcs.csv")) << "refused before simulating";
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

// The ladder alone: two rungs of 3 members over a short run. Each rung's W₁
// to the reference in ladder.csv is recomputed here from ladder_members.csv
// (equal sizes: W₁ is the mean distance of the sorted samples), and a rung
// name that does not exist is refused with the list of rungs.
TEST(Commands, LadderWritesRungsWhoseDistancesFollowFromTheMembers)
{
  const fs::path dir = fresh_folder("cmd_ladder");
  CliRun run = run_beamslider({"ladder", "--rung", "ROM N=10", "--members", "3", "--end-time", "0.3", "--quiet",
                               "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, "");
  EXPECT_TRUE(starts_with(first_line(dir / "ladder.csv"), "index,rung,family,n_modes,n_elements,integrator,time_step_s"));
  EXPECT_EQ(first_line(dir / "ladder_members.csv"),
            "rung,member,perturbation,status,jump_time_s,final_x_over_L,final_amplitude_over_h,wall_s,outcome");
  // final_x_over_L of each rung's members, and the rung's W₁ column.
  std::map<std::string, std::vector<double>> finals;
  for (const auto &cells : text_rows(dir / "ladder_members.csv"))
    {
      ASSERT_GE(cells.size(), 6u);
      finals[cells[0]].push_back(std::stod(cells[5]));
    }
  ASSERT_EQ(finals.size(), 2u) << "the asked rung and the reference";
  ASSERT_EQ(finals["ROM N=10"].size(), 3u);
  const std::string reference = "FE Δt/2 θ=0.51"; // the scene's FE model: 1e-5 s, θ = 0.51
  ASSERT_EQ(finals[reference].size(), 3u);
  double w1 = 0;
  std::sort(finals["ROM N=10"].begin(), finals["ROM N=10"].end());
  std::sort(finals[reference].begin(), finals[reference].end());
  for (unsigned int k = 0; k < 3; ++k)
    w1 += std::abs(finals["ROM N=10"][k] - finals[reference][k]) / 3;
  bool found = false;
  for (const auto &cells : text_rows(dir / "ladder.csv"))
    if (cells.size() >= 26 && cells[1] == "ROM N=10")
      {
        found = true;
        EXPECT_NEAR(std::stod(cells[25]), w1, 1e-5 + 1e-4 * w1) << "w1_to_reference (6 digits in the CSV)";
      }
  EXPECT_TRUE(found) << "no ROM N=10 row in ladder.csv";
  EXPECT_NE(read_file(dir / "summary.md").find("| ROM N=10 |"), std::string::npos);

  run = run_beamslider({"ladder", "--rung", "ROM N=11", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--rung 'ROM N=11' is not a rung"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("'FE Δt/4'"), std::string::npos) << "the error lists the diagnostic rungs too: " << run.err;

  // The diagnostic rungs belong to the full report: alone they are refused.
  run = run_beamslider({"verify", "--diagnostics", "--output", dir.string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--diagnostics requires --full"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

// verify --section writes only the sections asked for, and says so.
TEST(Commands, VerifySectionWritesOnlyThatSection)
{
  const fs::path dir = fresh_folder("cmd_verify_section");
  const CliRun run   = run_beamslider({"verify", "--section", "1", "--quiet", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string report = read_file(dir / "report.md");
  EXPECT_NE(report.find("\n## 1. "), std::string::npos);
  EXPECT_EQ(report.find("\n## 2. "), std::string::npos);
  EXPECT_NE(report.find("Only section(s) 1"), std::string::npos);
  fs::remove_all(dir);
}

// A verify of one process runs section 8 (the solid strip) in a second
// process beside the others and puts its text in place. That process must
// see the same scene: with the beam stiffened, the 1D beam's f1 in section 8
// (child) equals the FE f1 of section 1 (this verify) on the same mesh, and
// neither process's record is clobbered by the other.
TEST(Commands, VerifyRunsSectionEightBesideTheOthersOnTheSameScene)
{
  const fs::path dir = fresh_folder("cmd_verify_beside");
  const CliRun run   = run_beamslider({"verify", "--section", "1", "--section", "8", "--set",
                                       "Beam/Young's modulus=2.541e11", "--quiet", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string report = read_file(dir / "report.md");
  const std::size_t one = report.find("\n## 1. "), eight = report.find("\n## 8. ");
  ASSERT_NE(one, std::string::npos);
  ASSERT_NE(eight, std::string::npos);
  EXPECT_LT(one, eight);
  EXPECT_EQ(report.find("\n## 8. ", eight + 1), std::string::npos) << "section 8 once";
  EXPECT_NE(report.find("(beside 1–7)"), std::string::npos) << "the wall-time table says where section 8 ran";

  // Section 8's beam f1, printed with 2 decimals.
  const std::string key = "| f1 [Hz] | ";
  const std::size_t at  = report.find(key, eight);
  ASSERT_NE(at, std::string::npos);
  const double f1_beside = std::stod(report.substr(at + key.size()));
  double f1_here         = 0;
  for (const auto &cells : read_csv_cells(dir / "frequency_convergence.csv"))
    if (cells.size() > 3 && cells[0] == "elastic" && cells[1] == "32" && cells[2] == "1")
      f1_here = std::stod(cells[3]);
  ASSERT_GT(f1_here, 0.) << "no elastic 32-element mode 1 in frequency_convergence.csv";
  EXPECT_NEAR(f1_beside, f1_here, 0.006) << "section 8 ran on another scene than section 1";

  // The whole verify's record, not the second process's internal options.
  EXPECT_NE(read_file(dir / "run.txt").find("--section 1 --section 8"), std::string::npos);
  EXPECT_EQ(read_file(dir / "run.txt").find("part-file"), std::string::npos);
  EXPECT_EQ(read_file(dir / "command.prm").find("part-file"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / ".section8.part.md")) << "the part file is removed once read";
  fs::remove_all(dir);
}

// Every output folder holds what repeats its run: parameters.prm (the scene
// after --set and --case) and run.txt (command line, version, revision, instruction set).
// Running simulate on the folder's parameters.prm alone gives the same trace.
TEST(Commands, ARunRepeatsFromItsOutputFolderAlone)
{
  const fs::path dir = fresh_folder("cmd_repeat");
  CliRun run = run_beamslider({"simulate", "--case", "signature-move", "--set", "Contact/Restitution=0.45",
                               "--end-time", "0.15", "--quiet", "--output", (dir / "first").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string record = read_file(dir / "first" / "run.txt");
  EXPECT_NE(record.find("simulate --case signature-move --set Contact/Restitution=0.45 --end-time 0.15"),
            std::string::npos)
    << record;
  EXPECT_NE(record.find("revision:  "), std::string::npos) << record;
  EXPECT_NE(record.find("built for: "), std::string::npos) << record;
  const std::string parameters = read_file(dir / "first" / "parameters.prm");
  const auto restitution       = parameters.find("set Restitution");
  ASSERT_NE(restitution, std::string::npos);
  EXPECT_EQ(parameters.substr(restitution, parameters.find('\n', restitution) - restitution).substr(
              parameters.substr(restitution).find('=') + 2),
            "0.45");

  run = run_beamslider({"simulate", (dir / "first" / "parameters.prm").string(), "--quiet", "--output",
                        (dir / "again").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(read_file(dir / "again" / "trace.csv"), read_file(dir / "first" / "trace.csv"));
  // The same parameters (the first line names the scene: 'parameters' now).
  auto without_first_line = [](const std::string &text) { return text.substr(text.find('\n') + 1); };
  EXPECT_EQ(without_first_line(read_file(dir / "again" / "parameters.prm")),
            without_first_line(read_file(dir / "first" / "parameters.prm")))
    << "the repeated run's scene is the same, parameter for parameter";
  fs::remove_all(dir);
}

// The README's tour runs as written: every line of its block, split into
// words (no shell), with options appended that only shorten it (end time,
// positions, sections) and an output folder. Each must exit 0 and draw the
// picture or write the file the README names on that line.
TEST(Commands, ReadmeTourRunsAsWritten)
{
  const std::string readme = read_file(BEAMSLIDER_SOURCE_DIR "/README.md");
  const auto begin         = readme.find("<!-- tour:");
  const auto end           = readme.find("<!-- end of tour -->");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  std::istringstream block(readme.substr(begin, end - begin));
  const std::map<std::string, std::vector<std::string>> shorter = {
    {"simulate", {"--end-time", "0.2"}},
    {"sweep", {"--from", "0.30", "--to", "0.31", "--step", "0.01", "--settle-time", "0.05", "--average-time", "0.05",
               "--free-time", "0.1"}},
    {"backbone", {"--max-amplitude", "1"}},
    {"verify", {"--section", "1"}}};
  const std::map<std::string, std::string> drawn = {{"modes", "modes.vtu"},         {"coefficients", "summary.md"},
                                                    {"backbone", "backbone.png"}, {"simulate", "trace.png"},
                                                    {"sweep", "pcs.png"},         {"verify", "report.md"}};
  const fs::path dir = fresh_folder("cmd_tour");
  unsigned int n_lines = 0;
  for (std::string line; std::getline(block, line);)
    {
      if (!starts_with(line, "build/beamslider "))
        continue;
      std::istringstream words(line.substr(0, line.find('#')));
      std::vector<std::string> args;
      std::string word;
      words >> word; // build/beamslider
      while (words >> word)
        args.push_back(word);
      ASSERT_FALSE(args.empty()) << line;
      const std::string command = args.front();
      if (shorter.count(command))
        for (const auto &a : shorter.at(command))
          args.push_back(a);
      const fs::path out = dir / std::to_string(n_lines++);
      args.insert(args.end(), {"--quiet", "--output", out.string()});
      const CliRun run = run_beamslider(args);
      EXPECT_EQ(run.exit_code, 0) << line << "\n" << run.err;
      ASSERT_TRUE(drawn.count(command)) << "a tour line with a command this test does not know: " << line;
      EXPECT_NE(line.find(drawn.at(command)), std::string::npos) << "the README line names what it writes: " << line;
      EXPECT_TRUE(fs::exists(out / drawn.at(command))) << line;
    }
  EXPECT_EQ(n_lines, 6u) << "modes, coefficients, backbone, simulate, sweep, verify";
  fs::remove_all(dir);
}

// Each model runs at its own step: the FE at the scene's `FE time step`, the
// ROM at its `Time step` (doc/scenes.md). 0.01 s is 1000 FE steps of 1e-5 s
// and 500 ROM steps of 2e-5 s; the console line states the count.
TEST(Commands, TheFERunsAtTheScenesFETimeStepAndTheROMAtItsTimeStep)
{
  for (const auto &[model, steps] : std::vector<std::pair<std::string, std::string>>{{"fe", "1000"}, {"rom", "500"}})
    {
      const fs::path dir = fresh_folder("model_step_" + model);
      const CliRun run   = run_beamslider({"simulate", "--model", model, "--end-time", "0.01", "--set",
                                           "Time stepping/FE time step=1e-5", "--output", dir.string()});
      ASSERT_EQ(run.exit_code, 0) << run.err;
      EXPECT_NE(run.out.find("(" + steps + " steps)"), std::string::npos) << model << ": " << run.out;
      fs::remove_all(dir);
    }
}

// ensemble and map --model auto run the model the scene's cached ladder
// picks (model_choice.h): the cache here puts N = 7, not the scene's N = 5,
// within the default tolerance (0.005), so the runs must say N = 7. A map
// axis over the discretisation would change the pick and is refused, and
// --tolerance without --model auto is an input error.
TEST(Commands, EnsembleAndMapWithModelAutoRunThePickOfTheCachedLadder)
{
  const fs::path dir   = fresh_folder("cmd_model_auto");
  const fs::path cache = dir / "reports" / "mueller2023" / "model_choice";
  fs::create_directories(cache);
  const beamslider::Scene scene = beamslider::read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm");
  std::ofstream(cache / ("ladder-" + beamslider::scene_content_key(scene) + ".csv"))
    << beamslider::choice_cache_file_text(
         "rung,family,n_modes,static_corrections,ritz_blocks,n_elements,integrator,time_step_s,damped_modes,theta,"
         "reference,cost_units,final_x_median,w1,w1_high,refined_alike\n"
         "ROM N=5 (published),rom,5,0,1,0,explicit,2e-05,0,0.5,0,1250000,0.33,0.09,0.1,1\n"
         "ROM N=7,rom,7,0,1,0,explicit,2e-05,0,0.5,0,1750000,0.40,0.002,0.004,1\n"
         "FE,fe,0,0,1,32,implicit,1e-05,0,0.51,1,1.56e9,0.41,0.001,0.002,1\n");
  const auto in_dir = CliLimits().in_directory(dir.string());

  CliRun run = run_beamslider({"ensemble", "--model", "auto", "--members", "2", "--end-time", "0.3", "--quiet",
                               "--output", (dir / "ensemble").string()},
                              in_dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string ensemble = read_file(dir / "ensemble" / "summary.md");
  EXPECT_NE(ensemble.find("- Model: ROM N=7"), std::string::npos) << ensemble;
  EXPECT_NE(ensemble.find("picked ROM N=7"), std::string::npos) << ensemble;

  run = run_beamslider({"map", "--model", "auto", "--frequency", "124", "--acceleration", "14", "--end-time", "0.3",
                        "--quiet", "--output", (dir / "map").string()},
                       in_dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string map = read_file(dir / "map" / "summary.md");
  EXPECT_NE(map.find("by `--model auto` on the scene without the axes: ROM N=7"), std::string::npos) << map;

  run = run_beamslider({"map", "--model", "auto", "--axis", "Discretisation/Number of modes=5:7:1", "--end-time",
                        "0.3", "--quiet", "--output", (dir / "map-modes").string()},
                       in_dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("'Discretisation/Number of modes'"), std::string::npos) << run.err;
  run = run_beamslider({"ensemble", "--tolerance", "0.01", "--members", "2", "--end-time", "0.3", "--quiet",
                        "--output", (dir / "no-auto").string()},
                       in_dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--tolerance applies to --model auto only"), std::string::npos) << run.err;
  fs::remove_all(dir);
}
