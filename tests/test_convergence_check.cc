// The reference's convergence check (verification/studies/
// convergence_check.h): the decision on synthetic ensembles whose end states
// are set by hand, the rounds it runs (counted through a runner that
// fabricates members), and the refinements it builds.
#include "verification/studies/convergence_check.h"

#include "contact/beam_system.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace beamslider;

namespace
{
  const std::string mueller = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

  // An ensemble whose members end at `centre` + spread·(m − (K−1)/2).
  std::vector<EnsembleMember> ending_at(const double centre, const double spread, const unsigned int n = 8)
  {
    std::vector<EnsembleMember> members(n);
    for (unsigned int m = 0; m < n; ++m)
      {
        members[m].index                  = m;
        members[m].analysis.valid         = true;
        members[m].analysis.final_position  = centre + spread * (m - (n - 1) / 2.);
        members[m].analysis.final_amplitude = 1.;
      }
    return members;
  }

  ModelSetting fe_at(const double dt)
  {
    ModelSetting s;
    s.family    = "fe";
    s.time_step = dt;
    s.theta     = 0.51;
    return s;
  }
} // namespace

// Halving plans: Δt, Δt/2, Δt/4 and nothing else changed.
TEST(ConvergenceCheck, StepRefinementsHalveTheStepOnly)
{
  const RefinementPlan plan = step_refinements("FE", fe_at(1e-5), 2);
  ASSERT_EQ(plan.models.size(), 3u);
  EXPECT_EQ(plan.parameter, "Δt");
  EXPECT_DOUBLE_EQ(plan.models[1].time_step, 5e-6);
  EXPECT_DOUBLE_EQ(plan.models[2].time_step, 2.5e-6);
  for (const ModelSetting &m : plan.models)
    {
      EXPECT_EQ(m.family, "fe");
      EXPECT_EQ(m.theta, 0.51);
    }
}

// A second ensemble that ends 0.02 L away is a difference however the first
// is judged; one within the members' own scatter is none; trials judged
// from the coarsest, the first whose refinement agrees is accepted.
TEST(ConvergenceCheck, AcceptsTheFirstStepWhoseHalfEndsAlike)
{
  const RefinementPlan plan = step_refinements("FE", fe_at(1e-5), 2);
  // Δt moves by 0.02 L on halving, Δt/2 and Δt/4 agree within the scatter.
  const ConvergenceCheck c =
    judge_convergence(plan, {ending_at(0.38, 0.002), ending_at(0.40, 0.002), ending_at(0.4003, 0.002)});
  EXPECT_TRUE(c.decided);
  ASSERT_TRUE(c.converged);
  EXPECT_EQ(c.accepted, 1u);
  EXPECT_DOUBLE_EQ(c.reference().model.time_step, 5e-6);
  EXPECT_TRUE(c.trials[0].position_to_next.distinguishable);
  EXPECT_NEAR(c.trials[0].position_to_next.wasserstein, 0.02, 1e-12); // a pure shift: W₁ is the shift
  EXPECT_FALSE(c.trials[1].position_to_next.distinguishable);
  EXPECT_NE(c.verdict().find("converged at Δt = 5e-06 s"), std::string::npos) << c.verdict();
}

// Every halving moves the end state: not converged, decided only when the
// plan has no refinement left, and the finest trial is what a study uses.
TEST(ConvergenceCheck, SaysNotConvergedWhenEveryHalvingMovesTheEnd)
{
  const RefinementPlan plan = step_refinements("FE", fe_at(1e-4), 2);
  ConvergenceCheck c        = judge_convergence(plan, {ending_at(0.30, 0.001), ending_at(0.33, 0.001)});
  EXPECT_FALSE(c.decided) << "a refinement is left: the check must go on";
  EXPECT_FALSE(c.converged);
  c = judge_convergence(plan, {ending_at(0.30, 0.001), ending_at(0.33, 0.001), ending_at(0.35, 0.001)});
  EXPECT_TRUE(c.decided);
  EXPECT_FALSE(c.converged);
  EXPECT_DOUBLE_EQ(c.reference().model.time_step, 2.5e-5);
  EXPECT_NE(c.verdict().find("NOT CONVERGED"), std::string::npos) << c.verdict();
}

