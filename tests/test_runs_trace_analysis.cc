// The one trace analysis (runs/trace_analysis.h) on constructed period
// records: each rule where it must fire and where it must not, and each
// outcome class from a trace built to be of that class.
#include "runs/trace_analysis.h"

#include "tests/synthetic_periods.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace beamslider;

namespace
{

  // A scene whose backbone is 5 % stiffer at 0.6 h (c ≈ 0.285, like mueller2023).
  const TraceThresholds scene_like = TraceThresholds::for_backbone((1.05 * 1.05 - 1.) / (0.6 * 0.6));

  // The published signature move in caricature: toward the clamp at a low
  // level, a jump to the upper branch at 10 s, back toward the centre, stays high.
  double signature_x(const double t) { return t < 10 ? 0.3 - 0.005 * t : t < 20 ? 0.25 + 0.01 * (t - 10) : 0.35; }
  double signature_a(const double t) { return t < 10 ? 0.1 : 1.5; }
} // namespace

TEST(TraceThresholds, UpperBranchLevelIsWhereTheBackboneIsFivePercentStiffer)
{
  EXPECT_NEAR(scene_like.high_level_over_h, 0.6, 1e-12);
  EXPECT_TRUE(std::isinf(TraceThresholds::for_backbone(0.).high_level_over_h)) << "a linear beam has no upper branch";
}

TEST(TraceAnalysis, SignatureMoveIsFoundWithItsJumpTurnAndEndState)
{
  const TraceAnalysis a = analyse_trace(synthetic_periods(30, signature_x, signature_a), RunStatus::completed, scene_like);
  EXPECT_EQ(a.outcome, AdaptationClass::signature_move) << a.line;
  EXPECT_EQ(a.initial_direction, "toward the clamp");
  ASSERT_TRUE(a.jumped);
  EXPECT_GT(a.jump_time, 10.);
  EXPECT_LE(a.jump_time, 10.1 + 0.01) << "within the 0.1 s envelope's rise";
  EXPECT_NEAR(a.level_before_jump, 0.1, 1e-12);
  EXPECT_EQ(a.n_upward_jumps, 1u);
  EXPECT_TRUE(a.turned);
  EXPECT_NEAR(a.turn_position, 0.25, 0.001);
  EXPECT_NEAR(a.final_position, 0.35, 1e-12);
  EXPECT_NEAR(a.final_amplitude, 1.5, 1e-12);
}

// A rise of the rattling to 0.16 h (five times its level, lasting) stays far
// below the upper branch of this scene: no jump (the quick report called such
// a bump a jump before there was one rule).
TEST(TraceAnalysis, BumpBelowTheUpperBranchIsNoJump)
{
  auto a_bump = [](double t) { return t > 10 && t < 15 ? 0.16 : 0.03; };
  const TraceAnalysis a = analyse_trace(synthetic_periods(30, [](double) { return 0.3; }, a_bump), RunStatus::completed, scene_like);
  EXPECT_FALSE(a.jumped) << a.line;
  // Without the scene's level the same bump passes every relative rule.
  const TraceAnalysis relative = analyse_trace(synthetic_periods(30, [](double) { return 0.3; }, a_bump), RunStatus::completed, {});
  EXPECT_TRUE(relative.jumped);
}

TEST(TraceAnalysis, RiseDuringTheBuildUpOrTooBriefIsNoJump)
{
  // From rest to 1.5 h within the first second: the build-up, not a jump.
  const TraceAnalysis build_up =
    analyse_trace(synthetic_periods(20, [](double) { return 0.3; }, [](double t) { return std::min(1.5, 0.01 + 3 * t); }),
                  RunStatus::completed, scene_like);
  EXPECT_FALSE(build_up.jumped) << build_up.line;
  // A 0.5 s burst to the upper branch: not lasting.
  const TraceAnalysis burst = analyse_trace(
    synthetic_periods(20, [](double) { return 0.3; }, [](double t) { return t > 8 && t < 8.5 ? 1.5 : 0.1; }), RunStatus::completed,
    scene_like);
  EXPECT_FALSE(burst.jumped) << burst.line;
}

