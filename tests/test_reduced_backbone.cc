// Harmonic-balance backbones of the reduced model (reduced/harmonic_balance.h)
// checked against independent results on the mueller2023 beam with an ideal
// clamp (analytic clamped–clamped modes, tests/test_reduced_clamped_beam.h):
//
// - seed Eq. 4, ω² = ω₁² + ¾ b₁₁₁ q̂², is the exact single-mode, single-harmonic
//   HB solution; written as (ω/ω₁)² = 1 + c (ŵ_{L/2}/h)², doc/verification.md quotes
//   c ≈ 0.5395 for this beam;
// - a single mode with many harmonics is the undamped Duffing oscillator
//   q̈ + ω₀² q + b q³ = 0, whose exact frequency at turning-point amplitude A is
//   ω = (π/2) sqrt(ω₀² + bA²) / K(m), m = bA² / (2(ω₀² + bA²))
//   (complete elliptic integral of the first kind; e.g. Nayfeh & Mook 1979);
//   Lindstedt–Poincaré gives, with ε = b/ω₀², ω/ω₀ = 1 + ⅜εA² − 21/256 ε²A⁴ and
//   a first harmonic a₁ = A − εA³/32, hence ω/ω₀ = 1 + ⅜εa₁² − 15/256 ε²a₁⁴,
//   while Eq. 4 expands to 1 + ⅜εa₁² − 18/256 ε²a₁⁴: at a given first-harmonic
//   amplitude the exact backbone lies ABOVE Eq. 4 by 3/256 ε² a₁⁴ ω₀;
// - a multi-mode HB point is a periodic orbit: integrating the ODE over one
//   period from it (RK4) must return to it;
// - the solver does not care in which coordinates the system is written: a
//   dense M, K (q = P x) gives the same backbone.
#include "reduced/beam_backbone.h"
#include "reduced/rom_operator.h"
#include "tests/test_reduced_clamped_beam.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cmath>
#include <iostream>

using namespace beamslider;
using beamslider_test::ClampedBeam;
using beamslider_test::relative_error;

namespace
{
  struct RomSetup
  {
    ClampedBeam beam;
    ClampedBeam::Modes modes;
    ReducedOrderModel rom;
    Eigen::VectorXd output; // φ_n(L/2): y = w(L/2) [m]

    explicit RomSetup(const unsigned int N)
      : modes(beam.modes(N))
      , rom(modes.basis, 0.)
    {
      Eigen::VectorXd dphi;
      modes.basis.evaluate(beam.L / 2, output, dphi);
    }

    double omega_1() const { return modes.basis.omega[0]; }
    // b₁₁₁ = (k_ax/2) K'₁₁² (seed Eq. 3 after integration by parts).
    double b_111() const { return rom.analytic_cubic_terms()[0].value; }
  };

  BackboneSettings settings_for(const RomSetup &s, const unsigned int H, const double w_end_over_h)
  {
    BackboneSettings b;
    b.hb.n_harmonics   = H;
    b.output           = s.output;
    b.start_amplitude  = 0.01 * s.beam.h;
    b.end_amplitude    = w_end_over_h * s.beam.h;
    return b;
  }

  void expect_all_converged(const Backbone &bb)
  {
    for (const auto &p : bb.points)
      EXPECT_LT(p.relative_residual, 1e-8) << "at amplitude " << p.amplitude;
  }

  // Exact Duffing frequency at turning-point amplitude A.
  double duffing_exact_frequency(const double omega_0, const double b, const double A)
  {
    const double pi = std::acos(-1.);
    const double s  = omega_0 * omega_0 + b * A * A;
    const double m  = b * A * A / (2. * s);
    return 0.5 * pi * std::sqrt(s) / std::comp_ellint_1(std::sqrt(m));
  }
} // namespace

TEST(SingleModeBackboneLaw, CoefficientOfTheIdealClampMuellerBeamIs0p5395)
{
  const RomSetup s(1);
  const double c = single_mode_backbone_coefficient(s.omega_1(), s.b_111(), s.output[0], s.beam.h);
  std::cout << "  c = " << c << " (doc/physics.md: 0.5395); (ω/ω₁)² at ŵ/h = 2.5: " << 1 + c * 6.25 << '\n';
  EXPECT_NEAR(c, 0.5395, 5e-4);
  // The seed's "doubles": sqrt(1 + 6.25 c) ≈ 2.09 at ŵ/h = 2.5 is about ω; doc/physics.md says ×2.09 on ω.
  EXPECT_NEAR(1 + c * 6.25, 4.37, 0.01);
}