// Members that have not spread yet (early in a run) have no scatter to
// hide a difference in: a shift below the stated resolution is still no
// difference, one above it is.
TEST(ConvergenceCheck, ShiftsBelowTheResolutionAreNoneWhenMembersHaveNotSpread)
{
  const RefinementPlan plan = step_refinements("FE", fe_at(1e-5), 1);
  const double small        = 0.3 * convergence_resolution, large = 3 * convergence_resolution;
  const ConvergenceCheck same = judge_convergence(plan, {ending_at(0.3, 0), ending_at(0.3 + small, 0)});
  EXPECT_TRUE(same.trials[0].position_to_next.distinguishable) << "no scatter: the interval test alone separates them";
  EXPECT_TRUE(same.converged);
  const ConvergenceCheck apart = judge_convergence(plan, {ending_at(0.3, 0), ending_at(0.3 + large, 0)});
  EXPECT_FALSE(apart.converged);
  EXPECT_TRUE(apart.decided);
}

// The rounds: the pair together, then one refinement at a time, only for
// the checks still undecided, with the mask shared before every round
// (and 0 at the end); the members each round returns are the trials'.
TEST(ConvergenceCheck, RunsThePairThenOneRefinementPerRound)
{
  Scene scene                  = read_scene(mueller);
  scene.time_stepping.end_time = 1;
  // Check 0 moves on every halving; check 1 agrees at once.
  const std::vector<RefinementPlan> plans = {step_refinements("moving", fe_at(1e-4), 3),
                                             step_refinements("steady", fe_at(2e-5), 3)};
  std::vector<std::size_t> groups_per_round;
  const MemberGroupRunner fabricate = [&](const std::vector<MemberGroup> &groups) {
    groups_per_round.push_back(groups.size());
    std::vector<std::vector<EnsembleMember>> out;
    for (const MemberGroup &g : groups)
      {
        EXPECT_EQ(g.n_members, 4u);
        const bool moving = g.name.rfind("moving", 0) == 0;
        // The moving check's end state drifts with log2 of its step.
        out.push_back(ending_at(moving ? 0.3 + 0.01 * std::log2(g.model.time_step / 1e-6) : 0.4, 0.001, 4));
      }
    return out;
  };
  std::vector<unsigned long> masks;
  const auto share = [&](const unsigned long mask) {
    masks.push_back(mask);
    return mask;
  };
  const std::vector<ConvergenceCheck> checks =
    run_convergence_checks(scene, plans, {}, 4, 1e-9, fabricate, share);
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_FALSE(checks[0].converged);
  EXPECT_EQ(checks[0].trials.size(), 4u);
  EXPECT_TRUE(checks[1].converged);
  EXPECT_EQ(checks[1].accepted, 0u);
  EXPECT_EQ(checks[1].trials.size(), 2u);
  // Round 1: both pairs (4 groups); then the moving check alone, twice.
  EXPECT_EQ(groups_per_round, (std::vector<std::size_t>{4, 1, 1}));
  EXPECT_EQ(masks, (std::vector<unsigned long>{3, 1, 1, 0}));

  // The other ranks, told the same masks, run the same rounds.
  std::size_t i = 0;
  std::vector<std::size_t> worker_rounds;
  work_on_convergence_checks(
    scene, plans, {0, 0}, 4, 1e-9, [&](const std::vector<MemberGroup> &g) { worker_rounds.push_back(g.size()); },
    [&](unsigned long) { return masks.at(i++); });
  EXPECT_EQ(worker_rounds, groups_per_round);
}

// The reference's check judges the sequence of steps. End states that drift
// as x(h) = x* + C h^p, fabricated at 2Δt (the witness), Δt, Δt/2 and Δt/4
// with every neighbouring pair within the members' spread: at p = 0.3 the
// drift is far from over (Richardson puts the remaining error at several
// times the last difference), and no step may be accepted; at p = 1 and
// p = 2 the scene's own step is.
namespace
{
  ConvergenceCheck judged_drift(const double order, const double last_difference)
  {
    const RefinementPlan plan = step_sequence("FE", fe_at(1e-5), 2);
    // C such that x(Δt/2) − x(Δt/4) = last_difference.
    const double C = last_difference / (std::pow(0.5, order) - std::pow(0.25, order));
    std::vector<std::vector<EnsembleMember>> trials;
    for (const ModelSetting &m : plan.models) // the plan's order: Δt, Δt/2, 2Δt, Δt/4
      trials.push_back(ending_at(0.40 + C * std::pow(m.time_step / 1e-5, order), 0.003));
    return judge_convergence(plan, trials);
  }
} // namespace

