// The error ladder (verification/studies/error_ladder.h) and the model
// choice of `simulate --model auto` built on it (model_choice.h): the same
// model twice is at distance zero, a changed model is at the distance the
// two-sample statistics give for its members, the cost is the stated cost
// model's; the choice takes the cheapest rung within the tolerance, from a
// cache keyed by the scene's physical content.
#include "verification/studies/error_ladder.h"
#include "verification/cli/ladder_cache.h"
#include "verification/studies/model_choice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

using namespace beamslider;

namespace
{
  const std::string mueller = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

  LadderRung rom_rung(const std::string &name, const unsigned int n_modes, const double time_step)
  {
    LadderRung r;
    r.name              = name;
    r.change            = "test";
    r.model.family      = "rom";
    r.model.n_modes     = n_modes;
    r.model.time_step   = time_step;
    return r;
  }

  std::vector<double> finals(const LadderRungResult &r)
  {
    return outcome_samples(r.members).final_position;
  }
} // namespace

// Rungs 0 and 1 are the same model: their members are the same runs to the
// bit, so W₁ is exactly 0 and they are indistinguishable. Rung 2 keeps three
// modes: its distance to the reference is W₁ of the members' end positions
// (recomputed here from the members), and the step 1 → 2 is the same pair.
TEST(ErrorLadder, SameModelIsAtDistanceZeroAndAChangedModelAtItsMembersDistance)
{
  Scene scene       = read_scene(mueller);
  const double dt   = scene.time_stepping.time_step;
  const auto rungs  = std::vector<LadderRung>{rom_rung("A", 5, dt), rom_rung("A again", 5, dt), rom_rung("B", 3, dt)};
  std::vector<std::string> order;
  const LadderStudy study =
    run_ladder(scene, rungs, 0, 1.0, 3, [&order](const LadderRung &r, std::size_t) { order.push_back(r.name); });
  ASSERT_EQ(study.rungs.size(), 3u);
  EXPECT_EQ(order, (std::vector<std::string>{"A", "A again", "B"})); // each rung announced once, in ladder order

  const SampleComparison &same = study.rungs[1].position_to_reference;
  EXPECT_EQ(same.n_a, 3u);
  EXPECT_EQ(same.wasserstein, 0.);
  EXPECT_FALSE(same.distinguishable);
  EXPECT_EQ(finals(study.rungs[0]), finals(study.rungs[1]));

  const double w = wasserstein_1(finals(study.rungs[2]), finals(study.rungs[0]));
  EXPECT_GT(w, 0.);
  EXPECT_DOUBLE_EQ(study.rungs[2].position_to_reference.wasserstein, w);
  EXPECT_DOUBLE_EQ(study.steps[2].wasserstein, w);
  EXPECT_EQ(study.steps[1].wasserstein, 0.);

  for (const auto &r : study.rungs)
    {
      EXPECT_DOUBLE_EQ(r.cost_units, cost_per_simulated_second(r.rung.model, scene) * 1.0);
      unsigned int classified = 0;
      for (const auto &[name, n] : r.outcome_classes)
        classified += n;
      EXPECT_EQ(classified, 3u) << r.rung.name;
      EXPECT_EQ(r.n_failed, 0u);
    }
  EXPECT_EQ(study.rungs[0].position_to_reference.n_a, 0u); // the reference is not compared with itself
}

// The choice on a constructed ladder: the cheapest rung whose W₁ interval
// ends within the tolerance; none: the reference; an undefined distance
// never qualifies.
TEST(ModelChoice, CheapestRungWithinTheTolerance)
{
  std::vector<LadderChoiceRow> rows(4);
  rows[0].rung = "ROM cheap", rows[0].cost_units = 1e6, rows[0].w1_high = 0.05;
  rows[1].rung = "ROM dear", rows[1].cost_units = 4e6, rows[1].w1_high = 0.01;
  rows[2].rung = "ROM undefined", rows[2].cost_units = 1e5, rows[2].w1_high = std::nan("");
  rows[3].rung = "FE", rows[3].cost_units = 1e9, rows[3].reference = true;
  EXPECT_EQ(cheapest_within(rows, 0.1).rung, "ROM cheap");
  EXPECT_EQ(cheapest_within(rows, 0.02).rung, "ROM dear");
  EXPECT_EQ(cheapest_within(rows, 0.01).rung, "ROM dear");
  EXPECT_EQ(cheapest_within(rows, 0.001).rung, "FE");
}