TEST(SingleModeBackboneLaw, OneModeOneHarmonicBackboneIsSeedEq4)
{
  const RomSetup s(1);
  const double c = single_mode_backbone_coefficient(s.omega_1(), s.b_111(), s.output[0], s.beam.h);
  for (const auto method : {BackboneSettings::Method::arclength, BackboneSettings::Method::amplitude})
    {
      BackboneSettings settings = settings_for(s, 1, 4.);
      settings.method           = method;
      const Backbone bb         = compute_backbone(make_conservative_system(s.rom), settings);
      ASSERT_TRUE(bb.completed) << bb.message;
      EXPECT_GT(bb.points.size(), 10u);
      EXPECT_NEAR(bb.points.back().amplitude, 4e-3, 1e-15);
      expect_all_converged(bb);
      double worst = 0;
      for (const auto &p : bb.points)
        {
          const double q_hat = p.amplitude / s.output[0];
          worst = std::max(worst, relative_error(p.omega, single_mode_backbone_frequency(s.omega_1(), s.b_111(), q_hat)));
          const double r = p.amplitude / s.beam.h;
          worst = std::max(worst, relative_error(std::pow(p.omega / s.omega_1(), 2), 1 + c * r * r));
        }
      EXPECT_LT(worst, 1e-10);
    }
}

TEST(SingleModeBackboneLaw, TenHarmonicsGiveTheExactDuffingFrequency)
{
  const RomSetup s(1);
  const double w0 = s.omega_1(), b = s.b_111(), phi = s.output[0];
  // H = 10 is exact to the harmonic truncation: the Fourier coefficients of
  // the Duffing solution (a Jacobi cn) decay like q_nome^{h/2} with the nome
  // q_nome ≈ 0.04 at ŵ/h = 4, so the first neglected one (h = 11) is ~1e-8 of
  // q̂; at H = 16 the frequency is exact to round-off.
  for (const unsigned int H : {10u, 16u})
    for (const bool odd : {true, false})
      {
        BackboneSettings settings      = settings_for(s, H, 4.);
        settings.hb.odd_harmonics_only = odd;
        const Backbone bb              = compute_backbone(make_conservative_system(s.rom), settings);
        ASSERT_TRUE(bb.completed) << bb.message;
        expect_all_converged(bb);
        double worst = 0, worst_below_1 = 0;
        for (const auto &p : bb.points)
          {
            const double A = p.harmonics.sum(); // q(τ = 0), the turning point
            const double e = relative_error(p.omega, duffing_exact_frequency(w0, b, A));
            worst          = std::max(worst, e);
            if (p.amplitude <= s.beam.h)
              worst_below_1 = std::max(worst_below_1, e);
            EXPECT_NEAR(p.peak, std::abs(A * phi), 1e-12 * p.peak);
          }
        std::cout << "  H = " << H << (odd ? " (odd)" : " (all)") << ": worst |ω/ω_exact − 1| = " << worst
                  << " (ŵ/h ≤ 1: " << worst_below_1 << "), " << bb.points.size() << " points, "
                  << bb.n_newton_iterations << " Newton iterations, " << bb.seconds << " s\n";
        EXPECT_LT(worst, H == 10 ? 2e-7 : 1e-11) << "H = " << H << ", odd harmonics only: " << odd;
        EXPECT_LT(worst_below_1, H == 10 ? 1e-9 : 1e-13);
        if (H == 10 && odd)
          {
            const auto &p  = bb.points.back();
            const double q = p.amplitude / phi;
            std::cout << "  ŵ/h = 4: HB(H=10) ω/ω₁ = " << p.omega / w0
                      << ", Eq. 4: " << single_mode_backbone_frequency(w0, b, q) / w0 << " (+"
                      << 100 * (p.omega / single_mode_backbone_frequency(w0, b, q) - 1) << " %)\n";
          }
      }
}

TEST(SingleModeBackboneLaw, HigherHarmonicsRaiseTheBackboneByTheLindstedtCorrection)
{
  const RomSetup s(1);
  const double w0 = s.omega_1(), b = s.b_111(), phi = s.output[0];
  for (const double eps_a2 : {0.02, 0.05})
    {
      // First-harmonic amplitude with ε a₁² = eps_a2.
      const double q_hat = std::sqrt(eps_a2 * w0 * w0 / b);
      BackboneSettings settings = settings_for(s, 10, q_hat * phi / s.beam.h);
      settings.start_amplitude  = 0.01 * settings.end_amplitude;
      settings.hb.odd_harmonics_only = true;
      const Backbone bb = compute_backbone(make_conservative_system(s.rom), settings);
      ASSERT_TRUE(bb.completed) << bb.message;
      const double deviation = (bb.points.back().omega - single_mode_backbone_frequency(w0, b, q_hat)) / w0;
      const double lindstedt = 3. / 256. * eps_a2 * eps_a2;
      std::cout << "  ε a₁² = " << eps_a2 << ": (ω_HB − ω_Eq4)/ω₁ = " << deviation << ", Lindstedt 3/256 ε²a₁⁴ = "
                << lindstedt << '\n';
      EXPECT_GT(deviation, 0.);
      EXPECT_NEAR(deviation, lindstedt, 0.1 * lindstedt);
    }
}

