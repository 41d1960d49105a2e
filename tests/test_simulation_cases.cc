// The named adaptation cases (verification/simulation_cases): each applies
// the parameters doc/scenes.md gives for it; an unknown name is an error that
// lists the valid ones; the verdict finds a jump, a turn and recurrent jumps
// in constructed period records where we put them; a beam model whose solver
// fails stops the run cleanly with time and place.
#include "runs/adaptation_run.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "reduced/rom_beam_system.h"
#include "verification/studies/simulation_cases.h"

#include "tests/synthetic_periods.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>

using namespace beamslider;

namespace
{
  const std::string mueller = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

} // namespace

// doc/scenes.md: frequency [Hz], base acceleration [m/s²], start x_C/L.
TEST(SimulationCases, ApplyThePublishedParameters)
{
  struct Expected
  {
    std::string name;
    double f, a, x;
  };
  for (const Expected &e : std::vector<Expected>{{"signature-move", 124, 14, 0.3},
                                                 {"trivial-adaption", 104, 14, 0.3},
                                                 {"relaxation-oscillation", 126, 10, 0.3},
                                                 {"self-damping", 124, 6, 0.3},
                                                 {"trivial-adaption-106", 106, 10, 0.3},
                                                 {"signature-move-106", 106, 10, 0.4}})
    {
      const Scene s = read_case_scene(mueller, find_case(e.name), {});
      EXPECT_DOUBLE_EQ(s.excitation.frequency_hz, e.f) << e.name;
      EXPECT_DOUBLE_EQ(s.excitation.acceleration_amplitude, e.a) << e.name;
      EXPECT_DOUBLE_EQ(s.initial.slider_position_over_L, e.x) << e.name;
      EXPECT_GE(s.time_stepping.end_time, 60.) << e.name; // the published runs: 60–120 s
      EXPECT_TRUE(s.discretisation.geometric_nonlinearity);
      EXPECT_DOUBLE_EQ(s.contact.friction_coefficient, 0.2);
      EXPECT_DOUBLE_EQ(s.slider.window_height_ratio, 1.05);
    }
  // The ablations change one thing of the signature move each.
  const Scene base = read_case_scene(mueller, find_case("signature-move"), {});
  EXPECT_FALSE(read_case_scene(mueller, find_case("no-geometric-nonlinearity"), {}).discretisation.geometric_nonlinearity);
  EXPECT_DOUBLE_EQ(read_case_scene(mueller, find_case("frictionless"), {}).contact.friction_coefficient, 0.);
  EXPECT_DOUBLE_EQ(read_case_scene(mueller, find_case("tight-fit"), {}).slider.window_height_ratio, 1.01);
  EXPECT_DOUBLE_EQ(read_case_scene(mueller, find_case("large-clearance"), {}).slider.window_height_ratio, 1.2);
  const Scene heavy = read_case_scene(mueller, find_case("heavy-slider"), {});
  EXPECT_DOUBLE_EQ(heavy.slider_mass(), 2 * base.slider_mass());
  EXPECT_DOUBLE_EQ(heavy.slider_inertia(), 2 * base.slider_inertia());
  EXPECT_DOUBLE_EQ(heavy.slider.window_height_ratio, 1.1);
  EXPECT_DOUBLE_EQ(heavy.excitation.frequency_hz, 124.);

  // The user's --set comes after the case's.
  const Scene shortened = read_case_scene(mueller, find_case("signature-move"), {"Time stepping/End time=2"});
  EXPECT_DOUBLE_EQ(shortened.time_stepping.end_time, 2.);
}

TEST(SimulationCases, UnknownNameListsTheCases)
{
  try
    {
      find_case("signature-mvoe");
      FAIL() << "accepted a misspelt case";
    }
  catch (const InputError &e)
    {
      const std::string m = e.what();
      EXPECT_NE(m.find("signature-mvoe"), std::string::npos) << m;
      for (const SimulationCase &c : simulation_cases())
        EXPECT_NE(m.find(c.name), std::string::npos) << m;
    }
}

// A constructed signature move: x_C/L 0.3 → 0.25 over 10 s at amplitude 0.1 h,
// then a jump to 1.5 h and x_C/L back to 0.35 by 20 s, held to 30 s. The
// verdict must say: toward the clamp, a jump just after 10 s (while the 0.1 s
// envelope rises, within 0.1 s of the step), a turn at 0.25,
// ending at 0.35 with 1.5 h; no disagreement with the signature-move
// expectation, a disagreement on the turn with large-clearance's.
TEST(CaseVerdict, FindsTheJumpAndTheTurnWhereTheyWerePut)
{
  auto x = [](double t) { return t < 10 ? 0.3 - 0.005 * t : t < 20 ? 0.25 + 0.01 * (t - 10) : 0.35; };
  auto a = [](double t) { return t < 10 ? 0.1 : 1.5; };
  RunResult done;
  const CaseVerdict v = case_verdict(synthetic_periods(30, x, a), done);
  EXPECT_EQ(v.initial_direction, "toward the clamp");
  EXPECT_TRUE(v.jumped);
  EXPECT_GT(v.jump_time, 10.);         // not before the step ...
  EXPECT_LE(v.jump_time, 10.1 + 0.01); // ... and within the 0.1 s envelope's rise
  EXPECT_TRUE(v.turned);
  EXPECT_NEAR(v.turn_position, 0.25, 0.001);
  EXPECT_NEAR(v.final_position, 0.35, 1e-9);
  EXPECT_NEAR(v.final_amplitude, 1.5, 1e-9);
  EXPECT_EQ(v.n_upward_jumps, 1u);
  EXPECT_FALSE(v.crosses_centre);
  EXPECT_EQ(disagreements(v, find_case("signature-move").expected), "");
  EXPECT_NE(disagreements(v, find_case("large-clearance").expected).find("turn-around"), std::string::npos);
}

