// The verdict across the signature-move region (verification/studies/
// region_verdict.h): the points, and how the study splits one list of
// member runs back into a checked ladder per point. The members come from a
// runner that fabricates end states from the group's model and point, so
// that every number the study returns can be predicted.
#include "io/csv_writer.h"
#include "tests/fresh_folder.h"
#include "verification/report/report_region.h"
#include "verification/studies/region_verdict.h"
#include "verification/studies/simulation_cases.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>

using namespace beamslider;

namespace
{
  const std::string mueller = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

  std::vector<EnsembleMember> ending_at(const double centre, const unsigned int n)
  {
    std::vector<EnsembleMember> members(n);
    for (unsigned int m = 0; m < n; ++m)
      {
        members[m].index                    = m;
        members[m].analysis.valid           = true;
        members[m].analysis.final_position  = centre + 1e-4 * m;
        members[m].analysis.final_amplitude = 1.;
      }
    return members;
  }
} // namespace

// Six points, the scene's own among them, every one a valid scene.
TEST(RegionVerdict, SixPointsAroundTheScenesExcitation)
{
  const Scene scene                        = read_scene(mueller);
  const std::vector<OperatingPoint> points = signature_move_region(scene);
  ASSERT_EQ(points.size(), 6u);
  bool own = false;
  for (const OperatingPoint &p : points)
    {
      own = own || (p.frequency_hz == scene.excitation.frequency_hz &&
                    p.acceleration_m_s2 == scene.excitation.acceleration_amplitude);
      EXPECT_NO_THROW(at_point(scene, p)) << p.label();
    }
  EXPECT_TRUE(own);
  EXPECT_EQ(points.front().label(), "116 Hz / 12 m/s²");
}

// At the point whose FE moves on the first halving (the first point), the
// reference becomes Δt/2; elsewhere it stays at the scene's step. Every
// ROM's W₁ to its point's reference is the fabricated shift.
TEST(RegionVerdict, EachPointGetsItsOwnCheckedReference)
{
  Scene scene                                    = read_scene(mueller);
  const std::vector<OperatingPoint> points        = signature_move_region(scene);
  const double fe_dt                              = scene.time_stepping.fe_time_step;
  // End states: ROMs at 0.30 + 0.01·N/5 below N = 20, at 0.3995 from
  // there (converged in N); the FE at 0.40, except at the first point
  // where Δt and the witness 2Δt end at 0.38.
  const auto rom_end = [](const unsigned int n) { return n < 20 ? 0.30 + 0.01 * n / 5. : 0.3995; };
  const auto end_state = [&](const MemberGroup &g) {
    const bool first_point = g.scene.excitation.frequency_hz == points[0].frequency_hz &&
                             g.scene.excitation.acceleration_amplitude == points[0].acceleration_m_s2;
    if (g.model.family == "fe")
      return first_point && g.model.time_step >= fe_dt ? 0.38 : 0.40;
    return rom_end(g.model.n_modes);
  };
  std::vector<std::size_t> round_sizes;
  const MemberGroupRunner fabricate = [&](const std::vector<MemberGroup> &groups) {
    round_sizes.push_back(groups.size());
    std::vector<std::vector<EnsembleMember>> out;
    for (const MemberGroup &g : groups)
      out.push_back(ending_at(end_state(g), g.n_members));
    return out;
  };
  const RegionStudy study = run_region(scene, points, 40., 4, fabricate);
  ASSERT_EQ(study.ladders.size(), points.size());
  // One list: 6 rungs (published, N = 10, 20, the front's N = 15 and
  // 6 + 4 corrections, the reference) and 7 first trials of the checks per
  // point (the reference at half its step and its witness at twice it, four
  // ROMs at half their step, N = 20 against 30); then Δt/4 at the first
  // point alone.
  EXPECT_EQ(round_sizes, (std::vector<std::size_t>{13 * points.size(), 1}));
  for (std::size_t p = 0; p < points.size(); ++p)
    {
      const LadderStudy &l = study.ladders[p];
      ASSERT_EQ(l.checks.size(), 6u);
      EXPECT_TRUE(l.proven());
      const LadderRungResult &ref = l.rungs[l.reference];
      EXPECT_EQ(ref.rung.model.family, "fe");
      EXPECT_DOUBLE_EQ(ref.rung.model.time_step, p == 0 ? fe_dt / 2 : fe_dt) << points[p].label();
      EXPECT_NEAR(ref.final_position.median, 0.40 + 1.5e-4, 1e-12);
      for (std::size_t i = 0; i < l.rungs.size(); ++i)
        {
          if (i != l.reference)
            EXPECT_NEAR(l.rungs[i].position_to_reference.wasserstein, 0.40 - rom_end(l.rungs[i].rung.model.n_modes),
                        1e-12);
        }
    }
}

