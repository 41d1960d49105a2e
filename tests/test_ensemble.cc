// Ensembles (verification/studies/ensemble.h): members are reproducible and really
// differ; order statistics and two-sample distances against values worked
// out by hand.
#include "io/csv_writer.h"
#include "io/input_file.h"
#include "verification/report/member_files.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/member_runs.h"
#include "verification/studies/simulation_cases.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace beamslider;

namespace
{
  const std::string mueller = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

  EnsembleSettings rom_settings(const Scene &scene, const unsigned int members, const double perturbation)
  {
    EnsembleSettings s;
    s.model.family    = "rom";
    s.model.n_modes   = scene.discretisation.n_modes;
    s.model.time_step = scene.time_stepping.time_step;
    s.n_members       = members;
    s.perturbation    = perturbation;
    return s;
  }
} // namespace

// Member m of two ensembles with the same settings is the same run to the
// bit (threads or not); members 0 and 1 start 1e-9 L apart and the rattling
// makes that visible within the first second; the perturbation is what the
// settings say.
TEST(Ensemble, MembersAreReproducibleAndActuallyDiffer)
{
  Scene scene                    = read_scene(mueller);
  scene.time_stepping.end_time   = 1.5;
  const auto first  = run_ensemble(scene, rom_settings(scene, 2, 1e-9));
  const auto second = run_ensemble(scene, rom_settings(scene, 2, 1e-9));
  ASSERT_EQ(first.size(), 2u);
  for (unsigned int m = 0; m < 2; ++m)
    {
      EXPECT_DOUBLE_EQ(first[m].perturbation, m * 1e-9);
      ASSERT_EQ(first[m].periods.size(), second[m].periods.size());
      for (std::size_t k = 0; k < first[m].periods.size(); ++k)
        {
          EXPECT_EQ(first[m].periods[k].slider_x_over_L, second[m].periods[k].slider_x_over_L) << m << ", " << k;
          EXPECT_EQ(first[m].periods[k].amplitude_over_h, second[m].periods[k].amplitude_over_h) << m << ", " << k;
        }
    }
  // The members part: far more than the 1e-9 they started apart.
  double largest = 0;
  for (std::size_t k = 0; k < first[0].periods.size(); ++k)
    largest = std::max(largest, std::abs(first[0].periods[k].amplitude_over_h - first[1].periods[k].amplitude_over_h));
  EXPECT_GT(largest, 1e-3) << "members 0 and 1 did not part";
}

// A member through its record (its cells, which member_runs.csv holds as one
// CSV line and MPI carries length-prefixed) comes back bit for bit: the run's figures, the periods'
// start, end, x_C/L and amplitude, and so the trace analysis recomputed from
// them. A line cut short (a kill during the write) is refused.
TEST(Ensemble, MemberRecordReadsBackBitForBit)
{
  Scene scene                  = read_scene(mueller);
  scene.time_stepping.end_time = 1.0;
  const EnsembleMember m = run_member(scene, rom_settings(scene, 1, 0).model, 3, 1e-9);
  ASSERT_GT(m.periods.size(), 20u);
  const std::string line = CsvWriter::line(member_record(2, "a, \"rung\"", m));
  std::size_t group = 0;
  std::string name;
  const EnsembleMember back = member_from_record(CsvWriter::cells(line), trace_thresholds(scene), group, name);
  EXPECT_EQ(group, 2u);
  EXPECT_EQ(name, "a, \"rung\"");
  EXPECT_EQ(back.index, 3u);
  EXPECT_EQ(back.perturbation, 3 * 1e-9);
  EXPECT_EQ(back.result.status, m.result.status);
  EXPECT_EQ(back.result.t_end, m.result.t_end);
  EXPECT_EQ(back.result.slider_x_over_L, m.result.slider_x_over_L);
  EXPECT_EQ(back.result.n_steps, m.result.n_steps);
  EXPECT_EQ(back.wall_seconds, m.wall_seconds);
  ASSERT_EQ(back.periods.size(), m.periods.size());
  for (std::size_t k = 0; k < m.periods.size(); ++k)
    {
      EXPECT_EQ(back.periods[k].index, m.periods[k].index);
      EXPECT_EQ(back.periods[k].t_start, m.periods[k].t_start);
      EXPECT_EQ(back.periods[k].t_end, m.periods[k].t_end);
      EXPECT_EQ(back.periods[k].slider_x_over_L, m.periods[k].slider_x_over_L);
      EXPECT_EQ(back.periods[k].amplitude_over_h, m.periods[k].amplitude_over_h);
    }
  EXPECT_EQ(back.analysis.final_position, m.analysis.final_position);
  EXPECT_EQ(back.analysis.final_amplitude, m.analysis.final_amplitude);
  EXPECT_EQ(back.analysis.jumped, m.analysis.jumped);
  EXPECT_EQ(back.analysis.outcome, m.analysis.outcome);
  for (const std::size_t cut : {line.size() - 1, line.size() / 2, line.size() / 10})
    EXPECT_THROW(member_from_record(CsvWriter::cells(line.substr(0, cut)), trace_thresholds(scene), group, name),
                 std::invalid_argument)
      << cut;
}