// Monotone drift toward the centre with a growing amplitude: no jump, no
// turn (the farthest point from the centre is the start), agrees with
// trivial-adaption; three bursts to the high level count as three upward
// jumps; a slider that passes x = L/2 is said to cross the centre.
TEST(CaseVerdict, TrivialAdaptionRecurrentJumpsAndCentreCrossing)
{
  RunResult done;
  const CaseVerdict trivial =
    case_verdict(synthetic_periods(30, [](double t) { return 0.3 + 0.005 * t; }, [](double t) { return 0.1 + 0.03 * t; }), done);
  EXPECT_EQ(trivial.initial_direction, "toward the centre");
  EXPECT_FALSE(trivial.jumped);
  EXPECT_FALSE(trivial.turned);
  EXPECT_EQ(disagreements(trivial, find_case("trivial-adaption").expected), "");

  const CaseVerdict bursts = case_verdict(
    synthetic_periods(40, [](double) { return 0.3; },
            [](double t) { return (t > 5 && t < 10) || (t > 15 && t < 20) || (t > 25 && t < 30) ? 1.5 : 0.1; }),
    done);
  EXPECT_EQ(bursts.n_upward_jumps, 3u);
  EXPECT_EQ(disagreements(bursts, find_case("relaxation-oscillation").expected), "");

  const CaseVerdict cycling =
    case_verdict(synthetic_periods(20, [](double t) { return 0.5 - 0.2 * std::cos(t); }, [](double) { return 0.5; }), done);
  EXPECT_TRUE(cycling.crosses_centre);
  EXPECT_EQ(disagreements(cycling, find_case("frictionless").expected), "");
}

// A beam model whose own solver gives up (as the FE model's Newton iteration
// may) stops the run with RunStatus::beam_solver_failure, the time of the
// failed step in the message, and the state before the step kept (finite).
TEST(SimulationRun, BeamSolverFailureStopsCleanly)
{
  class FailingBeam : public RomBeamSystem
  {
  public:
    explicit FailingBeam(const RomBeamSystem &rom)
      : RomBeamSystem(rom)
    {}

  protected:
    void compute_free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                               Eigen::VectorXd &u_free) override
    {
      if (t_M > 0.01)
        throw std::runtime_error("Newton did not converge (test)");
      RomBeamSystem::compute_free_velocity(t_M, q_M, u_B, dt, u_free);
    }
  };
  const Scene scene = read_scene(mueller);
  const FEBeam fe(scene);
  FailingBeam beam(RomBeamSystem::from_scene(scene, make_modal_basis(fe, compute_bending_modes(fe, 3), 3)));
  RunOptions options = RunOptions::from_scene(scene);
  options.end_time   = 0.1;
  AdaptationRun run(scene, beam, options);
  std::vector<TraceRow> rows;
  run.on_trace_row       = [&rows](const TraceRow &r) { rows.push_back(r); };
  const RunResult result = run.run();
  EXPECT_EQ(result.status, RunStatus::beam_solver_failure);
  EXPECT_NEAR(result.t_end, 0.01, 2 * scene.time_stepping.time_step);
  EXPECT_NE(result.message.find("t = 0.01"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("Newton did not converge"), std::string::npos) << result.message;
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(rows.back().t, result.t_end, 1e-12);
  for (const TraceRow &r : rows)
    EXPECT_TRUE(std::isfinite(r.w_center) && std::isfinite(r.slider_x_over_L));
}

// The scene's Solvers settings reach the solvers: with a cap of one sweep
// per contact solve the ROM run stops at its first contact that needs more,
// and with one Newton iteration per step the FE step cannot converge (two
// are the floor of its test); the same runs complete with the defaults.
TEST(SimulationRun, SolverSettingsOfTheSceneReachTheSolvers)
{
  auto run_for = [](const std::vector<std::string> &overrides, const bool fe) {
    const Scene scene = read_scene(mueller, overrides);
    const FEBeam mesh(scene);
    std::unique_ptr<BeamSystem> beam =
      fe ? make_fe_beam_system(scene)
         : std::make_unique<RomBeamSystem>(
             RomBeamSystem::from_scene(scene, make_modal_basis(mesh, compute_bending_modes(mesh, 5), 5)));
    RunOptions options        = RunOptions::from_scene(scene);
    options.end_time          = fe ? 0.002 : 0.2;
    options.progress_interval = 1e9;
    AdaptationRun run(scene, *beam, options);
    return run.run();
  };
  EXPECT_EQ(run_for({}, false).status, RunStatus::completed);
  const RunResult capped = run_for({"Solvers/Contact sweeps=1", "Contact/Solver=projected"}, false);
  EXPECT_EQ(capped.status, RunStatus::contact_solver_failure) << capped.message;
  EXPECT_EQ(run_for({}, true).status, RunStatus::completed);
  const RunResult newton = run_for({"Solvers/Newton iterations=1"}, true);
  EXPECT_EQ(newton.status, RunStatus::beam_solver_failure) << newton.message;
}
