// The published full report (reports/mueller2023-full/, written by
// `mpirun -n 2 beamslider verify --full` and committed) cannot go stale
// silently: the published ROM's rung of its ladder is run again by the code
// as it is (two of its members, the same starts and end time) and must end
// within the interval the report publishes for that rung. A change of the
// physics, the model or the trace analysis that moves the published model's
// end state fails here; then the report is run again and committed.
#include "scene/scene.h"
#include "verification/report/report_ladder.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/error_ladder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>

using namespace beamslider;

namespace
{
  const std::string report_dir = BEAMSLIDER_SOURCE_DIR "/reports/mueller2023-full";

  // The first row of ladder.csv whose `column` holds `value`, as {column: cell}.
  std::map<std::string, std::string> ladder_row(const std::string &value, const std::string &column = "rung")
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
        if (row[column] == value)
          return row;
      }
    ADD_FAILURE() << "no row with " << column << " = '" << value << "' in " << report_dir << "/ladder.csv";
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

// README quotes the verdict at the scene's own point from the published
// report: each quoted number is the ladder.csv cell rounded to the digits
// the README prints (a new report, or an edit of the README, that lets the
// two disagree fails here).
TEST(PublishedReport, TheReadmeQuotesTheLaddersNumbers)
{
  std::ifstream in(BEAMSLIDER_SOURCE_DIR "/README.md");
  ASSERT_TRUE(in.good());
  std::string readme((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  readme = std::regex_replace(readme, std::regex(R"(\s+)"), " "); // lines wrap anywhere

  const auto published = ladder_row("ROM N=5 (published)"), converged = ladder_row("ROM N=20");
  const auto reference = ladder_row("1", "reference");
  ASSERT_FALSE(reference.empty()) << "no reference rung in ladder.csv";

  // Each quoted number against its cell, to the quoted number's decimals.
  auto expect_quoted = [](const std::string &quoted, const std::string &cell, const std::string &what) {
    const std::size_t point = quoted.find('.');
    const int decimals      = point == std::string::npos ? 0 : static_cast<int>(quoted.size() - point - 1);
    EXPECT_NEAR(std::stod(quoted), std::stod(cell), 0.5 * std::pow(10., -decimals) + 1e-12)
      << what << ": README says " << quoted << ", ladder.csv " << cell;
  };
  // README's two verdict sentences, each number with the ladder.csv cell it quotes.
  using Row = std::map<std::string, std::string>;
  struct Quote
  {
    const Row &row;
    std::string column, what;
  };
  const std::string x = R"(([0-9]+\.[0-9]+))";
  const std::vector<std::pair<std::string, std::vector<Quote>>> sentences = {
    {"the published ROM \\(N = 5\\) ends at " + x + " L \\[" + x + ", " + x + "\\]; the FE reference at " + x +
       " L \\[" + x + ", " + x + "\\]: W₁ = " + x + " L \\[" + x + ", " + x + "\\]",
     {{published, "final_x_median", "published ROM, median"},
      {published, "final_x_min", "published ROM, lowest member"},
      {published, "final_x_max", "published ROM, highest member"},
      {reference, "final_x_median", "FE reference, median"},
      {reference, "final_x_min", "FE reference, lowest member"},
      {reference, "final_x_max", "FE reference, highest member"},
      {published, "w1_to_reference", "published ROM, W1"},
      {published, "w1_low", "published ROM, W1 interval low"},
      {published, "w1_high", "published ROM, W1 interval high"}}},
    {"\\(N = 20\\) ends at " + x + " L \\[" + x + ", " + x + "\\], W₁ = " + x + " \\[" + x + ", " + x + "\\]",
     {{converged, "final_x_median", "ROM N=20, median"},
      {converged, "final_x_min", "ROM N=20, lowest member"},
      {converged, "final_x_max", "ROM N=20, highest member"},
      {converged, "w1_to_reference", "ROM N=20, W1"},
      {converged, "w1_low", "ROM N=20, W1 interval low"},
      {converged, "w1_high", "ROM N=20, W1 interval high"}}}};
  for (const auto &[pattern, quotes] : sentences)
    {
      std::smatch m;
      ASSERT_TRUE(std::regex_search(readme, m, std::regex(pattern))) << "README's verdict sentence changed its form: "
                                                                     << pattern;
      for (std::size_t i = 0; i < quotes.size(); ++i)
        expect_quoted(m[i + 1], quotes[i].row.at(quotes[i].column), quotes[i].what);
    }
}
