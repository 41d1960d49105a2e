// Tests of the prescribed-slider-position sweep (runs/prescribed_position_sweep)
// and of the Eq. 5 resonance curve (reduced/resonance_curve), on the reduced
// model of the ideal-clamp mueller2023 beam with the analytic clamped–clamped
// modes of test_reduced_clamped_beam.h (no FE code involved).
#include "runs/prescribed_position_sweep.h"
#include "reduced/beam_backbone.h"
#include "reduced/resonance_curve.h"
#include "reduced/rom_beam_system.h"
#include "test_reduced_clamped_beam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace beamslider;
using beamslider_test::ClampedBeam;
using beamslider_test::ideal_clamp_scene;

namespace
{
  PcsPoint point(const double x, const double amplitude, const double fx)
  {
    PcsPoint p;
    p.x_over_L         = x;
    p.amplitude_over_h = amplitude;
    p.mean_fx          = fx;
    return p;
  }
} // namespace

// The resonance curve is defined by ω̃₁(ŵ, x_C) = 2π f_ex with ω̃₁ from seed
// Eq. 5: put the returned amplitude back into Eq. 5 (a separate function,
// checked against harmonic balance in test_reduced_backbone) and get f_ex; where
// the slider's added inertia alone keeps ω̃₁(0, x_C) above 2π f_ex there is no
// resonance and the curve must say so (NaN), nowhere else.
TEST(ResonanceCurve, SatisfiesEq5AndIsUndefinedExactlyAboveTheExcitation)
{
  const Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  const ReducedOrderModel rom(beam.modes(3).basis, scene.damping_ratio, true);
  const ResonanceCurveData data =
    ResonanceCurveData::from_model(rom, scene.slider_mass(), scene.slider_inertia(), scene.beam.thickness);
  const double f_ex = 124., Omega = 2. * M_PI * f_ex;
  unsigned int n_defined = 0, n_undefined = 0;
  for (double x_over_L = 0.05; x_over_L <= 0.5 + 1e-12; x_over_L += 0.01)
    {
      const double x = x_over_L * beam.L;
      Eigen::VectorXd phi, dphi;
      rom.basis().evaluate(x, phi, dphi);
      const double linear = single_mode_backbone_frequency_with_slider(data.omega_1, data.b_111, 0., scene.slider_mass(),
                                                                       scene.slider_inertia(), phi[0], dphi[0]);
      const double a = resonance_amplitude_over_h(rom, data, x, f_ex);
      if (linear > Omega)
        {
          EXPECT_TRUE(std::isnan(a)) << "x_C/L = " << x_over_L;
          ++n_undefined;
          continue;
        }
      ASSERT_TRUE(std::isfinite(a)) << "x_C/L = " << x_over_L;
      ++n_defined;
      const double q_hat = a * scene.beam.thickness / std::abs(data.phi_1_centre);
      const double omega = single_mode_backbone_frequency_with_slider(data.omega_1, data.b_111, q_hat,
                                                                      scene.slider_mass(), scene.slider_inertia(),
                                                                      phi[0], dphi[0]);
      EXPECT_NEAR(omega / Omega, 1., 1e-12) << "x_C/L = " << x_over_L;
    }
  // Both regimes occur for the mueller2023 beam at 124 Hz (bare beam ~ 257
  // Hz, slider three times the beam's mass): the test covers both branches.
  EXPECT_GT(n_defined, 3u);
  EXPECT_GT(n_undefined, 3u);
}

// F̄_x(x) = (x − 0.2)(x − 0.35) sampled every 0.01: zero crossings at 0.2
// (F̄_x falling: stable) and 0.35 (rising: unstable); linear interpolation of a
// parabola on 0.01 steps is exact at sample points and within (Δx)²/4·|F''|/|F'|
// ≈ 2e-4 elsewhere. A factor-3 amplitude step between 0.26 and 0.27 is the
// jump; a smooth branch has none.
TEST(PcsAnalysis, FindsZeroCrossingsWithStabilityAndTheJump)
{
  std::vector<PcsPoint> branch, smooth;
  for (int i = 0; i <= 40; ++i)
    {
      const double x = 0.1 + 0.01 * i;
      const double a = x < 0.265 ? 0.2 : 0.6;
      branch.push_back(point(x, a, (x - 0.2) * (x - 0.35)));
      smooth.push_back(point(x, 0.2 + x, 1.));
    }
  const std::vector<ForceZeroCrossing> c = force_zero_crossings(branch);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].x_over_L, 0.2, 1e-9);
  EXPECT_TRUE(c[0].stable);
  EXPECT_NEAR(c[1].x_over_L, 0.35, 1e-9);
  EXPECT_FALSE(c[1].stable);

  // The same branch walked downward gives the same crossings.
  std::vector<PcsPoint> reversed(branch.rbegin(), branch.rend());
  const std::vector<ForceZeroCrossing> cr = force_zero_crossings(reversed);
  ASSERT_EQ(cr.size(), 2u);
  EXPECT_NEAR(cr[0].x_over_L, 0.2, 1e-9);
  EXPECT_TRUE(cr[0].stable);

  const auto jump = largest_amplitude_jump(branch);
  ASSERT_TRUE(jump.has_value());
  EXPECT_NEAR(jump->x_before_over_L, 0.26, 1e-12);
  EXPECT_NEAR(jump->x_after_over_L, 0.27, 1e-12);
  EXPECT_NEAR(jump->amplitude_after_over_h / jump->amplitude_before_over_h, 3., 1e-12);
  EXPECT_FALSE(largest_amplitude_jump(smooth).has_value());
  EXPECT_TRUE(force_zero_crossings(smooth).empty());
}