// The region's summary names the points where more modes do not bring the
// ROM to the FE: N = 20 (converged in N) and its check, N = 30, both end
// apart from the reference. At the second point every ROM with N ≥ 20 ends
// at 0.35 against the FE's 0.40; elsewhere they end with the FE. When N = 30
// does reach the FE there, the sentence is not written.
TEST(RegionVerdict, TheSummaryNamesWhereMoreModesDoNotReachTheFE)
{
  const Scene scene                        = read_scene(mueller);
  const std::vector<OperatingPoint> points = signature_move_region(scene);
  const auto summary_when = [&](const unsigned int modes_that_reach_the_fe) {
    const MemberGroupRunner fabricate = [&](const std::vector<MemberGroup> &groups) {
      std::vector<std::vector<EnsembleMember>> out;
      for (const MemberGroup &g : groups)
        {
          const bool second = g.scene.excitation.frequency_hz == points[1].frequency_hz &&
                              g.scene.excitation.acceleration_amplitude == points[1].acceleration_m_s2;
          const unsigned int n = g.model.n_modes;
          double end = 0.40;
          if (g.model.family == "rom")
            end = n < 20 ? 0.30 : (second && n < modes_that_reach_the_fe ? 0.35 : 0.40);
          out.push_back(ending_at(end, g.n_members));
        }
      return out;
    };
    return region_summary(run_region(scene, points, 40., 4, fabricate));
  };
  const std::string never = summary_when(1000);
  EXPECT_NE(never.find(" At " + points[1].label() + " (W₁ 0.0500 and 0.0500 L), ROM N=20, converged in N, and "
                       "ROM N=30, its check, both end apart from the reference: more modes do not bring the ROM to "
                       "the FE there"),
            std::string::npos)
    << never;
  for (std::size_t p = 0; p < points.size(); ++p)
    {
      if (p != 1)
        EXPECT_EQ(never.find(points[p].label()), std::string::npos) << never;
    }
  EXPECT_NE(never.find("no reduced model tried meets the reference at every point."), std::string::npos) << never;

  const std::string at_thirty = summary_when(30);
  EXPECT_EQ(at_thirty.find("more modes do not bring"), std::string::npos) << at_thirty;
}

