// The published full report (reports/mueller2023-full/, written by
// `mpirun -n 2 beamslider verify --full` and committed) cannot go stale
// silently: the published ROM's rung of its ladder is run again by the code
// as it is (two of its members, the same starts and end time) and must end
// within the interval the report publishes for that rung. A change of the
// physics, the model or the trace analysis that moves the published model's
// end state fails here; then the report is run again and committed.
#include "meshes/scene.h"
#include "verification/report/report_ladder.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/error_ladder.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace beamslider;

namespace
{
  const std::string report_dir = BEAMSLIDER_SOURCE_DIR "/reports/mueller2023-full";

  // The row of ladder.csv whose `rung` is `name`, as {column: cell}.
  std::map<std::string, std::string> ladder_row(const std::string &name)
  {
    std::ifstream in(report_dir + "/ladder.csv");
    EXPECT_TRUE(in.good()) << "the published report's ladder.csv is missing";
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = CsvWriter::cells(line);
    while (std::getline(in, line))
      {
        const std::vector<std::string> cells = CsvWriter::cells(line);
        std::map<std::string, std::string> row;
        for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i)
          row[header[i]] = cells[i];
        if (row["rung"] == name)
          return row;
      }
    ADD_FAILURE() << "no rung '" << name << "' in " << report_dir << "/ladder.csv";
    return {};
  }
} // namespace

TEST(PublishedReport, ThePublishedROMStillEndsWithinItsPublishedInterval)
{
  const Scene scene = read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm");
  const ReportLadder full = report_ladder(scene, true, false);
  const LadderRung &published = full.rungs.front();
  ASSERT_NE(published.name.find("published"), std::string::npos) << published.name;

  const auto row = ladder_row(published.name);
  ASSERT_FALSE(row.empty());
  ASSERT_EQ(std::stod(row.at("time_step_s")), published.model.time_step);
  ASSERT_EQ(std::stoul(row.at("members")), full.settings.members);
  const double low = std::stod(row.at("final_x_min")), high = std::stod(row.at("final_x_max"));
  ASSERT_LT(low, high);

  // Members 0 and 1 of the published rung: the same runs as the report's first two.
  const std::vector<MemberGroup> groups = ladder_groups(scene, {published}, full.settings.end_time, 2);
  const std::vector<std::vector<EnsembleMember>> members = run_groups_in_threads(groups);
  const std::vector<double> finals = outcome_samples(members.front()).final_position;
  ASSERT_EQ(finals.size(), 2u);
  // The CSV keeps 6 significant digits: the interval is widened by that much only.
  const double rounding = 1e-6 * high;
  for (const double x : finals)
    {
      EXPECT_GE(x, low - rounding) << "the published ROM now ends below the published report's interval: run "
                                      "`mpirun -n 2 build/beamslider verify --full --output reports/mueller2023-full` "
                                      "and commit it";
      EXPECT_LE(x, high + rounding) << "the published ROM now ends above the published report's interval";
    }
}