TEST(PcsSweep, RejectsRangesThatPutTheSliderOffTheBeam)
{
  const Scene scene = ideal_clamp_scene();
  PcsSweepSettings s;
  s.low_over_L = 0.01; // window corners at x_C − B/2 < 0
  try
    {
      s.validate(scene);
      FAIL() << "accepted x_C/L = 0.01";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("low x_C/L"), std::string::npos) << e.what();
    }
  s            = PcsSweepSettings::for_scene(scene);
  s.step_over_L = 0;
  EXPECT_THROW(s.validate(scene), InputError);
}

// The clamped–clamped beam and the slider are symmetric about x = L/2, so the
// sweep at x_C and at L − x_C must give the same amplitude and opposite F̄_x
// (the horizontal force mirrors). The two runs are mirror images up to
// round-off; the rattling slider amplifies round-off, so the means are
// compared within three standard errors of the per-period spread (plus 2 %
// of the amplitude: the averaging window is finite). Also checks that the
// slider is held: every point sits exactly on its grid position.
TEST(PcsSweep, MirroredBranchesAgree)
{
  Scene scene = ideal_clamp_scene();
  const ClampedBeam beam;
  PcsSweepSettings s;
  s.step_over_L  = 0.01;
  s.settle_time  = 0.3;
  s.average_time = 0.2;

  s.low_over_L  = 0.20;
  s.high_over_L = 0.23;
  RomBeamSystem left_beam = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  const PcsBranch left    = run_pcs_branch(scene, left_beam, s, scene.time_stepping.time_step, SweepDirection::up);

  s.low_over_L             = 0.77;
  s.high_over_L            = 0.80;
  RomBeamSystem right_beam = RomBeamSystem::from_scene(scene, beam.modes(5).basis);
  const PcsBranch right    = run_pcs_branch(scene, right_beam, s, scene.time_stepping.time_step, SweepDirection::down);

  ASSERT_EQ(left.last_run.status, RunStatus::completed) << left.last_run.message;
  ASSERT_EQ(right.last_run.status, RunStatus::completed) << right.last_run.message;
  ASSERT_EQ(left.points.size(), 4u);
  ASSERT_EQ(right.points.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i)
    {
      const PcsPoint &a = left.points[i], &b = right.points[i];
      EXPECT_NEAR(a.x_over_L, 0.20 + 0.01 * i, 1e-12);
      EXPECT_NEAR(a.x_over_L + b.x_over_L, 1., 1e-12);
      const double n = a.n_periods;
      ASSERT_GE(n, 20);
      const double amplitude_tolerance =
        3. * std::hypot(a.amplitude_std_over_h, b.amplitude_std_over_h) / std::sqrt(n) + 0.02 * a.amplitude_over_h;
      const double force_tolerance = 3. * std::hypot(a.mean_fx_std, b.mean_fx_std) / std::sqrt(n) + 1e-4;
      std::cout << "x_C/L = " << a.x_over_L << ": amplitude " << a.amplitude_over_h << " / " << b.amplitude_over_h
                << " h (std " << a.amplitude_std_over_h << "), F_x " << a.mean_fx << " / " << -b.mean_fx << " N (std "
                << a.mean_fx_std << ")" << std::endl;
      EXPECT_NEAR(a.amplitude_over_h, b.amplitude_over_h, amplitude_tolerance) << "x_C/L = " << a.x_over_L;
      EXPECT_NEAR(a.mean_fx, -b.mean_fx, force_tolerance) << "x_C/L = " << a.x_over_L;
      EXPECT_GT(a.amplitude_over_h, 0.01); // the beam does vibrate
    }
}

// The crossing's interval on a constructed linear force with a constant 95 %
// half width c: F̄_x = −k (x − x*), so the bands F̄_x ± c cross zero at
// x* ± c/k exactly (linear interpolation is exact on linear data). When the
// half width exceeds |F̄_x| at a neighbour, that band does not change sign
// within the bracket: the interval reaches the bracket's edge and the
// crossing is unresolved.
TEST(PcsAnalysis, ZeroCrossingIntervalFromTheForceBands)
{
  const double k = 2.0, x_star = 0.3237;
  for (const double c : {0.002, 0.015})
    {
      std::vector<PcsPoint> branch;
      for (int i = 0; i <= 20; ++i)
        {
          const double x = 0.25 + 0.01 * i;
          PcsPoint p      = point(x, 0.5, -k * (x - x_star));
          p.mean_fx_ci95  = c;
          branch.push_back(p);
        }
      const std::vector<ForceZeroCrossing> crossings = force_zero_crossings(branch);
      ASSERT_EQ(crossings.size(), 1u);
      const ForceZeroCrossing &z = crossings[0];
      EXPECT_NEAR(z.x_over_L, x_star, 1e-12);
      EXPECT_TRUE(z.stable);
      if (c / k < 0.0037) // inside the bracket [0.32, 0.33] on both sides
        {
          EXPECT_TRUE(z.resolved);
          EXPECT_NEAR(z.x_low_over_L, x_star - c / k, 1e-12);
          EXPECT_NEAR(z.x_high_over_L, x_star + c / k, 1e-12);
        }
      else
        {
          EXPECT_FALSE(z.resolved);
          EXPECT_NEAR(z.x_low_over_L, 0.32, 1e-12);
          EXPECT_NEAR(z.x_high_over_L, 0.33, 1e-12);
        }
    }
}