// The runs of several ensembles longest first by the stated cost model: an
// FE group before a ROM group at a smaller step before the published ROM;
// within a group, by member index.
TEST(Ensemble, RunsAreHandedOutLongestFirst)
{
  Scene scene                  = read_scene(mueller);
  scene.time_stepping.end_time = 1.0;
  ModelSetting rom = rom_settings(scene, 1, 0).model, fine = rom, fe = rom;
  fine.time_step /= 4;
  fe.family     = "fe";
  fe.n_elements = scene.discretisation.n_elements;
  const std::vector<MemberGroup> groups = {{"rom", scene, rom, 2, 1e-9}, {"fe", scene, fe, 2, 1e-9},
                                           {"fine", scene, fine, 1, 1e-9}};
  EXPECT_EQ(n_runs(groups), 5u);
  EXPECT_EQ(group_and_member(groups, 3), (std::pair<std::size_t, unsigned int>{1, 1}));
  EXPECT_EQ(longest_first(groups), (std::vector<std::size_t>{2, 3, 4, 0, 1}));
}

TEST(EnsembleStatistics, QuartilesOfAConstructedSampleByHand)
{
  // Sorted: 1 2 3 4 10. Type-7 quantiles: q(p) = x[⌊p(n−1)⌋] + frac · (next − it).
  const std::vector<double> sample = {4, 1, 10, 3, 2};
  const OutcomeStatistics s        = statistics("x", sample);
  EXPECT_EQ(s.n, 5u);
  EXPECT_DOUBLE_EQ(s.median, 3.);
  EXPECT_DOUBLE_EQ(s.q1, 2.);
  EXPECT_DOUBLE_EQ(s.q3, 4.);
  EXPECT_DOUBLE_EQ(s.min, 1.);
  EXPECT_DOUBLE_EQ(s.max, 10.);
  EXPECT_DOUBLE_EQ(quantile({1, 2, 3, 4}, 0.5), 2.5);
  EXPECT_TRUE(std::isnan(statistics("none", {}).median));
}

