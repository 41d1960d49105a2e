// Pinned supports (Supports/Type = pinned: immovable hinges, w = u = 0, w'
// free) against exact answers:
//  - the linear frequencies of the hinged beam, ω_n = (nπ/L)² √(EI/ρA);
//  - the exact single-mode von Kármán backbone (Woinowsky-Krieger 1950).
//    With axial inertia neglected, w = a sin(πx/L) is an exact motion: the
//    membrane force EA a² π²/(4L²) is uniform, and the modal equation is
//    the Duffing oscillator q̈ + ω₀² (q + ε q³) = 0 with ε a² = (a/r)²/4,
//    r = h/√12. Its frequency is an elliptic integral; published ω/ω₀ at
//    a/r = 1 … 5: 1.089158, 1.317776, 1.625677, 1.976016, 2.350142, and
//    with first-order harmonic balance 1.089725 … 2.384848.
// The reduced model (analytic coefficients on the FE modes) must give these
// numbers with one mode and with three (the sine modes do not couple through
// the stretch, ∫φ₁'φ₃' = 0); the FE transient without axial inertia must
// give them in time; with axial inertia the FE differs by the part the
// hinged beam's axial modes add, bounded below.
#include "contact/beam_system.h"
#include "fem/fe_beam.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/fe_transient.h"
#include "scene/scene.h"
#include "reduced/rom_beam_system.h"

#include "tests/duffing_period.h"
#include "tests/free_step.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>

using namespace beamslider;

namespace
{
  const std::string scene_file = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

  Scene pinned_scene()
  {
    Scene s                   = read_scene(scene_file);
    s.supports.ideal_clamp    = false;
    s.supports.pinned_end     = {{true, true}};
    s.damping_ratio           = 0.;
    return s;
  }

  constexpr std::array<double, 5> exact_ratio{{1.089158, 1.317776, 1.625677, 1.976016, 2.350142}};
  // First-order harmonic balance, ω/ω₀ = √(1 + ¾ ε a²), published at a/r = 1 and 5.
  constexpr double first_order_hb_at_1 = 1.089725, first_order_hb_at_5 = 2.384848;

  using beamslider::testing::duffing_period;
  using beamslider::testing::free_step;

  // Mean period of w(x) from its zero crossings over `periods` periods of a
  // free vibration stepped by `step(t, q, u)`.
  template <class Step, class Deflection>
  double crossing_period(Step step, Deflection w_of, const unsigned int periods, const double t_max)
  {
    double t = 0, w_prev = w_of();
    std::vector<double> crossings;
    while (crossings.size() < 2 * periods + 1 && t < t_max)
      {
        const double dt = step(t);
        const double w  = w_of();
        if ((w_prev > 0) != (w > 0))
          crossings.push_back(t - dt * w / (w - w_prev));
        w_prev = w;
      }
    if (crossings.size() < 2 * periods + 1)
      return std::nan("");
    return (crossings.back() - crossings.front()) / periods;
  }
} // namespace

TEST(PinnedSupports, FrequenciesAreThoseOfTheHingedBeam)
{
  const Scene s = pinned_scene();
  const double L = s.beam.length, c = std::sqrt(s.beam.bending_stiffness() / s.beam.mass_per_length());
  // Hermite cubics: the frequencies converge at order 4 in the element size.
  const FEModes coarse = compute_bending_modes(FEBeam(s, 32), 4), fine = compute_bending_modes(FEBeam(s, 64), 4);
  for (unsigned int n = 1; n <= 4; ++n)
    {
      const double exact = std::pow(n * M_PI / L, 2) * c;
      const double e32 = coarse.omega[n - 1] / exact - 1, e64 = fine.omega[n - 1] / exact - 1;
      std::cout << "pinned beam, mode " << n << ": relative error " << e32 << " (32 el.), " << e64
                << " (64 el.), order " << std::log2(e32 / e64) << "\n";
      EXPECT_LT(std::abs(e32), 1e-4) << "mode " << n;
      EXPECT_NEAR(std::log2(e32 / e64), 4., 0.2) << "mode " << n;
    }
  // The immovable hinges: the membrane is the bare beam, k_ax = EA/L.
  EXPECT_DOUBLE_EQ(s.supports.membrane_stiffness(s.beam), s.beam.axial_stiffness() / L);
}

