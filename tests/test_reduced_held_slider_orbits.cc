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

// Why the rattling system has no edge state between its low and high
// regimes (doc/physics.md §12): at x_C/L = 0.40 the ideal-clamp reduced
// model is bistable (about 0.045 h and 1.12 h). Bisecting on the line from
// the low state to the high one finds the boundary of their basins to
// round-off. Were it the stable manifold of a saddle (an unstable orbit or a
// chaotic saddle, what edge tracking follows), two states ε either side of
// it would part like e^{λk} ε, and their fates would take ~ ln(1/ε)/λ
// periods to show: halving the distance would add the same number of
// periods. Instead the map jumps there: after one period the two states
// are apart by the same finite fraction of the low–high distance at
// ε = 1e-6 and at ε = 1e-12, and their fates show after the same number of
// periods (a corner's contact set differs between them: a discontinuity of
// the rigid slider's impact map, not a saddle).
TEST(HeldSliderMap, TheBasinBoundaryOfTheRattlingSliderIsAJumpOfTheMapNotASaddle)
{
  const Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  HeldSliderMap map(scene, rom, scene.time_stepping.time_step);
  const double x = 0.40;
  Eigen::VectorXd low = map.resting(x), high = map.resting(x);
  BeamPointKinematics centre;
  rom.evaluate(0.5 * rom.length(), Eigen::VectorXd::Unit(rom.n_dofs(), 0), centre);
  high[0] = 3. * scene.beam.thickness / centre.w;
  double a_low = 0, a_high = 0;
  for (int i = 0; i < 200; ++i)
    {
      const PeriodMapValue l = map(low, x), h = map(high, x);
      low  = l.end;
      high = h.end;
      if (i >= 150)
        {
          a_low += l.observables[0] / 50;
          a_high += h.observables[0] / 50;
        }
    }
  ASSERT_LT(a_low, 0.1);
  ASSERT_GT(a_high, 0.8); // bistable here

  // The fate of a state: +1 once five periods in a row are above the
  // upper quarter of [a_low, a_high], −1 below the lower quarter; and when.
  const double upper = a_high - 0.25 * (a_high - a_low), lower = a_low + 0.25 * (a_high - a_low);
  struct Fate
  {
    int side = 0, periods = 0;
  };
  const auto fate = [&](Eigen::VectorXd y) {
    Fate f;
    for (int above = 0, below = 0; f.periods < 400; ++f.periods)
      {
        const PeriodMapValue v = map(y, x);
        y                      = v.end;
        above                  = v.observables[0] > upper ? above + 1 : 0;
        below                  = v.observables[0] < lower ? below + 1 : 0;
        if (above == 5 || below == 5)
          {
            f.side = above == 5 ? 1 : -1;
            break;
          }
      }
    return f;
  };
  double a = 0, b = 1;
  for (int i = 0; i < 48; ++i)
    {
      const double m = 0.5 * (a + b);
      const int side = fate(low + m * (high - low)).side;
      ASSERT_NE(side, 0) << "undecided after 400 periods at alpha = " << m;
      (side > 0 ? b : a) = m;
    }

  const Eigen::VectorXd scale = map.scale(high);
  const auto distance = [&](const Eigen::VectorXd &p, const Eigen::VectorXd &q) {
    return (p - q).cwiseQuotient(scale).lpNorm<Eigen::Infinity>();
  };
  const double span = distance(high, low);
  double parted[2];
  Fate fates[2][2];
  const double eps[2] = {1e-6, 1e-12};
  for (int e = 0; e < 2; ++e)
    {
      const Eigen::VectorXd below = low + (a - eps[e]) * (high - low), above = low + (b + eps[e]) * (high - low);
      parted[e]   = distance(map(above, x).end, map(below, x).end) / span;
      fates[e][0] = fate(below);
      fates[e][1] = fate(above);
      std::cout << "eps " << eps[e] << ": one period parts them by " << parted[e] << " of the low-high distance; fates "
                << fates[e][0].side << " after " << fates[e][0].periods << ", " << fates[e][1].side << " after "
                << fates[e][1].periods << " periods" << std::endl;
    }
  // A smooth map would part them by |μ| ε, a few ε: here by a finite
  // fraction, the same at both ε.
  EXPECT_GT(parted[1], 1e-3);
  EXPECT_NEAR(parted[0], parted[1], 0.1 * parted[1]);
  for (int e = 0; e < 2; ++e)
    {
      EXPECT_EQ(fates[e][0].side, -1);
      EXPECT_EQ(fates[e][1].side, 1);
    }
  // ln(1e6) more periods for the closer pair were it a saddle with λ of
  // order one per period; here the same count.
  EXPECT_EQ(fates[1][0].periods, fates[0][0].periods);
  EXPECT_EQ(fates[1][1].periods, fates[0][1].periods);
}
