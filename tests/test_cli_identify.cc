// `beamslider identify` end to end on one fact and two candidates: the
// files it writes, a row per candidate with the fact's score, and the input
// errors it refuses before any run.
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

using namespace beamslider::testing;

TEST(CliIdentify, OneFactTwoCandidates)
{
  const auto dir   = fresh_folder("identify");
  const CliRun run = run_beamslider({"identify", "system1", "--fact", "fig11", "--axis",
                                     "Contact/Restitution=0.3:0.6:0.3", "--quiet", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char *file : {"identification.csv", "verdicts.csv", "facts.csv", "summary.md", "fig11/map.csv"})
    EXPECT_TRUE(std::filesystem::exists(dir / file)) << file;
  std::istringstream table(read_file(dir / "identification.csv"));
  std::string header, line;
  std::getline(table, header);
  EXPECT_EQ(header, "contact_restitution,score_fig11,pass_fig11,total");
  unsigned int rows = 0;
  while (std::getline(table, line))
    ++rows;
  EXPECT_EQ(rows, 2u);
  const std::string summary = read_file(dir / "summary.md");
  EXPECT_NE(summary.find("Fig. 11: tight fit"), std::string::npos) << summary;
  EXPECT_NE(summary.find("Best candidate"), std::string::npos);
}

TEST(CliIdentify, RefusesBadInputBeforeAnyRun)
{
  const auto dir = fresh_folder("identify_errors");
  const CliRun no_axis = run_beamslider({"identify", "system1", "--output", dir.string()});
  EXPECT_EQ(no_axis.exit_code, 2);
  EXPECT_NE(no_axis.err.find("no unknown given"), std::string::npos) << no_axis.err;
  const CliRun bad_fact =
    run_beamslider({"identify", "system1", "--fact", "fig99", "--axis", "Contact/Restitution=0.5", "--output", dir.string()});
  EXPECT_EQ(bad_fact.exit_code, 2);
  EXPECT_NE(bad_fact.err.find("fig10"), std::string::npos) << "names the known facts: " << bad_fact.err;
  // A candidate outside the allowed range is refused before any run.
  const CliRun bad_value =
    run_beamslider({"identify", "system1", "--axis", "Contact/Restitution=0.5:1.5:0.5", "--output", dir.string()});
  EXPECT_EQ(bad_value.exit_code, 2) << bad_value.err;
}

// Report section 7 judges the seed's System 1 facts; on another scene it
// says that they do not apply (and runs nothing).
TEST(CliIdentify, ReportSectionSevenOnlyForSystem1)
{
  const auto dir   = fresh_folder("identify_report");
  const CliRun run = run_beamslider({"verify", "mueller2023", "--section", "7", "--quiet", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string report = read_file(dir / "report.md");
  EXPECT_NE(report.find("## 7. The seed's System 1 facts"), std::string::npos) << report;
  EXPECT_NE(report.find("apply to the scene `system1` only"), std::string::npos) << report;
}