TEST(PinnedSupports, ClampedPinnedFrequenciesSolveTanEqualsTanh)
{
  // Clamped at x = 0, hinged at x = L: tan βL = tanh βL, roots by bisection
  // on ((n + ¼)π ± 0.2); the FE converges to them at order 4.
  Scene s                 = pinned_scene();
  s.supports.ideal_clamp  = true;
  s.supports.pinned_end   = {{false, true}};
  const double L = s.beam.length, c = std::sqrt(s.beam.bending_stiffness() / s.beam.mass_per_length());
  const FEModes coarse = compute_bending_modes(FEBeam(s, 32), 3), fine = compute_bending_modes(FEBeam(s, 64), 3);
  for (unsigned int n = 1; n <= 3; ++n)
    {
      auto g   = [](const double b) { return std::sin(b) * std::cosh(b) - std::cos(b) * std::sinh(b); };
      double a = (n + 0.25) * M_PI - 0.2, b = (n + 0.25) * M_PI + 0.2;
      ASSERT_LT(g(a) * g(b), 0.);
      for (int it = 0; it < 200; ++it)
        {
          const double m = 0.5 * (a + b);
          (g(a) * g(m) <= 0 ? b : a) = m;
        }
      const double exact = std::pow(0.5 * (a + b) / L, 2) * c;
      const double e32 = coarse.omega[n - 1] / exact - 1, e64 = fine.omega[n - 1] / exact - 1;
      EXPECT_LT(std::abs(e32), 1e-4) << "mode " << n;
      EXPECT_NEAR(std::log2(e32 / e64), 4., 0.2) << "mode " << n;
    }
}

TEST(PinnedSupports, ReducedModelBackboneIsTheExactSingleModeOne)
{
  const Scene s = pinned_scene();
  const FEBeam beam(s);
  const unsigned int N = 3;
  const FEModes modes  = compute_bending_modes(beam, N);
  const ModalBasis basis = make_modal_basis(beam, modes, N);
  const double L = s.beam.length, h = s.beam.thickness, r = h / std::sqrt(12.);
  const double omega0 = basis.omega[0];
  const double b111   = 0.5 * basis.membrane_stiffness * std::pow(basis.stretch(0, 0), 2);
  Eigen::VectorXd phi, dphi;
  basis.evaluate(0.5 * L, phi, dphi);

  // The sine modes do not couple through the stretch: mode 1 alone is exact.
  EXPECT_LT(std::abs(basis.stretch(0, 1)), 1e-8 * basis.stretch(0, 0));
  EXPECT_LT(std::abs(basis.stretch(0, 2)), 1e-8 * basis.stretch(0, 0));

  for (unsigned int k = 0; k < 5; ++k)
    {
      const double a_over_r = k + 1., q0 = a_over_r * r / phi[0];
      const double ratio    = 2 * M_PI / duffing_period(omega0, b111, q0) / omega0;
      const double hb1      = std::sqrt(1. + 0.75 * b111 * q0 * q0 / (omega0 * omega0));
      // Published to 6 decimals; the FE modes add < 1e-9.
      EXPECT_NEAR(ratio, exact_ratio[k], 1e-6) << "a/r = " << a_over_r;
      if (k == 0)
        {
          EXPECT_NEAR(hb1, first_order_hb_at_1, 1e-6);
        }
      if (k == 4)
        {
          EXPECT_NEAR(hb1, first_order_hb_at_5, 1e-6);
        }
    }

  // The three-mode ROM in time (explicit midpoint, Δt far below 2/ω_3) from
  // rest at a/r = 2: the period of mode 1 alone, the others stay at rest.
  RomBeamSystem rom(ReducedOrderModel(basis, 0., true), h, BaseExcitation{0., 0.});
  const double q0 = 2. * r / phi[0], dt = 2e-6;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(N), u = Eigen::VectorXd::Zero(N);
  q[0]              = q0;
  BeamPointKinematics p;
  const double T_exact = duffing_period(omega0, b111, q0);
  const double T       = crossing_period(
    [&](double &t) {
      free_step(rom, t, dt, q, u);
      t += dt;
      return dt;
    },
    [&] {
      rom.evaluate(0.5 * L, q, p);
      return p.w;
    },
    10, 20 * T_exact);
  std::cout << "pinned beam, ROM N = 3 at a/r = 2: omega/omega0 = " << 2 * M_PI / T / omega0 << " (exact "
            << exact_ratio[1] << "), |q_2|+|q_3| = " << std::abs(q[1]) + std::abs(q[2]) << " (q_1 " << q0 << ")\n";
  // The midpoint rule lengthens the period by (ωΔt)²/24; the crossings'
  // linear interpolation adds far less.
  EXPECT_NEAR(T / T_exact, 1., 1e-6);
  EXPECT_LT(std::abs(q[1]) + std::abs(q[2]), 1e-8 * q0);
}