TEST(MultiModeBackbone, HarmonicBalancePointIsAPeriodicOrbitOfTheRom)
{
  // At ŵ/h = 2 the backbone is near the 3:1 interaction with mode 3
  // (3ω ≈ ω₃), so the higher harmonics matter: the orbit closes to the
  // harmonic truncation error, which falls exponentially with H.
  const RomSetup s(3);
  const unsigned int N = 3;
  for (const unsigned int H : {10u, 24u})
    {
      const Backbone bb = compute_backbone(make_conservative_system(s.rom), settings_for(s, H, 2.));
      ASSERT_TRUE(bb.completed) << bb.message;
      expect_all_converged(bb);
      const auto &p = bb.points.back();
      const Eigen::Map<const Eigen::MatrixXd> Q(p.harmonics.data(), N, bb.harmonics.size());
      const Eigen::VectorXd q0 = Q.rowwise().sum(); // q(0); q̇(0) = 0 for a cosine series

      // RK4 over one period on x = (q, q̇); its own error is ~1e-13 here.
      const Eigen::ArrayXd w2 = s.modes.basis.omega.array().square();
      auto rhs                = [&](const Eigen::VectorXd &x) {
        Eigen::VectorXd dx(2 * N);
        dx.head(N) = x.tail(N);
        dx.tail(N) = -(w2 * x.head(N).array()).matrix() - s.rom.nonlinear_force(x.head(N));
        return dx;
      };
      const unsigned int n_steps = 20000;
      const double dt            = 2. * std::acos(-1.) / p.omega / n_steps;
      Eigen::VectorXd x          = Eigen::VectorXd::Zero(2 * N);
      x.head(N)                  = q0;
      for (unsigned int i = 0; i < n_steps; ++i)
        {
          const Eigen::VectorXd k1 = rhs(x), k2 = rhs(x + 0.5 * dt * k1), k3 = rhs(x + 0.5 * dt * k2),
                                k4 = rhs(x + dt * k3);
          x += dt / 6. * (k1 + 2. * k2 + 2. * k3 + k4);
        }
      const double error = (x.head(N) - q0).norm() / q0.norm();
      std::cout << "  ŵ/h = 2, N = 3, H = " << H << ": ω/ω₁ = " << p.omega / s.omega_1()
                << ", |q(T) − q(0)|/|q(0)| = " << error << ", q3/q1 = " << q0[2] / q0[0] << '\n';
      const double tolerance = H == 10 ? 1e-5 : 1e-10;
      EXPECT_LT(error, tolerance);
      EXPECT_LT(x.tail(N).norm() / p.omega / q0.norm(), 3 * tolerance);
      // The antisymmetric mode 2 is not excited by the symmetric backbone.
      EXPECT_LT(std::abs(q0[1]), 1e-12 * std::abs(q0[0]));
      // Mode 3 takes part.
      EXPECT_GT(std::abs(q0[2]), 1e-2 * std::abs(q0[0]));
    }
}

TEST(MultiModeBackbone, DenseMassAndStiffnessGiveTheSameBackbone)
{
  const RomSetup s(3);
  const unsigned int N = 3;
  // q = P x with a fixed, well-conditioned, non-orthogonal P.
  Eigen::MatrixXd P(3, 3);
  P << 1.0, 0.3, -0.2, 0.1, 0.8, 0.4, -0.3, 0.2, 1.1;
  P *= 2.5;
  ConservativeSystem dense;
  const Eigen::MatrixXd W2 = s.modes.basis.omega.array().square().matrix().asDiagonal();
  dense.mass               = P.transpose() * P;
  dense.stiffness          = P.transpose() * W2 * P;
  dense.force   = [&](const Eigen::VectorXd &x) -> Eigen::VectorXd { return P.transpose() * s.rom.nonlinear_force(P * x); };
  dense.tangent = [&](const Eigen::VectorXd &x) -> Eigen::MatrixXd {
    return P.transpose() * s.rom.nonlinear_tangent(P * x) * P;
  };
  // H = 1 up to ŵ/h = 4 and H = 3 below the 3:1 interaction with mode 3
  // (3ω = ω₃ near ŵ/h ≈ 2): no internal-resonance tongue on the way, so both
  // continuations follow the same smooth branch.
  for (const auto &[H, w_end] : {std::pair<unsigned int, double>{1, 4.}, {3, 1.}, {3, 1.5}})
    {
      BackboneSettings modal_settings = settings_for(s, H, w_end);
      BackboneSettings dense_settings = modal_settings;
      dense_settings.output           = P.transpose() * s.output;
      const Backbone bm               = compute_backbone(make_conservative_system(s.rom), modal_settings);
      const Backbone bd               = compute_backbone(dense, dense_settings);
      ASSERT_TRUE(bm.completed && bd.completed) << bm.message << " / " << bd.message;
      EXPECT_LT(relative_error(bd.points.back().omega, bm.points.back().omega), 1e-10);
      const Eigen::Map<const Eigen::MatrixXd> Xd(bd.points.back().harmonics.data(), N, bd.harmonics.size());
      const Eigen::Map<const Eigen::MatrixXd> Qm(bm.points.back().harmonics.data(), N, bm.harmonics.size());
      EXPECT_LT((P * Xd - Qm).norm() / Qm.norm(), 1e-8);
    }
}