// The cache key follows the physics: any physical parameter changes it, the
// name, end time and output rate do not.
TEST(ModelChoice, SceneKeyChangesWithThePhysicsOnly)
{
  const Scene scene     = read_scene(mueller);
  const std::string key = scene_content_key(scene);
  EXPECT_EQ(key.size(), 16u);
  Scene same = scene;
  same.name                        = "other";
  same.time_stepping.end_time      = 7;
  same.time_stepping.output_rate   = 10;
  EXPECT_EQ(scene_content_key(same), key);
  for (const auto &change : std::vector<std::function<void(Scene &)>>{
         [](Scene &s) { s.contact.friction_coefficient *= 1 + 1e-12; },
         [](Scene &s) { s.time_stepping.time_step /= 2; },
         [](Scene &s) { s.discretisation.n_modes += 1; },
         [](Scene &s) { s.initial.slider_position_over_L += 1e-9; },
         [](Scene &s) { s.supports.axial_stiffness *= 2; }})
    {
      Scene changed = scene;
      change(changed);
      EXPECT_NE(scene_content_key(changed), key);
    }
}

// With a cache for the scene's key in place, the choice reads it and runs
// nothing: the picked model is the cached rung's, with its time step.
TEST(ModelChoice, ReadsTheCacheOfTheScene)
{
  const Scene scene     = read_scene(mueller);
  const std::string dir = (std::filesystem::temp_directory_path() / "beamslider_model_choice_test").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/ladder-" + scene_content_key(scene) + ".csv")
    << "rung,family,n_modes,n_elements,integrator,time_step_s,damped_modes,theta,reference,cost_units,final_x_median,"
       "w1,w1_high\n"
    << "ROM N=5,rom,5,0,explicit,2e-05,0,0.5,0,2500000,0.33,0.09,0.1\n"
    << "ROM N=20,rom,20,0,explicit,5e-06,0,0.5,0,8.5e7,0.40,0.02,0.025\n"
    << "FE,fe,0,32,implicit,1e-05,0,0.51,1,1.56e9,0.41,0,0\n";
  std::string why;
  const ModelSetting picked = choose_model(scene, 0.03, dir, why);
  EXPECT_EQ(picked.family, "rom");
  EXPECT_EQ(picked.n_modes, 20u);
  EXPECT_EQ(picked.time_step, 5e-6);
  EXPECT_NE(why.find("cached"), std::string::npos) << why;
  const ModelSetting strict = choose_model(scene, 0.001, dir, why);
  EXPECT_EQ(strict.family, "fe");
  EXPECT_EQ(strict.n_elements, 32u);
  EXPECT_EQ(strict.time_step, 1e-5);
  EXPECT_EQ(strict.theta, 0.51); // the FE reference's own scheme, not the midpoint rule
  std::filesystem::remove_all(dir);
}