TEST(PinnedSupports, FEBackboneWithAndWithoutAxialInertia)
{
  // Free vibration of the FE beam from rest in the mode-1 shape at a/r = 2
  // (axial displacement zero at the start), without and with axial inertia.
  const Scene s = pinned_scene();
  const double L = s.beam.length, h = s.beam.thickness, r = h / std::sqrt(12.), dt = 5e-6;
  double period_ratio[2] = {0., 0.};
  double omega0 = 0;
  for (const bool inertia : {false, true})
    {
      FETransientSettings settings;
      settings.axial_inertia = inertia;
      FETransientBeam sys(s, BaseExcitation{0., 0.}, 0, settings);
      omega0 = sys.modes().omega[0];
      Eigen::VectorXd phi;
      FETransientBeam::to_eigen(sys.modes().shapes[0], phi);
      Eigen::VectorXd q = 2. * r / sys.beam().deflection(sys.modes().shapes[0], 0.5 * L) * phi;
      Eigen::VectorXd u = Eigen::VectorXd::Zero(sys.n_dofs());
      BeamPointKinematics p;
      sys.evaluate(0.5 * L, q, p);
      const double T_guess = 2 * M_PI / (exact_ratio[1] * omega0);
      const double T = crossing_period(
        [&](double &t) {
          free_step(sys, t, dt, q, u);
          t += dt;
          return dt;
        },
        [&] { return p.grad_w.dot(q); }, 10, 20 * T_guess);
      period_ratio[inertia] = 2 * M_PI / T / omega0;
    }
  // The hinged beam's first axial mode, ω_ax = (π/L) √(E/ρ): the scale of
  // what axial inertia changes, (ω/ω_ax)² relative.
  const double omega_axial = M_PI / L * std::sqrt(s.beam.youngs_modulus / s.beam.density);
  const double axial_scale = std::pow(exact_ratio[1] * omega0 / omega_axial, 2);
  const double scheme      = std::pow(exact_ratio[1] * omega0 * dt, 2) / 12; // trapezoidal period error
  std::cout << std::setprecision(8) << "pinned beam, FE at a/r = 2: omega/omega0 = " << period_ratio[0] << " without axial inertia, "
            << period_ratio[1] << " with (exact single mode " << exact_ratio[1] << "); (omega/omega_ax)^2 = "
            << axial_scale << ", scheme " << scheme << "\n";
  // Without axial inertia the FE is the exact single-mode motion up to the
  // time discretisation, the mesh (6e-8 on mode 1) and the published
  // rounding (4e-7). The time discretisation: the trapezoidal rule's period
  // error (ωΔt)²/12 on the bending, plus the membrane force at the midpoint
  // taken from the mean of the end equilibria, off by (2ωΔt)²/8 of the
  // axial part (at most 6 × scheme); measured 2.6 × scheme. With axial
  // inertia the axial modes add a part below (ω/ω_ax)² (measured 4 % of it).
  EXPECT_NEAR(period_ratio[0] / exact_ratio[1], 1., 7 * scheme + 1e-6);
  EXPECT_NEAR(period_ratio[1] / exact_ratio[1], 1., axial_scale + 2 * scheme + 1e-6);
}