TEST(ConvergenceCheck, SequencePlanRunsTheWitnessAfterThePair)
{
  const RefinementPlan plan = step_sequence("FE", fe_at(1e-5), 2);
  ASSERT_EQ(plan.models.size(), 4u);
  EXPECT_TRUE(plan.judged_by_order);
  EXPECT_DOUBLE_EQ(plan.models[0].time_step, 1e-5);
  EXPECT_DOUBLE_EQ(plan.models[1].time_step, 5e-6);
  EXPECT_DOUBLE_EQ(plan.models[2].time_step, 2e-5);
  EXPECT_DOUBLE_EQ(plan.models[3].time_step, 2.5e-6);
  EXPECT_THROW(step_sequence("FE", fe_at(1e-5), 0), std::invalid_argument);
}

TEST(ConvergenceCheck, DriftAtOrderPointThreeWithinTheSpreadIsNotAccepted)
{
  const ConvergenceCheck c = judged_drift(0.3, 0.0015);
  ASSERT_EQ(c.trials.size(), 4u);
  EXPECT_TRUE(c.trials.front().witness);
  for (std::size_t k = 0; k + 1 < c.trials.size(); ++k)
    {
      EXPECT_GT(c.trials[k].model.time_step, c.trials[k + 1].model.time_step) << "sorted coarsest first";
      EXPECT_TRUE(ends_alike(c.trials[k].position_to_next)) << "pair " << k << " is within the spread, by design";
    }
  EXPECT_TRUE(c.decided);
  EXPECT_FALSE(c.converged) << c.verdict();
  // Pure shifts: the medians' differences are exact, and so is the order.
  EXPECT_NEAR(c.trials[1].observed_order, 0.3, 1e-9);
  EXPECT_NEAR(c.trials[2].observed_order, 0.3, 1e-9);
  EXPECT_NE(c.verdict().find("NOT CONVERGED"), std::string::npos) << c.verdict();
  EXPECT_NE(c.verdict().find("observed order 0.30"), std::string::npos) << c.verdict();

  // The same drift judged by pairs alone passes at the scene's step: what
  // the sequence is for.
  const RefinementPlan pairs = step_refinements("FE", fe_at(1e-5), 1);
  EXPECT_TRUE(judge_convergence(pairs, {c.trials[1].members, c.trials[2].members}).converged);
}

TEST(ConvergenceCheck, ConvergenceAtOrderOneOrTwoIsAcceptedAtTheScenesStep)
{
  for (const double order : {1., 2.})
    {
      const ConvergenceCheck c = judged_drift(order, 0.0005);
      ASSERT_TRUE(c.converged) << "order " << order << ": " << c.verdict();
      EXPECT_DOUBLE_EQ(c.reference().model.time_step, 1e-5);
      const ConvergenceTrial &t = c.reference();
      EXPECT_NEAR(t.observed_order, order, 1e-9);
      // Richardson's remaining error of x(Δt) is exact for a pure power law.
      const double C = 0.0005 / (std::pow(0.5, order) - std::pow(0.25, order));
      EXPECT_NEAR(t.remaining_error, C, 1e-12);
      EXPECT_LE(t.remaining_error, t.tolerance);
      EXPECT_NE(c.verdict().find("extrapolated remaining error"), std::string::npos) << c.verdict();
    }
}

// A witness that failed (no end state) shows no order: the scene's step is
// not accepted however well the pair agrees; Δt/2 can be, from Δt and Δt/4.
TEST(ConvergenceCheck, AStepWithoutAnEndStateShowsNoOrder)
{
  const RefinementPlan plan = step_sequence("FE", fe_at(1e-5), 2);
  std::vector<EnsembleMember> failed = ending_at(0.4, 0.003);
  for (EnsembleMember &m : failed)
    m.analysis.valid = false;
  ConvergenceCheck c = judge_convergence(plan, {ending_at(0.4, 0.003), ending_at(0.4, 0.003), failed});
  EXPECT_FALSE(c.converged);
  EXPECT_FALSE(c.decided) << "Δt/4 is left";
  c = judge_convergence(plan, {ending_at(0.4, 0.003), ending_at(0.4, 0.003), failed, ending_at(0.4, 0.003)});
  ASSERT_TRUE(c.converged) << c.verdict();
  EXPECT_DOUBLE_EQ(c.reference().model.time_step, 5e-6);
}