// A relaxation oscillation that ends low is not a signature move, even with
// a first jump, a turn and a start toward the clamp.
TEST(TraceAnalysis, RecurrentJumpsAreARelaxationOscillation)
{
  auto x = [](double t) { return 0.3 - 0.002 * std::min(t, 10.) + 0.004 * std::max(0., t - 10); };
  auto a = [](double t) { return (t > 5 && t < 10) || (t > 15 && t < 20) || (t > 25 && t < 30) ? 1.5 : 0.05; };
  const TraceAnalysis r = analyse_trace(synthetic_periods(40, x, a), RunStatus::completed, scene_like);
  EXPECT_EQ(r.n_upward_jumps, 3u) << r.line;
  EXPECT_EQ(r.outcome, AdaptationClass::relaxation_oscillation);
}

TEST(TraceAnalysis, VibrationDyingOffResonanceIsSelfDamping)
{
  const TraceAnalysis d = analyse_trace(
    synthetic_periods(30, [](double t) { return 0.3 - 0.006 * t; }, [](double t) { return 0.2 * std::exp(-t / 5.); }),
    RunStatus::completed, scene_like);
  EXPECT_EQ(d.outcome, AdaptationClass::self_damping) << d.line;
}

TEST(TraceAnalysis, SteadyGrowthTowardTheCentreIsTrivialAdaption)
{
  const TraceAnalysis t = analyse_trace(
    synthetic_periods(30, [](double t) { return 0.3 + 0.002 * t; }, [](double t) { return 0.1 + 0.035 * t; }),
    RunStatus::completed, scene_like);
  EXPECT_FALSE(t.jumped);
  EXPECT_EQ(t.initial_direction, "toward the centre");
  EXPECT_EQ(t.outcome, AdaptationClass::trivial_adaption) << t.line;
  // The same drift at a level that never reaches the upper branch.
  const TraceAnalysis low = analyse_trace(
    synthetic_periods(30, [](double t) { return 0.3 + 0.002 * t; }, [](double t) { return 0.05 + 0.002 * t; }),
    RunStatus::completed, scene_like);
  EXPECT_EQ(low.outcome, AdaptationClass::no_adaptation) << low.line;
}

TEST(TraceAnalysis, StatusDecidesSupportAndFailure)
{
  const auto p = synthetic_periods(30, signature_x, signature_a);
  EXPECT_EQ(analyse_trace(p, RunStatus::slider_at_support, scene_like).outcome, AdaptationClass::reached_support);
  EXPECT_EQ(analyse_trace(p, RunStatus::unphysical_state, scene_like).outcome, AdaptationClass::failed);
  EXPECT_EQ(analyse_trace(p, RunStatus::contact_solver_failure, scene_like).outcome, AdaptationClass::failed);
  EXPECT_EQ(analyse_trace(synthetic_periods(0.1, signature_x, signature_a), RunStatus::completed, scene_like).outcome,
            AdaptationClass::too_short);
}

TEST(TraceAnalysis, CentreCrossingAndEndStateWindow)
{
  const TraceAnalysis c = analyse_trace(
    synthetic_periods(20, [](double t) { return 0.5 - 0.2 * std::cos(t); }, [](double) { return 0.5; }), RunStatus::completed,
    scene_like);
  EXPECT_TRUE(c.crosses_centre);
  // End state: the mean over the last second (t in [19, 20)).
  double mean = 0;
  unsigned int n = 0;
  for (const auto &r : synthetic_periods(20, [](double t) { return 0.5 - 0.2 * std::cos(t); }, [](double) { return 0.5; }))
    if (r.t_start >= 20 - 124. / 124. - 1e-12)
      {
        mean += r.slider_x_over_L;
        ++n;
      }
  EXPECT_NEAR(c.final_position, mean / n, 2e-3);
}

TEST(TraceAnalysis, AdaptationTimeIsWhenTheSliderStaysNearItsEndPosition)
{
  // x moves from 0.3 at 0.02 L/s until t = 8 s, then stays at 0.46: it is
  // within 0.01 L of the end for good from t = 7.5 s on.
  const auto x = [](double t) { return 0.3 + 0.02 * std::min(t, 8.); };
  const TraceAnalysis a =
    analyse_trace(synthetic_periods(20, x, [](double) { return 1.0; }), RunStatus::completed, scene_like);
  EXPECT_NEAR(a.final_position, 0.46, 1e-12);
  EXPECT_NEAR(a.adaptation_time, 7.5, 2. / 124.);
  // A slider still on its way at the end has not settled: the time is near the end.
  const TraceAnalysis moving = analyse_trace(
    synthetic_periods(20, [](double t) { return 0.3 + 0.01 * t; }, [](double) { return 1.0; }), RunStatus::completed,
    scene_like);
  EXPECT_GT(moving.adaptation_time, 18.);
}
