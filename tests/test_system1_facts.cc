// The System 1 facts' criteria (verification/studies/system1_facts.h) on
// constructed traces read by the one trace analysis: each fact passes the
// trace drawn after the seed's figure and fails a trace of another behaviour,
// and the partial scores rank a near miss above a plain miss.
#include "verification/studies/system1_facts.h"

#include "runs/trace_analysis.h"
#include "scene/scene.h"

#include "tests/synthetic_periods.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

using namespace beamslider;

namespace
{
  // A scene whose backbone is 5 % stiffer at 0.6 h, as in the trace analysis' tests.
  const TraceThresholds scene_like = TraceThresholds::for_backbone((1.05 * 1.05 - 1.) / (0.6 * 0.6));

  TraceAnalysis trace(const double t_end, const std::function<double(double)> &x,
                      const std::function<double(double)> &a, const RunStatus status = RunStatus::completed)
  {
    return analyse_trace(synthetic_periods(t_end, x, a), status, scene_like);
  }

  // Fig. 10 in caricature, right half: out from 0.6 at a low level, a jump
  // at 10 s, back to `end` by 20 s on the upper branch.
  TraceAnalysis signature(const double end, const double x0 = 0.6)
  {
    const double out = x0 > 0.5 ? 1. : -1.;
    return trace(
      30, [=](double t) { return t < 10 ? x0 + out * 0.015 * t : t < 20 ? x0 + out * 0.15 + (end - x0 - out * 0.15) * (t - 10) / 10 : end; },
      [](double t) { return t < 10 ? 0.1 : 1.5; });
  }
  // No movement, low level.
  TraceAnalysis resting(const double x0) { return trace(30, [=](double) { return x0; }, [](double) { return 0.05; }); }
  // Monotonic from x0 toward the centre to `end` by 20 s, the amplitude
  // growing steadily (no jump) to the upper branch.
  TraceAnalysis to_centre(const double x0, const double end)
  {
    return trace(
      30, [=](double t) { return t < 20 ? x0 + (end - x0) * t / 20 : end; },
      [](double t) { return std::min(1.5, 0.1 + 0.07 * t); });
  }

  FactVerdict judge(const std::string &id, const TraceAnalysis &a)
  {
    const System1Fact &f = system1_fact(id);
    return f.judge(a, f.start_over_L());
  }
} // namespace

TEST(System1Facts, EveryFactHasANameAScenarioAndAStart)
{
  ASSERT_GE(system1_facts().size(), 7u);
  for (const System1Fact &f : system1_facts())
    {
      EXPECT_FALSE(f.name.empty()) << f.id;
      EXPECT_NE(f.name.find("Fig."), std::string::npos) << "named after the seed's figure: " << f.name;
      EXPECT_GT(f.end_time, 0.);
      EXPECT_GT(f.start_over_L(), 0.);
      EXPECT_LT(f.start_over_L(), 1.);
      EXPECT_TRUE(f.checks);
    }
  EXPECT_THROW(system1_fact("fig99"), InputError);
  // The frictionless ablation fixes the friction: it is no axis of that map.
  const auto fixed = system1_fact("fig8-frictionless").fixed_parameters();
  EXPECT_NE(std::find(fixed.begin(), fixed.end(), "Contact/Friction coefficient"), fixed.end());
}