TEST(EnsembleComparison, DistancesOfConstructedSamples)
{
  const std::vector<double> a = {0.30, 0.31, 0.32, 0.33, 0.34, 0.35, 0.36, 0.37};
  std::vector<double> shifted = a;
  for (auto &x : shifted)
    x += 0.1; // B = A + s: W₁ = |s| exactly, and disjoint supports give KS D = 1
  EXPECT_NEAR(wasserstein_1(a, shifted), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(kolmogorov_smirnov(a, shifted), 1.);
  EXPECT_NEAR(wasserstein_1(a, a), 0., 1e-15);
  EXPECT_DOUBLE_EQ(kolmogorov_smirnov(a, a), 0.);
  // {0, 1} against {0}: half the mass moves by 1.
  EXPECT_NEAR(wasserstein_1({0., 1.}, {0.}), 0.5, 1e-15);
  EXPECT_DOUBLE_EQ(kolmogorov_smirnov({0., 1.}, {0.}), 0.5);

  const SampleComparison far = compare_samples(a, shifted);
  EXPECT_NEAR(far.shift, 0.1, 1e-12);
  EXPECT_NEAR(far.spread, 0.04, 1e-12) << "halves {0.30..0.33} and {0.34..0.37} are 0.04 apart";
  EXPECT_TRUE(far.distinguishable) << far.interval_low << " vs scatter " << far.spread;
  EXPECT_LE(far.interval_low, 0.1 + 1e-12);
  EXPECT_GE(far.interval_high, 0.1 - 1e-12);
  // Overlapping supports: B = A + 0.05 leaves 3 of 8 points in common ranks,
  // D = 5/8.
  std::vector<double> overlap = a;
  for (auto &x : overlap)
    x += 0.05;
  EXPECT_DOUBLE_EQ(kolmogorov_smirnov(a, overlap), 0.625);
  // A small shift inside the ensembles' own scatter is not resolved.
  std::vector<double> near = a;
  for (auto &x : near)
    x += 0.002;
  EXPECT_FALSE(compare_samples(a, near).distinguishable);
}

// The store shared across studies (member_files.h, share_fe_members): an FE
// member one study ran is taken by another that asks for the same member
// under another group name, and gives the same numbers to the bit; a member
// of other settings (another Δt) is not taken; a damaged file is not used
// (its member runs again, with the same numbers); ROM members are not kept.
TEST(SharedMembers, AnFEMemberRunOnceIsTakenByAnotherStudyWithTheSameSettingsOnly)
{
  namespace fs         = std::filesystem;
  const fs::path store = fs::temp_directory_path() / ("beamslider-shared-" + std::to_string(::getpid()));
  fs::remove_all(store);
  Scene scene                  = read_scene(mueller);
  scene.time_stepping.end_time = 0.05;
  ModelSetting fe              = scene_model(scene, "fe");
  ModelSetting rom             = scene_model(scene, "rom");
  ModelSetting fe_half         = fe;
  fe_half.time_step /= 2;

  // The members taken from the shared store (not those a resumed study
  // reads back from its own member_runs.csv: none here).
  auto run = [&](const std::vector<MemberGroup> &groups, std::size_t &n_taken) {
    MemberRunsSettings settings;
    settings.n_threads = 1;
    share_fe_members(settings, store.string());
    const std::size_t before = shared_member_counts().reused;
    auto members             = run_member_groups(groups, settings);
    n_taken                  = shared_member_counts().reused - before;
    return members;
  };
  auto same = [](const EnsembleMember &a, const EnsembleMember &b) {
    if (a.periods.size() != b.periods.size() || a.result.slider_x_over_L != b.result.slider_x_over_L)
      return false;
    for (std::size_t k = 0; k < a.periods.size(); ++k)
      if (a.periods[k].slider_x_over_L != b.periods[k].slider_x_over_L ||
          a.periods[k].amplitude_over_h != b.periods[k].amplitude_over_h)
        return false;
    return true;
  };
  auto files = [&] {
    std::size_t n = 0;
    if (fs::exists(store))
      for (const auto &e : fs::recursive_directory_iterator(store))
        n += e.is_regular_file();
    return n;
  };

  std::size_t taken = 0;
  const auto first = run({{"ladder reference", scene, fe, 2, 1e-9}, {"rom", scene, rom, 1, 1e-9}}, taken);
  EXPECT_EQ(taken, 0u);
  EXPECT_EQ(files(), 2u); // the two FE members, not the ROM's
  const auto second = run({{"region reference", scene, fe, 2, 1e-9}}, taken);
  EXPECT_EQ(taken, 2u);
  ASSERT_EQ(second.size(), 1u);
  ASSERT_EQ(second[0].size(), 2u);
  EXPECT_TRUE(same(first[0][0], second[0][0]));
  EXPECT_TRUE(same(first[0][1], second[0][1]));
  EXPECT_NE(shared_member_counts().folder.find("fe_members"), std::string::npos);

  run({{"region reference", scene, fe_half, 1, 1e-9}}, taken);
  EXPECT_EQ(taken, 0u) << "a member of another time step was taken";
  EXPECT_EQ(files(), 3u);

  // A changed key line: the file is not used, its member runs again.
  for (const auto &e : fs::recursive_directory_iterator(store))
    if (e.is_regular_file())
      {
        const std::string text = read_text_file(e.path().string());
        if (text.find("; member 1") == std::string::npos) // only the first group has a member 1
          continue;
        std::string changed = text;
        changed.replace(changed.find("; member 1"), 10, "; member 7");
        std::ofstream(e.path(), std::ios::trunc) << changed;
      }
  const auto third = run({{"cases reference", scene, fe, 2, 1e-9}}, taken);
  EXPECT_EQ(taken, 1u);
  EXPECT_TRUE(same(first[0][1], third[0][1]));
  fs::remove_all(store);
}