// The published cases as sites: the six mueller2023 cases (not the
// ablations), each the scene `simulate --case` reads, at its own end time;
// each runs the published ROM, the quick ladder's two front candidates
// (N = 15 and the full front's pick, 6 + 4 static corrections) and the FE
// reference last. One list of member runs serves them all, every group at
// its case's end time, and each case gets its own checked ladder.
TEST(RegionVerdict, ThePublishedCasesRunAsSitesAtTheirOwnEndTimes)
{
  const std::vector<StudySite> sites = published_case_sites(mueller, {});
  ASSERT_EQ(sites.size(), 6u);
  std::map<std::string, double> end_of;
  for (const SimulationCase &c : simulation_cases())
    end_of[c.name] = c.end_time;
  for (const StudySite &s : sites)
    {
      ASSERT_TRUE(end_of.count(s.label)) << s.label;
      EXPECT_EQ(s.scene.time_stepping.end_time, end_of[s.label]) << s.label;
      EXPECT_TRUE(s.label.rfind("signature-move", 0) == 0 || s.label.rfind("trivial-adaption", 0) == 0 ||
                  s.label == "self-damping" || s.label == "relaxation-oscillation")
        << s.label << " is an ablation";
    }
  EXPECT_EQ(sites.back().label, "signature-move-106");
  EXPECT_EQ(sites.back().scene.excitation.frequency_hz, 106.);
  EXPECT_EQ(sites.back().scene.initial.slider_position_over_L, 0.4);

  std::size_t reference = 0;
  const Scene &scene                  = sites.front().scene;
  const std::vector<LadderRung> rungs = case_rungs(scene, reference);
  ASSERT_EQ(rungs.size(), 4u);
  ASSERT_EQ(reference, 3u);
  EXPECT_EQ(rungs[0].model.n_modes, scene.discretisation.n_modes);
  EXPECT_EQ(rungs[0].model.time_step, scene.time_stepping.time_step);
  EXPECT_TRUE(rungs[1].front_candidate && rungs[2].front_candidate);
  EXPECT_EQ(rungs[1].model.n_modes, 15u);
  EXPECT_EQ(rungs[2].model.n_modes, 6u);
  EXPECT_EQ(rungs[2].model.n_static_corrections, 4u);
  EXPECT_EQ(rungs[3].model.family, "fe");

  // Two sites of different end times through one list, the FE at 0.40 and
  // every ROM at 0.35: each ladder its own, every group at its site's end.
  const std::vector<StudySite> two = {sites[0], sites[2]}; // 60 s and 120 s
  ASSERT_NE(two[0].scene.time_stepping.end_time, two[1].scene.time_stepping.end_time);
  unsigned int wrong_end = 0;
  const auto fabricate   = [&](const std::vector<MemberGroup> &groups) {
    std::vector<std::vector<EnsembleMember>> out;
    for (const MemberGroup &g : groups)
      {
        const bool second = g.name.rfind(two[1].label, 0) == 0;
        wrong_end += g.scene.time_stepping.end_time != two[second ? 1 : 0].scene.time_stepping.end_time;
        out.push_back(ending_at(g.model.family == "fe" ? 0.40 : 0.35, g.n_members));
      }
    return out;
  };
  const std::vector<LadderStudy> ladders = run_sites(two, case_rungs, 4, fabricate);
  EXPECT_EQ(wrong_end, 0u);
  ASSERT_EQ(ladders.size(), 2u);
  for (const LadderStudy &l : ladders)
    {
      EXPECT_TRUE(l.proven());
      EXPECT_EQ(l.rungs[l.reference].rung.model.family, "fe");
      EXPECT_NEAR(l.rungs[0].position_to_reference.wasserstein, 0.05, 1e-12);
    }
}

