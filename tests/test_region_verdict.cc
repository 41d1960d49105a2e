// The verdict across the signature-move region (verification/studies/
// region_verdict.h): the points, and how the study splits one list of
// member runs back into a checked ladder per point. The members come from a
// runner that fabricates end states from the group's model and point, so
// that every number the study returns can be predicted.
#include "verification/studies/region_verdict.h"

#include <gtest/gtest.h>

#include <cmath>

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
  // where Δt ends at 0.38.
  const auto rom_end = [](const unsigned int n) { return n < 20 ? 0.30 + 0.01 * n / 5. : 0.3995; };
  const auto end_state = [&](const MemberGroup &g) {
    const bool first_point = g.scene.excitation.frequency_hz == points[0].frequency_hz &&
                             g.scene.excitation.acceleration_amplitude == points[0].acceleration_m_s2;
    if (g.model.family == "fe")
      return first_point && g.model.time_step == fe_dt ? 0.38 : 0.40;
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
  // 8 + 4 corrections, the reference) and 6 first refinements per point
  // (the reference and four ROMs at half their step, N = 20 against 30);
  // then Δt/4 at the first point alone.
  EXPECT_EQ(round_sizes, (std::vector<std::size_t>{12 * points.size(), 1}));
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
        if (i != l.reference)
          EXPECT_NEAR(l.rungs[i].position_to_reference.wasserstein, 0.40 - rom_end(l.rungs[i].rung.model.n_modes),
                      1e-12);
    }
}