TEST(MultiModeBackbone, SevenModesTenHarmonicsUpToFourThicknesses)
{
  // The seed's NMA setting (N = 7, H = 10); it reports a loop from modal
  // interaction near ŵ/h ≈ 4 (on its System 1). Report what the
  // continuation does here; every point it returns must be converged.
  const RomSetup s(7);
  for (const auto method : {BackboneSettings::Method::arclength, BackboneSettings::Method::amplitude})
    {
      BackboneSettings settings = settings_for(s, 10, 4.5);
      settings.method           = method;
      const Backbone bb         = compute_backbone(make_conservative_system(s.rom), settings);
      expect_all_converged(bb);
      double a_max = 0;
      for (const auto &p : bb.points)
        a_max = std::max(a_max, p.amplitude);
      const unsigned int n_turns = count_amplitude_folds(bb);
      std::cout << "  N = 7, H = 10, " << (method == BackboneSettings::Method::arclength ? "arclength" : "amplitude")
                << ": " << bb.points.size() << " points, max ŵ/h = " << a_max / s.beam.h
                << ", folds in amplitude: " << n_turns << ", " << bb.seconds << " s; " << bb.message << '\n';
      ASSERT_FALSE(bb.points.empty());
      EXPECT_FALSE(bb.message.empty());
      if (method == BackboneSettings::Method::arclength)
        {
          // Past the narrow 5:1 tongue near ŵ/h ≈ 0.64 (where the natural
          // continuation stops), then out along the 3:1 tongue with mode 3 at
          // ŵ/h ≈ 2.7 — where the seed sees Eq. 4 and the NMA part (≈ 2.6).
          EXPECT_GT(a_max / s.beam.h, 2.5);
          EXPECT_NE(bb.message.find("tongue"), std::string::npos) << bb.message;
          // The tongue is where the amplitude turns back: one fold, the one
          // the stop reports (the amplitude fell after its maximum).
          EXPECT_EQ(n_turns, 1u);
        }
      else
        {
          // Continuation in the amplitude can only go up: no fold, and it
          // stops at the first tongue (the 5:1 near ŵ/h ≈ 0.64).
          EXPECT_EQ(n_turns, 0u);
          EXPECT_NEAR(a_max / s.beam.h, 0.64, 0.03);
        }
    }
}

TEST(SingleModeBackboneLaw, SliderVersionEq5DividesByTheModalMassOfTheSlider)
{
  const RomSetup s(1);
  Eigen::VectorXd phi, dphi;
  s.modes.basis.evaluate(0.3 * s.beam.L, phi, dphi);
  const double m = 46.2e-3, J = 3.15e-6, q = 1e-3 / s.output[0];
  const double w  = single_mode_backbone_frequency(s.omega_1(), s.b_111(), q);
  const double ws = single_mode_backbone_frequency_with_slider(s.omega_1(), s.b_111(), q, m, J, phi[0], dphi[0]);
  EXPECT_NEAR(ws, w / std::sqrt(1 + m * phi[0] * phi[0] + J * dphi[0] * dphi[0]), 1e-12 * w);
  EXPECT_EQ(single_mode_backbone_frequency_with_slider(s.omega_1(), s.b_111(), q, 0, 0, phi[0], dphi[0]), w);
  EXPECT_THROW(single_mode_backbone_frequency_with_slider(s.omega_1(), s.b_111(), q, -1, 0, phi[0], dphi[0]),
               std::invalid_argument);
}

TEST(BackboneSettingsErrors, BadInputIsRejectedWithTheParameterName)
{
  const RomSetup s(2);
  BackboneSettings settings = settings_for(s, 3, 1.);
  settings.output           = Eigen::VectorXd::Ones(3);
  try
    {
      compute_backbone(make_conservative_system(s.rom), settings);
      FAIL() << "expected std::invalid_argument";
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("output"), std::string::npos) << e.what();
    }
  settings        = settings_for(s, 3, 1.);
  settings.mode   = 1; // antisymmetric mode 2: w(L/2) does not see it
  EXPECT_THROW(compute_backbone(make_conservative_system(s.rom), settings), std::invalid_argument);
}