// The published cases' report, run for real on short runs (0.3 s, 2
// members): every case has its checked reference and a row per model in
// published_cases.csv, and the count the Markdown gives per model ("N of
// 6") is the number of cases in that file whose majority class is the
// reference's and that did not move at Δt/2.
TEST(RegionVerdict, ThePublishedCasesCountTheClassesTheirFileHolds)
{
  const std::filesystem::path dir = beamslider::testing::fresh_folder("published_cases");
  const std::vector<StudySite> sites = published_case_sites(mueller, {"Time stepping/End time=0.3"});
  RegionRunSettings settings;
  settings.members       = 4; // 4 of 4 in one class decide it (2 of 2 would grow to 6)
  const std::string md   = run_and_describe_cases(dir.string(), sites, settings);

  std::ifstream file(dir / "published_cases.csv");
  std::string line;
  std::getline(file, line);
  const std::vector<std::string> header = CsvWriter::cells(line);
  const auto column = [&](const std::string &name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t c_case = column("case"), c_model = column("model"), c_majority = column("majority_class"),
                    c_moved = column("moves_at_half_step"), c_reference = column("reference_convergence");
  ASSERT_LT(c_reference, header.size());
  std::map<std::string, std::vector<std::vector<std::string>>> by_case;
  while (std::getline(file, line))
    {
      const std::vector<std::string> cells = CsvWriter::cells(line);
      ASSERT_EQ(cells.size(), header.size()) << line;
      by_case[cells[c_case]].push_back(cells);
    }
  ASSERT_EQ(by_case.size(), sites.size());
  std::map<std::string, unsigned int> held;
  std::vector<std::string> models;
  for (const auto &[name, rows] : by_case)
    {
      // The models (published ROM, N = 15, 6 + 4), then the reference.
      ASSERT_EQ(rows.size(), 4u) << name;
      const std::vector<std::string> &reference = rows.back();
      EXPECT_FALSE(reference[c_reference].empty()) << name;
      for (std::size_t i = 0; i + 1 < rows.size(); ++i)
        {
          EXPECT_TRUE(rows[i][c_reference].empty()) << name;
          held[rows[i][c_model]] += rows[i][c_majority] == reference[c_majority] && rows[i][c_moved] == "0";
          if (models.size() < rows.size() - 1)
            models.push_back(rows[i][c_model]);
        }
      EXPECT_NE(md.find("| `" + name + "` |"), std::string::npos) << name;
    }
  for (const std::string &m : models)
    EXPECT_NE(md.find(" " + m + ": " + std::to_string(held[m]) + " of " + std::to_string(sites.size())),
              std::string::npos)
      << m << " takes " << held[m] << " cases by the file:\n"
      << md;
  std::filesystem::remove_all(dir);
}

// A model is alike with the reference only when its majority class is the
// reference's and its end positions end alike. Members that end near the
// reference's but mostly in another class (120/9: the FE's relax, most of
// N = 20's make the signature move) are not alike; an even split decides no
// class; a model whose end positions part is not alike in the same class.
TEST(RegionVerdict, AlikeNeedsTheReferencesMajorityClassAndItsEndState)
{
  const auto members = [](const double centre, const std::vector<AdaptationClass> &outcomes) {
    std::vector<EnsembleMember> m = ending_at(centre, static_cast<unsigned int>(outcomes.size()));
    for (std::size_t i = 0; i < m.size(); ++i)
      m[i].analysis.outcome = outcomes[i];
    return m;
  };
  const auto sig = AdaptationClass::signature_move, none = AdaptationClass::no_adaptation;
  const std::vector<EnsembleMember> reference = members(0.380, {none, none, none, none});
  const std::vector<EnsembleMember> same      = members(0.3803, {none, none, none, sig});
  const std::vector<EnsembleMember> other     = members(0.3803, {sig, sig, sig, none});
  const std::vector<EnsembleMember> split     = members(0.3803, {sig, sig, none, none});
  const std::vector<EnsembleMember> apart     = members(0.420, {none, none, none, none});
  const auto final_positions = [](const std::vector<EnsembleMember> &ms) {
    return outcome_samples(ms).final_position;
  };
  const auto alike = [&](const std::vector<EnsembleMember> &model) {
    return alike_with_reference(compare_samples(final_positions(model), final_positions(reference)),
                                class_counts(model), class_counts(reference));
  };
  // Every close model ends alike by its end positions alone ...
  for (const auto *m : {&same, &other, &split})
    EXPECT_TRUE(ends_alike(compare_samples(final_positions(*m), final_positions(reference))));
  // ... but only the one in the reference's class is alike.
  EXPECT_TRUE(alike(same));
  EXPECT_FALSE(alike(other));
  EXPECT_FALSE(alike(split));
  EXPECT_FALSE(alike(apart));
  EXPECT_EQ(majority_class(class_counts(split)), "split");
  EXPECT_EQ(majority_class(class_counts(other)), to_string(sig));
  EXPECT_EQ(majority_class({}), "–");
  // A reference split evenly decides no class: nothing is alike with it.
  EXPECT_FALSE(alike_with_reference(compare_samples(final_positions(same), final_positions(split)),
                                    class_counts(same), class_counts(split)));
}

// The sign test's p-values against the binomial sums written out:
// P(X ≥ k | n, ½) = Σ_{j ≥ k} C(n, j) / 2ⁿ.
TEST(RegionVerdict, AMajorityClassIsDecidedByTheSignTest)
{
  const std::string a = "signature move", b = "no adaptation";
  EXPECT_DOUBLE_EQ(majority_p_value({{a, 4}}), 1. / 16);
  EXPECT_DOUBLE_EQ(majority_p_value({{a, 3}, {b, 1}}), (4. + 1) / 16);
  EXPECT_DOUBLE_EQ(majority_p_value({{a, 1}, {b, 7}}), (8. + 1) / 256);
  EXPECT_DOUBLE_EQ(majority_p_value({{a, 6}, {b, 2}}), (28. + 8 + 1) / 256);
  EXPECT_DOUBLE_EQ(majority_p_value({{a, 9}, {b, 3}}), (220. + 66 + 12 + 1) / 4096);
  EXPECT_DOUBLE_EQ(majority_p_value({{a, 2}, {b, 2}}), 1.); // a tie decides nothing
  EXPECT_DOUBLE_EQ(majority_p_value({}), 1.);
  EXPECT_TRUE(majority_decided({{a, 4}}));
  EXPECT_FALSE(majority_decided({{a, 3}, {b, 1}}));
  EXPECT_TRUE(majority_decided({{a, 7}, {b, 1}}));
  EXPECT_FALSE(majority_decided({{a, 6}, {b, 2}}));
}

// Members whose classes split get more members, round by round: at the
// second point N = 20's members 0–3 split 2–2 and every later one makes the
// signature move (decided at 12: 10 of 12); at the third point the
// reference's split 3–1 (decided at 8: 7 of 8); at the fourth N = 10's
// members alternate, so it stops at the ceiling, still split. Every other
// rung keeps its 4 members, and nothing else reruns.
TEST(RegionVerdict, ASplitRungGainsMembersUntilItsClassIsDecided)
{
  const Scene scene                        = read_scene(mueller);
  const std::vector<OperatingPoint> points = signature_move_region(scene);
  const double dt = scene.time_stepping.time_step, fe_dt = scene.time_stepping.fe_time_step;
  const auto sig = AdaptationClass::signature_move, none = AdaptationClass::no_adaptation;
  const auto at = [&](const MemberGroup &g, const std::size_t p) {
    return g.scene.excitation.frequency_hz == points[p].frequency_hz &&
           g.scene.excitation.acceleration_amplitude == points[p].acceleration_m_s2;
  };
  const auto outcome = [&](const MemberGroup &g, const unsigned int index) {
    if (at(g, 1) && g.model.family == "rom" && g.model.n_modes == 20)
      return index >= 4 || index < 2 ? sig : none;
    if (at(g, 2) && g.model.family == "fe" && g.model.time_step == fe_dt)
      return index == 1 ? none : sig;
    if (at(g, 3) && g.model.family == "rom" && g.model.n_modes == 10 && g.model.time_step == dt / 2)
      return index % 2 ? none : sig;
    return sig;
  };
  std::vector<std::size_t> round_sizes;
  std::vector<unsigned int> first_members;
  // Each group as the ranks name it, and what rank 0 shares with the others.
  const auto signature = [](const MemberGroup &g) {
    return g.name + " | " + g.model.label() + " | " + std::to_string(g.first_member) + "+" +
           std::to_string(g.n_members);
  };
  std::vector<std::string> rank0_groups, other_rank_groups;
  std::vector<unsigned long> shared;
  const auto share = [&](const unsigned long x) {
    shared.push_back(x);
    return x;
  };
  const MemberGroupRunner fabricate = [&](const std::vector<MemberGroup> &groups) {
    round_sizes.push_back(groups.size());
    std::vector<std::vector<EnsembleMember>> out;
    for (const MemberGroup &g : groups)
      {
        rank0_groups.push_back(signature(g));
        if (g.first_member > 0)
          first_members.push_back(g.first_member);
        std::vector<EnsembleMember> members = ending_at(0.40, g.n_members);
        for (unsigned int m = 0; m < g.n_members; ++m)
          {
            members[m].index            = g.first_member + m;
            members[m].analysis.outcome = outcome(g, members[m].index);
          }
        out.push_back(members);
      }
    return out;
  };
  const RegionStudy study = run_region(scene, points, 40., 4, fabricate, fabricate, share);
  EXPECT_EQ(round_sizes, (std::vector<std::size_t>{13 * points.size(), 3, 2, 1}));
  EXPECT_EQ(first_members, (std::vector<unsigned int>{4, 4, 4, 8, 8, 12}));

  // The other MPI ranks, told only what rank 0 shared, compute the same
  // groups in the same rounds (they never see a member).
  std::size_t next = 0;
  work_on_region(
    scene, points, 40., 4,
    [&](const std::vector<MemberGroup> &groups) {
      for (const MemberGroup &g : groups)
        other_rank_groups.push_back(signature(g));
    },
    [&](unsigned long) { return next < shared.size() ? shared[next++] : ~0ul; });
  EXPECT_EQ(next, shared.size());
  EXPECT_EQ(other_rank_groups, rank0_groups);

  const auto rung_of = [&](const std::size_t p, const std::function<bool(const ModelSetting &)> &is) {
    const LadderStudy &l = study.ladders[p];
    for (const LadderRungResult &r : l.rungs)
      if (is(r.rung.model))
        return &r;
    return static_cast<const LadderRungResult *>(nullptr);
  };
  const LadderRungResult *n20  = rung_of(1, [](const ModelSetting &m) { return m.family == "rom" && m.n_modes == 20; });
  const LadderRungResult *ref  = &study.ladders[2].rungs[study.ladders[2].reference];
  const LadderRungResult *n10  = rung_of(3, [&](const ModelSetting &m) { return m.n_modes == 10 && m.family == "rom"; });
  ASSERT_TRUE(n20 && n10);
  EXPECT_EQ(n20->members.size(), 12u);
  EXPECT_EQ(class_counts(n20->members), (ClassCounts{{to_string(sig), 10}, {to_string(none), 2}}));
  EXPECT_TRUE(majority_decided(class_counts(n20->members)));
  EXPECT_EQ(n20->outcome_classes.at(to_string(sig)), 10u); // the ladder assembled again with them
  EXPECT_EQ(ref->members.size(), 8u);
  EXPECT_EQ(majority_class(class_counts(ref->members)), to_string(sig));
  EXPECT_EQ(n10->members.size(), std::size_t(class_members_ceiling));
  EXPECT_EQ(majority_class(class_counts(n10->members)), "split");
  for (std::size_t m = 0; m < n10->members.size(); ++m)
    EXPECT_EQ(n10->members[m].index, m);
  std::size_t grown = 0;
  for (const LadderStudy &l : study.ladders)
    {
      EXPECT_EQ(l.members, 4u);
      for (const LadderRungResult &r : l.rungs)
        grown += r.members.size() != 4;
      EXPECT_TRUE(l.proven());
    }
  EXPECT_EQ(grown, 3u);
}

// Where N = 20 and N = 30 both end apart from the FE (the second point),
// two ROMs run beside it: every mode of the mesh stepped as the FE is, and
// N = 30 at its own step with the FE's θ. Fabricated so that both land on
// the FE while the explicit N = 30 does not, the summary puts the gap on
// the scheme's damping, not on the model's form; the other ranks, told
// what rank 0 shared, run the same probes.
TEST(RegionVerdict, WhereMoreModesDoNotReachTheFETheProbesNameWhatDoes)
{
  const Scene scene                        = read_scene(mueller);
  const std::vector<OperatingPoint> points = signature_move_region(scene);
  const double fe_dt = scene.time_stepping.fe_time_step, theta = scene.time_stepping.fe_theta;
  const unsigned int all_modes = fe_bending_modes(scene);
  std::vector<MemberGroup> probes;
  std::vector<std::string> rank0_groups, other_rank_groups;
  std::vector<unsigned long> shared;
  const MemberGroupRunner fabricate = [&](const std::vector<MemberGroup> &groups) {
    std::vector<std::vector<EnsembleMember>> out;
    for (const MemberGroup &g : groups)
      {
        rank0_groups.push_back(g.name + " | " + g.model.label());
        const bool second = g.scene.excitation.frequency_hz == points[1].frequency_hz &&
                            g.scene.excitation.acceleration_amplitude == points[1].acceleration_m_s2;
        const bool implicit = g.model.family == "rom" && g.model.integrator == "implicit";
        if (implicit)
          probes.push_back(g);
        double end = 0.40;
        if (g.model.family == "rom" && g.model.n_modes < 20)
          end = 0.30;
        else if (g.model.family == "rom" && second && !implicit)
          end = 0.35;
        out.push_back(ending_at(end, g.n_members));
      }
    return out;
  };
  const auto share = [&](const unsigned long x) {
    shared.push_back(x);
    return x;
  };
  const RegionStudy study = run_region(scene, points, 40., 4, fabricate, fabricate, share);

  ASSERT_EQ(study.model_form.size(), 1u);
  EXPECT_EQ(study.model_form.front().first, 1u);
  ASSERT_EQ(probes.size(), 2u);
  const LadderStudy &second = study.ladders[1];
  const auto n_check = std::find_if(second.checks.begin(), second.checks.end(),
                                    [](const ConvergenceCheck &c) { return c.parameter == "N"; });
  ASSERT_NE(n_check, second.checks.end());
  const ModelSetting &n30 = n_check->trials[1].model;
  EXPECT_EQ(probes[0].model.n_modes, all_modes);
  EXPECT_DOUBLE_EQ(probes[0].model.time_step, fe_dt);
  EXPECT_EQ(probes[0].model.damped_modes, scene.discretisation.n_modes);
  EXPECT_EQ(probes[1].model.n_modes, 30u);
  EXPECT_DOUBLE_EQ(probes[1].model.time_step, n30.time_step);
  EXPECT_LT(probes[1].model.time_step, fe_dt);
  EXPECT_EQ(probes[1].model.damped_modes, n30.damped_modes);
  for (const MemberGroup &g : probes)
    {
      EXPECT_DOUBLE_EQ(g.model.theta, theta);
      EXPECT_EQ(g.n_members, 4u);
    }
  const LadderStudy &l = study.model_form.front().second;
  EXPECT_NEAR(l.rungs[l.reference].final_position.median, 0.40 + 1.5e-4, 1e-12);
  EXPECT_NEAR(l.rungs[1].position_to_reference.wasserstein, 0., 1e-12);

  const std::string summary = region_summary(study);
  EXPECT_NE(summary.find("The model's form (no axial inertia, the cubic membrane, the contact on the modal sum) "
                         "does not separate ROM and FE there."),
            std::string::npos)
    << summary;
  EXPECT_NE(summary.find("lands on the FE: the scheme's numerical damping of the modes that ring after each impact, "
                         "not the basis, separates"),
            std::string::npos)
    << summary;

  std::size_t next = 0;
  work_on_region(
    scene, points, 40., 4,
    [&](const std::vector<MemberGroup> &groups) {
      for (const MemberGroup &g : groups)
        other_rank_groups.push_back(g.name + " | " + g.model.label());
    },
    [&](unsigned long) { return next < shared.size() ? shared[next++] : ~0ul; });
  EXPECT_EQ(next, shared.size());
  EXPECT_EQ(other_rank_groups, rank0_groups);
}
