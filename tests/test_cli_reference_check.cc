// The FE reference proves itself on the command line
// (verification/studies/convergence_check.h): on a cheap scene whose FE
// step is known to be too coarse (1e-4 s; over 2 s its end state moves by
// 0.005 and 0.0035 L on the first two halvings), `ensemble --model fe` and
// the ladder never return it silently: they refine it, and say that it did
// not converge, with the evidence in convergence.csv and summary.md.
#include "tests/cli_runner.h"
#include "tests/fresh_folder.h"
#include "tests/read_text_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace beamslider::testing;
namespace fs = std::filesystem;

namespace
{
  const std::string coarse_fe = "Time stepping/FE time step=1e-4";
  // 8 s of CPU on the plain build, ~10 times that under the sanitizers.
  const CliLimits long_enough = CliLimits().timeout(900);

  std::string first_line(const std::string &text) { return text.substr(0, text.find('\n')); }

  // convergence.csv's rows as name → cell, after the header.
  std::vector<std::map<std::string, std::string>> convergence_rows(const fs::path &dir)
  {
    const auto cells = read_csv_cells(dir / "convergence.csv");
    std::vector<std::map<std::string, std::string>> rows;
    for (std::size_t r = 1; r < cells.size(); ++r)
      {
        std::map<std::string, std::string> row;
        for (std::size_t c = 0; c < cells[0].size() && c < cells[r].size(); ++c)
          row[cells[0][c]] = cells[r][c];
        rows.push_back(row);
      }
    return rows;
  }
} // namespace

// The coarse step is refined twice (the stated limit), every halving moves
// the end state by more than the spread and the resolution, so the ensemble
// is the finest step's and the command says it did not converge (exit 3).
TEST(ReferenceCheck, EnsembleOfACoarseFeSaysItDidNotConverge)
{
  const fs::path dir = fresh_folder("reference_check_ensemble");
  const CliRun run = run_beamslider({"ensemble", "--model", "fe", "--members", "4", "--end-time", "2", "--set",
                                     coarse_fe, "--quiet", "--output", dir.string()},
                                   long_enough);
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_EQ(first_line(run.err).rfind("ensemble: the FE in Δt: NOT CONVERGED in Δt down to Δt = 2.5e-05 s", 0), 0u)
    << run.err;
  // run.txt says what happened: every result written, not converged; not
  // "failed … partial, --resume it" (ensemble has no --resume).
  const std::string record = read_file(dir / "run.txt");
  EXPECT_NE(record.find("completed, not converged (exit 3)"), std::string::npos) << record;
  EXPECT_NE(record.find("every result is written"), std::string::npos) << record;
  EXPECT_EQ(record.find("partial"), std::string::npos) << record;
  EXPECT_EQ(record.find("--resume"), std::string::npos) << record;
  // Coarsest first: the witness 2Δt, then the scene's step and its halvings.
  const auto rows = convergence_rows(dir);
  ASSERT_EQ(rows.size(), 4u);
  const double steps[] = {2e-4, 1e-4, 5e-5, 2.5e-5};
  for (std::size_t k = 0; k < 4; ++k)
    {
      EXPECT_DOUBLE_EQ(std::stod(rows[k].at("time_step_s")), steps[k]);
      EXPECT_EQ(rows[k].at("members"), "4");
    }
  EXPECT_EQ(rows[0].at("status"), "witness");
  // The observed order at each judged step, from the medians beside it.
  for (std::size_t k = 1; k < 3; ++k)
    {
      const auto median = [&](const std::size_t i) { return std::stod(rows[i].at("final_x_median")); };
      const double d1 = std::abs(median(k - 1) - median(k)), d2 = std::abs(median(k) - median(k + 1));
      if (std::max(d1, d2) > 1e-3)
        EXPECT_NEAR(std::stod(rows[k].at("observed_order")), std::log2(d1 / d2), 1e-6) << "row " << k;
    }
  for (std::size_t k = 1; k < 3; ++k)
    {
      // The W₁ of a shift is the shift: the medians' difference, give or
      // take the members' scatter.
      const double w1    = std::stod(rows[k].at("w1_to_next"));
      const double shift = std::abs(std::stod(rows[k + 1].at("final_x_median")) - std::stod(rows[k].at("final_x_median")));
      EXPECT_NEAR(w1, shift, 5e-4);
      EXPECT_GT(std::stod(rows[k].at("w1_to_next_low")), std::max(std::stod(rows[k].at("spread")), 1e-3));
      EXPECT_EQ(rows[k].at("distinguishable"), "1");
    }
  EXPECT_EQ(rows[3].at("status"), "not converged");
  const std::string summary = read_file(dir / "summary.md");
  EXPECT_NE(summary.find("dt=2.5e-05; 4 members"), std::string::npos) << "the statistics are the finest step's";
  EXPECT_NE(summary.find("NOT CONVERGED"), std::string::npos);
}

// Asked not to check, the ensemble runs the scene's step alone, exits 0 and
// says that it is unchecked.
TEST(ReferenceCheck, UncheckedEnsembleSaysSo)
{
  const fs::path dir = fresh_folder("reference_check_unchecked");
  const CliRun run   = run_beamslider({"ensemble", "--model", "fe", "--members", "2", "--end-time", "0.2", "--set",
                                       coarse_fe, "--unchecked", "--quiet", "--output", dir.string()},
                                      long_enough);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_FALSE(fs::exists(dir / "convergence.csv"));
  const std::string summary = read_file(dir / "summary.md");
  EXPECT_NE(summary.find("dt=0.0001; 2 members"), std::string::npos);
  EXPECT_NE(summary.find("**Unchecked**"), std::string::npos);
}

// The ladder's reference on the same scene: refined, not converged, said on
// standard error and in the summary, exit 3; its rung in ladder.csv is the
// finest step tried, and the reference row of convergence.csv says so.
TEST(ReferenceCheck, LadderWithACoarseReferenceSaysItDidNotConverge)
{
  const fs::path dir = fresh_folder("reference_check_ladder");
  const CliRun run   = run_beamslider({"ladder", "--rung", "ROM N=10", "--members", "3", "--end-time", "2", "--set",
                                       coarse_fe, "--quiet", "--output", dir.string()},
                                      long_enough);
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_NE(run.err.find("the reference in Δt: NOT CONVERGED"), std::string::npos) << run.err;
  // The reference's three steps and the witness; N=10's own check at half
  // its step beside them.
  std::vector<std::map<std::string, std::string>> rows;
  for (const auto &row : convergence_rows(dir))
    if (row.at("check") == "the reference in Δt")
      rows.push_back(row);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows.front().at("status"), "witness");
  EXPECT_EQ(rows.back().at("status"), "not converged");
  bool reference_found = false;
  const auto ladder    = read_csv_cells(dir / "ladder.csv");
  for (std::size_t c = 0; c < ladder[0].size(); ++c)
    if (ladder[0][c] == "time_step_s")
      for (std::size_t r = 1; r < ladder.size(); ++r)
        if (ladder[r][2] == "fe")
          {
            reference_found = true;
            EXPECT_DOUBLE_EQ(std::stod(ladder[r][c]), 2.5e-5);
          }
  EXPECT_TRUE(reference_found);
  EXPECT_NE(read_file(dir / "summary.md").find("Not every check converged"), std::string::npos);
}
