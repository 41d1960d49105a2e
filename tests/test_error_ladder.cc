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

#include <sys/stat.h>

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
// nothing: the picked model is the cached rung's, with its time step. A
// rung that moved when refined is never picked, however cheap and close;
// without a tolerance the choice grants the reference's own interval, at
// least choice_tolerance_floor.
TEST(ModelChoice, ReadsTheCacheOfTheScene)
{
  const Scene scene     = read_scene(mueller);
  const std::string dir = (std::filesystem::temp_directory_path() / "beamslider_model_choice_test").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto write_cache = [&](const std::string &reference_w1_high) {
    std::ofstream(dir + "/ladder-" + scene_content_key(scene) + ".csv")
      << choice_cache_file_text(
           "rung,family,n_modes,static_corrections,ritz_blocks,n_elements,integrator,time_step_s,damped_modes,theta,"
           "reference,cost_units,final_x_median,w1,w1_high,refined_alike\n"
           "ROM N=5,rom,5,0,1,0,explicit,2e-05,0,0.5,0,2500000,0.33,0.09,0.1,1\n"
           "ROM N=15,rom,15,0,1,0,explicit,1e-05,0,0.5,0,7.5e6,0.409,0.0005,0.0008,0\n"
           "ROM N=8+4sc,rom,8,4,1,0,explicit,1e-05,0,0.5,0,8.5e6,0.40,0.02,0.025,1\n"
           "FE,fe,0,0,1,32,implicit,1e-05,0,0.51,1,1.56e9,0.41,0.002," +
           reference_w1_high + ",1\n");
  };
  write_cache("0.003");
  std::string why;
  const ModelSetting picked = choose_model(scene, 0.03, dir, why);
  EXPECT_EQ(picked.family, "rom");
  EXPECT_EQ(picked.n_modes, 8u) << "N = 15 is within 0.03 and cheaper, but moved when refined";
  EXPECT_EQ(picked.n_static_corrections, 4u);
  EXPECT_EQ(picked.time_step, 1e-5);
  EXPECT_NE(why.find("cached"), std::string::npos) << why;
  EXPECT_NE(why.find("moves when refined"), std::string::npos) << why;
  const ModelSetting strict = choose_model(scene, 0.001, dir, why);
  EXPECT_EQ(strict.family, "fe");
  EXPECT_EQ(strict.n_elements, 32u);
  EXPECT_EQ(strict.time_step, 1e-5);
  EXPECT_EQ(strict.theta, 0.51); // the FE reference's own scheme, not the midpoint rule
  // No tolerance: max(0.005, 0.003) leaves 8+4sc (0.025) out; a reference
  // that knows its end state only to 0.03 lets it in.
  EXPECT_EQ(choose_model(scene, std::nullopt, dir, why).family, "fe");
  EXPECT_NE(why.find("tolerance 0.005 "), std::string::npos) << why;
  write_cache("0.03");
  EXPECT_EQ(choose_model(scene, std::nullopt, dir, why).n_modes, 8u);
  EXPECT_NE(why.find("tolerance 0.03 "), std::string::npos) << why;
  // The cache is there: ranks read it. Without it every rank would run the
  // ladder, so a run on more than one rank is refused and runs nothing.
  EXPECT_EQ(choose_model(scene, std::nullopt, dir, why, 2).n_modes, 8u);
  std::filesystem::remove_all(dir);
  try
    {
      choose_model(scene, std::nullopt, dir, why, 2);
      ADD_FAILURE() << "a choice on 2 ranks without the cache ran";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find(dir), std::string::npos) << e.what();
    }
  EXPECT_FALSE(std::filesystem::exists(dir));
  // A solid scene has no beam ladder to choose on.
  Scene solid            = scene;
  solid.solid.continuum = "plane stress";
  EXPECT_THROW(choose_model(solid, std::nullopt, dir, why), InputError);
}