TEST(System1Facts, PartialScores)
{
  EXPECT_TRUE(position_check("", 0.59, 0.57, 0.03).met);
  EXPECT_DOUBLE_EQ(position_check("", 0.59, 0.57, 0.03).score, 1.);
  EXPECT_FALSE(position_check("", 0.63, 0.57, 0.03).met);
  EXPECT_NEAR(position_check("", 0.63, 0.57, 0.03).score, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(position_check("", 0.70, 0.57, 0.03).score, 0.);
  EXPECT_TRUE(bound_check("", 0.3, 0.5, true, 0.5).met);
  EXPECT_NEAR(bound_check("", 0.75, 0.5, true, 0.5).score, 0.5, 1e-12);
  EXPECT_FALSE(bound_check("", 0.05, 0.1, false, 0.1).met);
  EXPECT_NEAR(bound_check("", 0.05, 0.1, false, 0.1).score, 0.5, 1e-12);
  // A run too short to judge fails with score 0.
  const FactVerdict v = judge("fig10", trace(0.1, [](double) { return 0.6; }, [](double) { return 0.1; }));
  EXPECT_FALSE(v.pass);
  EXPECT_DOUBLE_EQ(v.score, 0.);
}

TEST(System1Facts, Fig10SignatureMoveEndingNear057)
{
  const FactVerdict pass = judge("fig10", signature(0.58));
  EXPECT_TRUE(pass.pass) << pass.reason;
  EXPECT_DOUBLE_EQ(pass.score, 1.);
  // The move right, the end too far out: fails, but scores above a slider that rests.
  const FactVerdict near = judge("fig10", signature(0.64));
  EXPECT_FALSE(near.pass) << near.reason;
  EXPECT_NE(near.reason.find("NOT stops near"), std::string::npos) << near.reason;
  const FactVerdict rest = judge("fig10", resting(0.6));
  EXPECT_FALSE(rest.pass);
  EXPECT_GT(near.score, rest.score);
  EXPECT_LT(rest.score, 0.5) << rest.reason;
  // The mirror image from the left half.
  EXPECT_TRUE(judge("fig10-left", signature(0.42, 0.4)).pass) << judge("fig10-left", signature(0.42, 0.4)).reason;
  EXPECT_FALSE(judge("fig10-left", signature(0.58)).pass);
}

TEST(System1Facts, Fig12And13MonotonicToTheCentre)
{
  const FactVerdict pass = judge("fig12", to_centre(0.82, 0.56));
  EXPECT_TRUE(pass.pass) << pass.reason;
  EXPECT_TRUE(judge("fig13", to_centre(0.82, 0.56)).pass);
  // Resting near the clamp, or a signature move, is neither.
  EXPECT_FALSE(judge("fig12", resting(0.82)).pass);
  EXPECT_FALSE(judge("fig13", resting(0.82)).pass);
  EXPECT_FALSE(judge("fig12", signature(0.57)).pass);
  // Toward the centre but stopping halfway out: the position check fails.
  const FactVerdict halfway = judge("fig13", to_centre(0.82, 0.72));
  EXPECT_FALSE(halfway.pass) << halfway.reason;
  EXPECT_GT(halfway.score, 0.5);
}

TEST(System1Facts, Fig11TightFitStraightToTheCentre)
{
  const TraceAnalysis straight =
    trace(30, [](double t) { return std::max(0.5, 0.6 - 0.005 * t); }, [](double) { return 0.05; });
  EXPECT_TRUE(judge("fig11", straight).pass) << judge("fig11", straight).reason;
  EXPECT_FALSE(judge("fig11", signature(0.57)).pass);
  EXPECT_FALSE(judge("fig11", resting(0.6)).pass);
}

TEST(System1Facts, Fig6JumpWithoutTurnOnToTheClamp)
{
  // Out from 0.75, jump at 10 s, on out to 0.95 while the amplitude decays.
  const TraceAnalysis unstable = trace(
    30, [](double t) { return 0.75 + 0.2 * t / 30; },
    [](double t) { return t < 10 ? 0.1 : 1.5 * std::exp(-(t - 10) / 8); });
  const FactVerdict pass = judge("fig6", unstable);
  EXPECT_TRUE(pass.pass) << pass.reason;
  // The signature move turns: not Fig. 6.
  const FactVerdict turned = judge("fig6", signature(0.6, 0.75));
  EXPECT_FALSE(turned.pass);
  EXPECT_NE(turned.reason.find("NOT does not turn"), std::string::npos) << turned.reason;
}

TEST(System1Facts, Fig7RecurrentJumps)
{
  auto x = [](double t) { return 0.6 + 0.002 * std::min(t, 10.) - 0.004 * std::max(0., t - 10); };
  auto a = [](double t) { return (t > 5 && t < 10) || (t > 15 && t < 20) || (t > 25 && t < 30) ? 1.5 : 0.05; };
  EXPECT_TRUE(judge("fig7", trace(40, x, a)).pass) << judge("fig7", trace(40, x, a)).reason;
  const FactVerdict once = judge("fig7", signature(0.57));
  EXPECT_FALSE(once.pass);
  EXPECT_NEAR(once.score, 0.75, 1e-12) << "one of two jumps, on the beam: " << once.reason;
  // Recurrent jumps that end at a support are not the quasi-stable process.
  EXPECT_FALSE(judge("fig7", trace(40, x, a, RunStatus::slider_at_support)).pass);
}

TEST(System1Facts, Fig8SignatureMoveAndItsAblations)
{
  EXPECT_TRUE(judge("fig8", signature(0.6, 0.75)).pass) << judge("fig8", signature(0.6, 0.75)).reason;
  EXPECT_FALSE(judge("fig8", to_centre(0.82, 0.56)).pass);
  // Without geometric nonlinearity: out from the centre and stays, no jump.
  const TraceAnalysis linear =
    trace(30, [](double t) { return std::min(0.85, 0.75 + 0.01 * t); }, [](double t) { return 0.05 + 0.005 * t; });
  EXPECT_TRUE(judge("fig8-linear", linear).pass) << judge("fig8-linear", linear).reason;
  EXPECT_FALSE(judge("fig8-linear", signature(0.6, 0.75)).pass);
  // Frictionless: oscillates about the centre.
  const TraceAnalysis cycling =
    trace(30, [](double t) { return 0.5 + 0.05 * std::cos(0.5 * t); }, [](double) { return 0.5; });
  EXPECT_TRUE(judge("fig8-frictionless", cycling).pass) << judge("fig8-frictionless", cycling).reason;
  EXPECT_FALSE(judge("fig8-frictionless", resting(0.75)).pass);
  // Crossing once and coming to rest on the other side is no oscillation.
  const TraceAnalysis through =
    trace(30, [](double t) { return std::max(0.45, 0.75 - 0.03 * t); }, [](double) { return 0.5; });
  EXPECT_TRUE(through.crosses_centre);
  const FactVerdict once = judge("fig8-frictionless", through);
  EXPECT_FALSE(once.pass);
  EXPECT_NE(once.reason.find("NOT keeps moving"), std::string::npos) << once.reason;
}