// The ladder with diagnostics runs its diagnostic rungs (the ROM with all
// modes and the midpoint-rule FE at other time steps) with half the members,
// and the published ROM, the converged ROMs and the FE reference with all of
// them; the quick and the full ladder have no diagnostic rung, and the full
// one is the quick one and the implicit ROM N = 20.
TEST(ErrorLadder, OnlyTheLadderWithDiagnosticsRunsHalfTheMembersOnItsDiagnosticRungs)
{
  const Scene scene = read_scene(mueller);
  std::size_t reference = 0;
  const std::vector<LadderRung> full = default_ladder(scene, LadderScope::diagnostics, reference);
  const std::vector<MemberGroup> groups = ladder_groups(scene, full, 40., 8);
  ASSERT_EQ(groups.size(), full.size());
  unsigned int n_diagnostic = 0;
  for (std::size_t i = 0; i < full.size(); ++i)
    {
      const bool kept_whole = i == reference || (full[i].model.family == "rom" && full[i].model.n_modes <= 20);
      EXPECT_EQ(full[i].diagnostic, !kept_whole) << full[i].name;
      EXPECT_EQ(groups[i].n_members, kept_whole ? 8u : 4u) << full[i].name;
      n_diagnostic += full[i].diagnostic;
    }
  EXPECT_EQ(n_diagnostic, 5u);
  ASSERT_TRUE(full[reference - 1].diagnostic);
  EXPECT_EQ(rung_members(full[reference - 1], 3), 2u); // never fewer than two (W₁ needs a spread)

  const std::vector<LadderRung> quick = default_ladder(scene, LadderScope::quick, reference);
  for (const MemberGroup &g : ladder_groups(scene, quick, 25., 4))
    EXPECT_EQ(g.n_members, 4u) << g.name;
  const std::vector<LadderRung> verdict = default_ladder(scene, LadderScope::full, reference);
  ASSERT_EQ(verdict.size(), quick.size() + 1);
  for (const MemberGroup &g : ladder_groups(scene, verdict, 40., 8))
    EXPECT_EQ(g.n_members, 8u) << g.name;
  EXPECT_EQ(verdict[reference - 1].name, "ROM N=20 implicit");
  EXPECT_EQ(verdict[reference - 1].model.integrator, "implicit");
}

// The reference is the scene's own FE model, its step and θ, on either
// ladder, and always the last rung; a scene whose FE model is one of the
// full ladder's midpoint-rule rungs runs it once, as the reference.
TEST(ErrorLadder, TheReferenceIsTheScenesFEModelAndRunsOnce)
{
  const Scene scene = read_scene(mueller);
  for (const LadderScope scope : {LadderScope::quick, LadderScope::full, LadderScope::diagnostics})
    {
      std::size_t reference = 0;
      const std::vector<LadderRung> rungs = default_ladder(scene, scope, reference);
      ASSERT_EQ(reference, rungs.size() - 1);
      const ModelSetting &fe = rungs[reference].model;
      EXPECT_EQ(fe.family, "fe");
      EXPECT_EQ(fe.time_step, scene.time_stepping.fe_time_step);
      EXPECT_EQ(fe.theta, scene.time_stepping.fe_theta);
      EXPECT_EQ(fe.damped_modes, 0u); // the scene's N, as every FE run of the scene
      EXPECT_EQ(rungs[reference].name, fe_step_name(scene.time_stepping.time_step, fe.time_step, fe.theta));
    }
  EXPECT_EQ(fe_step_name(2e-5, 1e-5, 0.51), "FE Δt/2 θ=0.51");
  EXPECT_EQ(fe_step_name(2e-5, 2e-5, 0.5), "FE Δt");
  EXPECT_EQ(fe_step_name(2e-5, 3e-6, 0.5), "FE Δt=3e-06 s");

  Scene midpoint                     = scene;
  midpoint.time_stepping.fe_time_step = scene.time_stepping.time_step / 4;
  midpoint.time_stepping.fe_theta     = 0.5;
  std::size_t reference               = 0;
  const std::vector<LadderRung> rungs = default_ladder(midpoint, LadderScope::diagnostics, reference);
  EXPECT_EQ(rungs[reference].name, "FE Δt/4");
  EXPECT_EQ(std::count_if(rungs.begin(), rungs.end(), [](const LadderRung &r) { return r.name == "FE Δt/4"; }), 1);
  EXPECT_FALSE(rungs[reference].diagnostic);
}