// Run by rounds from nothing (`ensemble --model fe`): the pair and the
// witness at once, then Δt/4 only if still undecided.
TEST(ConvergenceCheck, SequenceRoundsThePairAndWitnessThenTheNextHalving)
{
  Scene scene                  = read_scene(mueller);
  scene.time_stepping.end_time = 1;
  for (const double order : {0.3, 1.})
    {
      std::vector<std::size_t> groups_per_round;
      const MemberGroupRunner fabricate = [&](const std::vector<MemberGroup> &groups) {
        groups_per_round.push_back(groups.size());
        std::vector<std::vector<EnsembleMember>> out;
        for (const MemberGroup &g : groups)
          out.push_back(ending_at(0.40 + (order < 1 ? 0.02 : 0.002) * std::pow(g.model.time_step / 1e-5, order), 0.003, 4));
        return out;
      };
      const ConvergenceCheck c =
        run_convergence_checks(scene, {step_sequence("FE", fe_at(1e-5), 2)}, {}, 4, 1e-9, fabricate).front();
      if (order == 1.)
        {
          EXPECT_TRUE(c.converged) << c.verdict();
          EXPECT_EQ(groups_per_round, (std::vector<std::size_t>{3}));
        }
      else
        {
          EXPECT_FALSE(c.converged) << c.verdict();
          EXPECT_EQ(groups_per_round, (std::vector<std::size_t>{3, 1}));
        }
    }
}

// The ROM's check in N: ⌈1.5 N⌉ modes at a step the explicit scheme takes,
// halved from the rung's own only as far as its limit 2/ω_max asks.
TEST(ConvergenceCheck, MoreModesAtAStableExplicitStep)
{
  const Scene scene = read_scene(mueller);
  ModelSetting rom;
  rom.family    = "rom";
  rom.n_modes   = 20;
  rom.time_step = scene.time_stepping.time_step / 4;
  const ModelSetting finer = more_modes(scene, rom);
  EXPECT_EQ(finer.n_modes, 30u);
  ModelSetting probe = finer;
  probe.time_step    = 1e-12;
  const double limit = make_beam_model(scene, probe)->max_stable_time_step();
  EXPECT_LE(finer.time_step, limit);
  if (finer.time_step < rom.time_step)
    {
      EXPECT_GT(2 * finer.time_step, limit) << "halved once more than the limit asks";
    }
  // The implicit ROM has no limit: its step stays.
  rom.integrator = "implicit";
  EXPECT_EQ(more_modes(scene, rom).time_step, rom.time_step);
}

// A failure is never a result: members that diverged keep their last
// position, but it is no end state. A step whose members all failed cannot
// be accepted however close their last positions lie, and the verdict says
// how many failed instead of printing a W₁ of nothing.
TEST(ConvergenceCheck, FailedMembersAreNoEndStates)
{
  const RefinementPlan plan = step_sequence("FE", fe_at(1e-5), 2);
  const auto diverged       = [](std::vector<EnsembleMember> members) {
    for (EnsembleMember &m : members)
      {
        m.result.status    = RunStatus::unphysical_state;
        m.analysis.outcome = AdaptationClass::failed;
      }
    return members;
  };
  // Every step's members diverged at the same place.
  std::vector<std::vector<EnsembleMember>> trials;
  for (std::size_t k = 0; k < plan.models.size(); ++k)
    trials.push_back(diverged(ending_at(0.4, 0.001)));
  const ConvergenceCheck c = judge_convergence(plan, trials);
  EXPECT_TRUE(c.decided);
  EXPECT_FALSE(c.converged) << c.verdict();
  EXPECT_EQ(c.trials[1].position_to_next.n_a, 0u);
  EXPECT_NE(c.verdict().find("8 of 8 members without an end state"), std::string::npos) << c.verdict();
  EXPECT_EQ(c.verdict().find("0.0000 [0.0000, 0.0000]"), std::string::npos) << c.verdict();

  // Half the members failed at every step: still enough to decide.
  for (auto &t : trials)
    for (std::size_t m = 0; m < t.size(); m += 2)
      {
        t[m].result.status    = RunStatus::completed;
        t[m].analysis.outcome = AdaptationClass::no_adaptation;
      }
  EXPECT_TRUE(judge_convergence(plan, trials).converged);
  // Fewer than half: not.
  for (auto &t : trials)
    {
      t[0].result.status    = RunStatus::unphysical_state;
      t[0].analysis.outcome = AdaptationClass::failed;
    }
  EXPECT_FALSE(judge_convergence(plan, trials).converged);
}
