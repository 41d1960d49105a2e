// The held slider's stroboscopic map (runs/held_slider_map.h) and the
// attached-slider model (reduced/attached_slider_model.h) on the reduced
// model of the ideal-clamp mueller2023 beam (test_reduced_clamped_beam.h):
// the map against the run loop's own period record, its unknowns, and the
// attached model's steady state by shooting against its frequency-domain
// solution.
#include "reduced/attached_slider_model.h"
#include "reduced/rom_beam_system.h"
#include "runs/adaptation_run.h"
#include "runs/held_slider_map.h"
#include "test_reduced_clamped_beam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace beamslider;
using beamslider_test::ClampedBeam;
using beamslider_test::ideal_clamp_scene;


// One period of the map is one period of AdaptationRun with the slider held,
// started from the same resting state at the same step: the same end state,
// amplitude and mean horizontal force, to round-off.
TEST(HeldSliderMap, OnePeriodIsThePrescribedRunsPeriod)
{
  Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  RomBeamSystem rom_map = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  HeldSliderMap map(scene, rom_map, scene.time_stepping.time_step);
  const double T = 1. / scene.excitation.frequency_hz;
  EXPECT_NEAR(map.step() * map.steps_per_map(), T, 1e-15);
  EXPECT_LE(map.step(), scene.time_stepping.time_step);

  const double x = 0.3;
  // Two periods, so that the slider has left its resting state.
  Eigen::VectorXd y          = map.resting(x);
  const PeriodMapValue first = map(y, x);
  const PeriodMapValue second = map(first.end, x);

  scene.initial.slider_position_over_L = x;
  RomBeamSystem rom_run                = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  RunOptions options                   = RunOptions::from_scene(scene, map.step());
  options.prescribed_slider_position   = true;
  options.output_rate                  = 1.;
  AdaptationRun run(scene, rom_run, options);
  std::vector<PeriodRecord> periods;
  run.on_period = [&](const PeriodRecord &r) { periods.push_back(r); };
  const RunResult result = run.run_until(2. * T); // llround(2T / Δt): exactly two maps' steps
  ASSERT_EQ(result.status, RunStatus::completed) << result.message;
  ASSERT_GE(periods.size(), 2u);
  for (int k = 0; k < 2; ++k)
    {
      const PeriodMapValue &v = k == 0 ? first : second;
      EXPECT_NEAR(v.observables[0], periods[k].amplitude_over_h, 1e-9 * periods[k].amplitude_over_h) << "period " << k;
      EXPECT_NEAR(v.observables[1], periods[k].mean_horizontal_contact_force,
                  1e-9 * std::abs(periods[k].mean_horizontal_contact_force) + 1e-15)
        << "period " << k;
    }
  // The run's state after two periods is the map's, up to the time origin
  // (the map restarts at t = 0 each period; the excitation is periodic).
  const Eigen::VectorXd y_run = map.pack(run.state());
  EXPECT_LT((y_run - second.end).cwiseQuotient(map.scale(second.end)).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_GT(periods[1].amplitude_over_h, 0.); // the beam does move
}

// The slider's unknowns are relative to the beam under x_C, so that packing
// a state and unpacking it gives it back, and a state unpacked at another
// x_C keeps each corner's gap to the beam there (to the curvature under the
// window): the slider is carried along, not left where the beam was.
TEST(HeldSliderMap, UnknownsAreRelativeToTheBeamUnderTheSlider)
{
  const Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  HeldSliderMap map(scene, rom, scene.time_stepping.time_step);
  Eigen::VectorXd y = map.resting(0.3);
  for (int i = 0; i < 20; ++i)
    y = map(y, 0.3).end; // a vibrating beam (w' ≠ 0 under the slider)
  const SystemState s = map.unpack(y, 0.3);
  EXPECT_LT((map.pack(s) - y).cwiseAbs().maxCoeff(), 1e-15 * y.cwiseAbs().maxCoeff() + 1e-18);

  // Carried to 0.32 L: z_C − w(x_C) and β − atan w'(x_C) are the same numbers.
  const SystemState moved = map.unpack(y, 0.32);
  BeamPointKinematics p;
  rom.evaluate(0.32 * rom.length(), moved.q, p);
  EXPECT_NEAR(moved.s[1] - p.w, y[y.size() - 4], 1e-15);
  EXPECT_NEAR(moved.s[2] - std::atan(p.dw), y[y.size() - 3], 1e-15);
  EXPECT_EQ(moved.v[0], 0.); // the horizontal motion is held
}

// With the slider attached, no cubic restoring force and no gravity, the
// system is linear and periodically forced: shooting from rest converges in
// one Newton step (a linear map) onto the steady state that the frequency-
// domain solve (−Ω² M + iΩC + K) Q = F gives independently.
TEST(AttachedSliderModel, LinearSteadyStateByShootingIsTheFrequencyDomainSolution)
{
  const Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  const ReducedOrderModel rom(beam.modes(4).basis, scene.damping_ratio, false);
  const AttachedSliderModel model(rom, scene.slider_mass(), scene.slider_inertia(), 0.,
                                  BaseExcitation::from_scene(scene.excitation), scene.beam.thickness);
  for (const double x : {0.2, 0.35})
    {
      const Eigen::VectorXd expected = model.linear_response(x);
      ShootingSettings s;
      s.scale     = model.scale(expected);
      s.tolerance = 1e-10;
      const ShootingOutcome out = shoot(model, Eigen::VectorXd::Zero(expected.size()), x, s);
      ASSERT_TRUE(out.converged) << out.reason;
      EXPECT_LE(out.point.iterations, 2u);
      // RK4 at ≥ 400 steps per period: relative error ~ (Ω Δt)⁴ / 120.
      EXPECT_LT((out.point.y - expected).cwiseQuotient(s.scale).cwiseAbs().maxCoeff(), 1e-6) << "x_C/L = " << x;
      EXPECT_TRUE(out.point.stable()); // a damped linear system
      EXPECT_GT(out.point.observables[0], 0.);
    }
}

// Validation of the attached model on the stable high branch (doc/physics.md
// §12): where the beam vibrates at about a thickness, the rattling held
// slider leaves the beam's amplitude within a few per cent of the attached
// slider's. The rattling one started from a large first-mode deflection,
// settled 150 periods, averaged over 40 (its period-to-period spread is a
// few per cent; the mean's standard error a fraction of that).
TEST(AttachedSliderModel, CarriesTheRattlingSlidersAmplitudeOnTheHighBranch)
{
  const Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  const ReducedOrderModel rom(beam.modes(5).basis, scene.damping_ratio, true);
  RomBeamSystem rattling = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  HeldSliderMap map(scene, rattling, scene.time_stepping.time_step);
  const AttachedSliderModel attached(rom, scene.slider_mass(), scene.slider_inertia(), scene.contact.gravity,
                                     BaseExcitation::from_scene(scene.excitation), scene.beam.thickness);
  for (const double x : {0.38, 0.42})
    {
      // Rattling: the first mode at 3 h at the centre, the slider resting relative to the beam.
      Eigen::VectorXd y = map.resting(x);
      BeamPointKinematics centre;
      rattling.evaluate(0.5 * rattling.length(), Eigen::VectorXd::Unit(rattling.n_dofs(), 0), centre);
      y[0] = 3. * scene.beam.thickness / centre.w;
      for (int i = 0; i < 150; ++i)
        y = map(y, x).end;
      double sum = 0, sum2 = 0;
      const int n = 40;
      for (int i = 0; i < n; ++i)
        {
          const PeriodMapValue v = map(y, x);
          sum += v.observables[0];
          sum2 += v.observables[0] * v.observables[0];
          y = v.end;
        }
      const double mean = sum / n, spread = std::sqrt(std::max(0., sum2 / n - mean * mean));

      // Attached: shooting from the rattling state's beam part.
      Eigen::VectorXd z(2 * rom.n_modes());
      z << y.head(rom.n_modes()), y.segment(rom.n_modes(), rom.n_modes());
      ShootingSettings s;
      s.scale     = attached.scale(z);
      s.tolerance = 1e-8;
      const ShootingOutcome out = shoot(attached, z, x, s);
      ASSERT_TRUE(out.converged) << out.reason;
      std::cout << "x_C/L = " << x << ": rattling " << mean << " h (spread " << spread << "), attached "
                << out.point.observables[0] << " h, stable " << out.point.stable() << std::endl;
      EXPECT_GT(mean, 0.8); // the high branch
      EXPECT_TRUE(out.point.stable());
      EXPECT_NEAR(out.point.observables[0], mean, 0.05 * mean) << "x_C/L = " << x;
    }
}