// The ladder with diagnostics runs its diagnostic rungs (the ROM with all
// modes and the midpoint-rule FE at other time steps) with half the members,
// and the published ROM, the converged ROMs and the FE reference with all of
// them; the quick and the front's ladder have no diagnostic rung, and the
// front's has the implicit ROM N = 20.
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
  const std::vector<LadderRung> verdict = default_ladder(scene, LadderScope::front, reference);
  for (const MemberGroup &g : ladder_groups(scene, verdict, 40., 8))
    EXPECT_EQ(g.n_members, 8u) << g.name;
  EXPECT_EQ(std::count_if(verdict.begin(), verdict.end(),
                          [](const LadderRung &r) { return r.name == "ROM N=20 implicit" && r.model.integrator == "implicit"; }),
            1);
}

// The reference is the scene's own FE model, its step and θ, on either
// ladder, and always the last rung; a scene whose FE model is one of the
// full ladder's midpoint-rule rungs runs it once, as the reference.
TEST(ErrorLadder, TheReferenceIsTheScenesFEModelAndRunsOnce)
{
  const Scene scene = read_scene(mueller);
  for (const LadderScope scope : {LadderScope::quick, LadderScope::front, LadderScope::diagnostics})
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

// The front's ladder (`verify --full`) is the quick ladder with the
// implicit ROM and the other candidates: more modes and few modes with
// static corrections, each at the largest step Δt/2^k its explicit scheme
// takes (read off the model: within 2/ω_max, and twice it is not unless it
// is the scene's Δt), and two implicit ones at Δt with the FE's θ. Every
// explicit ROM rung and every candidate is checked at Δt/2, one halving,
// but the one converged in N, whose check is in N. A candidate's
// cost counts its coordinates, modes, corrections and Ritz vectors alike.
TEST(ErrorLadder, TheFrontAddsCandidatesAtTheirStepLimitEachCheckedAtHalfTheStep)
{
  const Scene scene     = read_scene(mueller);
  std::size_t reference = 0, quick_reference = 0;
  const std::vector<LadderRung> quick = default_ladder(scene, LadderScope::quick, quick_reference);
  const std::vector<LadderRung> front = default_ladder(scene, LadderScope::front, reference);
  ASSERT_EQ(reference, front.size() - 1);
  ASSERT_EQ(front.size(), quick.size() + 10);
  for (const LadderRung &q : quick)
    EXPECT_EQ(std::count_if(front.begin(), front.end(), [&](const LadderRung &r) { return r.name == q.name; }), 1)
      << q.name;
  unsigned int n_corrected = 0, n_candidates = 0, n_quick_candidates = 0, n_implicit = 0;
  for (const LadderRung &q : quick)
    n_quick_candidates += q.front_candidate;
  EXPECT_EQ(n_quick_candidates, 2u);
  for (std::size_t i = 0; i < reference; ++i)
    {
      if (!front[i].front_candidate)
        continue;
      const ModelSetting &m = front[i].model;
      ++n_candidates;
      n_corrected += m.n_static_corrections > 0;
      if (m.integrator == "implicit")
        {
          // Family (d): few modes at the scene's step with the FE's θ.
          ++n_implicit;
          EXPECT_EQ(m.time_step, scene.time_stepping.time_step) << front[i].name;
          EXPECT_EQ(m.theta, scene.time_stepping.fe_theta) << front[i].name;
          EXPECT_GT(m.theta, 0.5);
          continue;
        }
      ModelSetting probe = m;
      probe.time_step    = 1e-12;
      const double limit = make_beam_model(scene, probe)->max_stable_time_step();
      EXPECT_LE(m.time_step, limit) << front[i].name;
      if (m.time_step < scene.time_stepping.time_step)
        {
          EXPECT_GT(2 * m.time_step, limit) << front[i].name;
        }
    }
  EXPECT_EQ(n_candidates, 11u);
  EXPECT_EQ(n_corrected, 5u);
  EXPECT_EQ(n_implicit, 2u);

  const LadderChecks checks = ladder_checks(scene, front, reference);
  unsigned int n_step_checks = 0, n_mode_checks = 0;
  for (std::size_t c = 0; c < checks.plans.size(); ++c)
    {
      const LadderRung &r = front[checks.rung[c]];
      if (checks.rung[c] == reference)
        continue;
      if (checks.plans[c].parameter != "Δt")
        {
          EXPECT_TRUE(r.converged_in_n) << r.name;
          ++n_mode_checks;
          continue;
        }
      ++n_step_checks;
      EXPECT_FALSE(r.converged_in_n) << r.name;
      ASSERT_EQ(checks.plans[c].models.size(), 2u) << r.name;
      EXPECT_DOUBLE_EQ(checks.plans[c].models[1].time_step, r.model.time_step / 2) << r.name;
      EXPECT_EQ(checks.plans[c].models[1].n_static_corrections, r.model.n_static_corrections);
      EXPECT_EQ(checks.plans[c].models[1].ritz_blocks, r.model.ritz_blocks);
    }
  unsigned int n_roms = 0;
  for (const LadderRung &r : front)
    n_roms += r.model.family == "rom" && (r.model.integrator == "explicit" || r.front_candidate);
  EXPECT_EQ(n_mode_checks, 1u);
  EXPECT_EQ(n_step_checks + n_mode_checks, n_roms);

  // The candidate with Ritz vectors: 6 modes, 4 corrections grown by 4.
  const auto grown = std::find_if(front.begin(), front.end(), [](const LadderRung &r) { return r.model.ritz_blocks > 1; });
  ASSERT_TRUE(grown != front.end());
  ModelSetting corrected = grown->model, plain = corrected;
  ASSERT_EQ(corrected.ritz_blocks, 2u);
  plain.n_modes += plain.n_static_corrections * plain.ritz_blocks;
  plain.n_static_corrections = 0;
  plain.ritz_blocks          = 1;
  EXPECT_DOUBLE_EQ(cost_per_simulated_second(corrected, scene), cost_per_simulated_second(plain, scene));
  ModelSetting uncorrected         = corrected;
  uncorrected.n_static_corrections = 0;
  EXPECT_GT(cost_per_simulated_second(corrected, scene), cost_per_simulated_second(uncorrected, scene));

  // The implicit N = 20 at the explicit one's step costs its Newton solve
  // more per step, as the ladders measured (3.2-3.4x): the stated cost keeps
  // it off the front where W₁ ties.
  const auto named = [&](const std::string &name) {
    return std::find_if(front.begin(), front.end(), [&](const LadderRung &r) { return r.name == name; });
  };
  const auto explicit20 = named("ROM N=20"), implicit20 = named("ROM N=20 implicit");
  ASSERT_TRUE(explicit20 != front.end() && implicit20 != front.end());
  ASSERT_EQ(explicit20->model.time_step, implicit20->model.time_step);
  const double ratio = cost_per_simulated_second(implicit20->model, scene) /
                       cost_per_simulated_second(explicit20->model, scene);
  EXPECT_GE(ratio, 3.2);
  EXPECT_LE(ratio, 3.4);
}

// The front from a study's numbers: a rung beaten on both cost and W₁ is
// off it, so is one that moved when refined (at Δt/2, or in N) however
// cheap and close it is, and the reference; the rest in ascending cost. A candidate that moved at
// Δt/2 is a finding: the ladder is still proven; the reference's check is
// a claim.
TEST(ErrorLadder, TheFrontKeepsTheUnbeatenRungsConvergedInTheStep)
{
  LadderStudy study;
  const auto add = [&](const double cost, const double w1, const bool checked, const bool converged) {
    LadderRungResult r;
    r.rung.name                          = "rung " + std::to_string(study.rungs.size());
    r.cost_units                         = cost;
    r.position_to_reference.n_a          = 8;
    r.position_to_reference.n_b          = 8;
    r.position_to_reference.wasserstein  = w1;
    study.rungs.push_back(r);
    if (checked)
      {
        ConvergenceCheck c;
        c.parameter = "Δt";
        c.converged = converged;
        c.decided   = true;
        study.checks.push_back(c);
        study.check_rungs.push_back(study.rungs.size() - 1);
      }
  };
  add(1.0, 0.08, true, true);   // 0: cheapest
  add(2.0, 0.001, true, false); // 1: best, but moved at Δt/2
  add(2.5, 0.01, true, true);   // 2: on the front
  add(3.0, 0.02, true, true);   // 3: beaten by 2
  add(9.0, 0.001, false, true); // 4: unchecked (e.g. the implicit ROM), best W₁
  add(50, 0, true, true);       // 5: the reference
  study.reference = 5;
  EXPECT_EQ(speed_accuracy_front(study), (std::vector<std::size_t>{0, 2, 4}));
  EXPECT_TRUE(study.proven());
  study.checks.back().converged = false; // the reference's own check
  EXPECT_FALSE(study.proven());
  ASSERT_NE(study.refinement_check(1), nullptr);
  EXPECT_FALSE(study.refinement_check(1)->converged);
  EXPECT_EQ(study.refinement_check(4), nullptr);

  // A rung whose check is in N (the converged-in-N ROM) is judged by it.
  study.checks[study.checks.size() - 1].converged = true;
  add(0.5, 0.0, false, true); // 6: cheapest and closest, but not converged in N
  ConvergenceCheck in_n;
  in_n.parameter = "N";
  in_n.decided   = true;
  study.checks.push_back(in_n);
  study.check_rungs.push_back(6);
  EXPECT_EQ(speed_accuracy_front(study), (std::vector<std::size_t>{0, 2, 4}));
  EXPECT_FALSE(study.proven()) << "a rung converged in N is a claim";
  study.checks.back().converged = true;
  EXPECT_EQ(speed_accuracy_front(study), (std::vector<std::size_t>{6}));
  EXPECT_TRUE(study.proven());
}

// The cache proves itself (ladder_cache.h): one changed byte, another
// build's seal, a cell that is not a number, a second reference row, a cut
// file or a FIFO in its place, and it is not used. On two ranks an unused
// cache is refused with its reason (one rank would compute the ladder
// again, minutes); the sound cache beside each is read.
TEST(ModelChoice, UsesOnlyACacheThatProvesItself)
{
  const Scene scene     = read_scene(mueller);
  const std::string dir = (std::filesystem::temp_directory_path() / "beamslider_model_choice_seal").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/ladder-" + scene_content_key(scene) + ".csv";
  const std::string header =
    "rung,family,n_modes,static_corrections,ritz_blocks,n_elements,integrator,time_step_s,damped_modes,theta,"
    "reference,cost_units,final_x_median,w1,w1_high,refined_alike\n";
  const std::string rom = "ROM N=8,rom,8,0,1,0,explicit,1e-05,0,0.5,0,8.5e6,0.40,0.002,0.003,1\n";
  const std::string fe  = "FE,fe,0,0,1,32,implicit,1e-05,0,0.51,1,1.56e9,0.41,0.002,0.003,1\n";
  const std::string sound = choice_cache_file_text(header + rom + fe);
  std::string why;
  const auto write = [&](const std::string &text) {
    std::filesystem::remove(path);
    std::ofstream(path) << text;
  };
  const auto refused_because = [&](const std::string &reason) {
    try
      {
        choose_model(scene, std::nullopt, dir, why, 2);
        ADD_FAILURE() << "a cache that should be refused (" << reason << ") was used";
      }
    catch (const InputError &e)
      {
        EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
      }
  };
  write(sound);
  EXPECT_EQ(choose_model(scene, std::nullopt, dir, why, 2).n_modes, 8u) << why;

  std::string changed = sound;
  changed[changed.find("0.40,")] = '5'; // ROM N=8 now ends at 5.40 L
  write(changed);
  refused_because("checksum does not match");
  std::string other_build = sound;
  other_build.replace(other_build.find(", build ") + 8, 10, "beamslider 0.0.0");
  write(other_build);
  refused_because("another build or format");
  write(choice_cache_file_text(header + "ROM N=8,rom,8,0,1,0,explicit,x,0,0.5,0,8.5e6,0.40,0.002,0.003,1\n" + fe));
  refused_because("not a number");
  write(choice_cache_file_text(header + rom + fe + fe));
  refused_because("2 reference rows");
  write(sound.substr(0, sound.size() - 10));
  refused_because("checksum does not match");
  std::filesystem::remove(path);
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  refused_because("not a regular file (a FIFO)");
  std::filesystem::remove_all(dir);
}
