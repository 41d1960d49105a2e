// Tests of the reduced model as a BeamSystem (reduced/rom_beam_system) with
// the shared contact code: the stability limit 2/ω_max, free vibration
// against the modal solution, force directions against finite differences of
// the gaps, the energy balance without friction and damping, and the end stop
// at a support; the implicit variant and the BeamStep protocol. Speed is
// measured by the RomContact benchmark, not here.
//
// The modal basis is built here from the analytic clamped–clamped modes
// (β_n L roots of cos βL cosh βL = 1, mass-normalised, K'_jk and γ_n by
// Gauss quadrature), independent of the FE code.
#include "runs/adaptation_run.h"
#include "contact/moreau_stepper.h"
#include "reduced/rom_beam_system.h"
#include "reduced/rom_implicit_beam_system.h"
#include "tests/free_step.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>

using namespace beamslider;

namespace
{
  // Clamped–clamped mode n (0-based) of a beam of length L: the shape
  // ψ = cosh βx − cos βx − σ (sinh βx − sin βx), written with exponentials so
  // that high modes do not cancel catastrophically.
  struct ClampedMode
  {
    double beta, one_minus_sigma, sigma, scale;
    void eval(const double x, double &phi, double &dphi) const
    {
      const double bx = beta * x;
      const double ep = std::exp(bx - beta * 0.); // e^{βx}
      const double em = std::exp(-bx);
      phi  = scale * (0.5 * (one_minus_sigma * ep + (1. + sigma) * em) - std::cos(bx) + sigma * std::sin(bx));
      dphi = scale * beta * (0.5 * (one_minus_sigma * ep - (1. + sigma) * em) + std::sin(bx) + sigma * std::cos(bx));
    }
  };

  ModalBasis clamped_clamped_basis(const BeamData &beam, const unsigned int N)
  {
    const double L = beam.length, rhoA = beam.mass_per_length();
    std::vector<ClampedMode> modes(N);
    ModalBasis basis;
    basis.length = L;
    basis.omega.resize(N);
    for (unsigned int n = 0; n < N; ++n)
      {
        // Newton on cos(z) cosh(z) − 1 = 0 from z ≈ (n + 3/2) π.
        double z = (n + 1.5) * M_PI;
        for (int it = 0; it < 50; ++it)
          z -= (std::cos(z) * std::cosh(z) - 1.) / (-std::sin(z) * std::cosh(z) + std::cos(z) * std::sinh(z));
        ClampedMode &m     = modes[n];
        m.beta             = z / L;
        const double denom = std::sinh(z) - std::sin(z);
        m.sigma            = (std::cosh(z) - std::cos(z)) / denom;
        m.one_minus_sigma  = (-std::exp(-z) - std::sin(z) + std::cos(z)) / denom;
        m.scale            = 1.;
        basis.omega[n]     = m.beta * m.beta * std::sqrt(beam.bending_stiffness() / rhoA);
      }
    // Gauss–Legendre (3 points) on 600 cells: mass normalisation, γ, K'.
    const double gp[3] = {-std::sqrt(0.6), 0., std::sqrt(0.6)}, gw[3] = {5. / 9., 8. / 9., 5. / 9.};
    const unsigned int cells = 600;
    Eigen::VectorXd mass = Eigen::VectorXd::Zero(N), integral = Eigen::VectorXd::Zero(N);
    Eigen::MatrixXd stretch = Eigen::MatrixXd::Zero(N, N);
    Eigen::VectorXd phi(N), dphi(N);
    for (int pass = 0; pass < 2; ++pass)
      {
        mass.setZero();
        integral.setZero();
        stretch.setZero();
        for (unsigned int c = 0; c < cells; ++c)
          for (int q = 0; q < 3; ++q)
            {
              const double x = (c + 0.5 + 0.5 * gp[q]) * L / cells, w = 0.5 * gw[q] * L / cells;
              for (unsigned int n = 0; n < N; ++n)
                modes[n].eval(x, phi[n], dphi[n]);
              mass += w * rhoA * phi.cwiseAbs2();
              integral += w * phi;
              stretch += w * dphi * dphi.transpose();
            }
        if (pass == 0)
          for (unsigned int n = 0; n < N; ++n)
            modes[n].scale = 1. / std::sqrt(mass[n]);
      }
    basis.gamma              = -rhoA * integral;
    basis.stretch            = stretch;
    basis.membrane_stiffness = beam.axial_stiffness() / L; // ideal clamp
    basis.evaluate           = [modes](const double x, Eigen::VectorXd &p, Eigen::VectorXd &dp) {
      p.resize(modes.size());
      dp.resize(modes.size());
      for (std::size_t n = 0; n < modes.size(); ++n)
        modes[n].eval(x, p[n], dp[n]);
    };
    return basis;
  }

  Scene mueller_scene()
  {
    Scene scene; // scene.h defaults are the mueller2023 numbers
    scene.name                = "mueller2023-analytic-clamp";
    scene.supports.ideal_clamp = true;
    return scene;
  }

  // The mueller2023 beam left to itself: no damping (D given), no base
  // motion, no geometric nonlinearity — a linear free vibration.
  Scene linear_free_scene(const double damping_ratio = 0.)
  {
    Scene scene                                 = mueller_scene();
    scene.damping_ratio                         = damping_ratio;
    scene.excitation.acceleration_amplitude     = 0.;
    scene.discretisation.geometric_nonlinearity = false;
    return scene;
  }


  using beamslider::testing::free_step;
} // namespace

TEST(AnalyticClampedBasis, IsMassNormalisedWithKnownFrequencies)
{
  const Scene scene = mueller_scene();
  const ModalBasis basis = clamped_clamped_basis(scene.beam, 5);
  const double beta_L[5] = {4.730041, 7.853205, 10.995608, 14.137165, 17.278760};
  const double c = std::sqrt(scene.beam.bending_stiffness() / scene.beam.mass_per_length());
  for (int n = 0; n < 5; ++n)
    EXPECT_NEAR(basis.omega[n], std::pow(beta_L[n] / scene.beam.length, 2) * c, 1e-6 * basis.omega[n]);
  // Symmetric modes have γ ≠ 0, antisymmetric ones γ = 0; φ(0) = φ'(0) = 0.
  EXPECT_LT(std::abs(basis.gamma[1]), 1e-10 * std::abs(basis.gamma[0]));
  Eigen::VectorXd phi, dphi;
  basis.evaluate(0., phi, dphi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-9);
  basis.evaluate(scene.beam.length, phi, dphi);
  EXPECT_LT(phi.cwiseAbs().maxCoeff(), 1e-6 * std::sqrt(1. / (scene.beam.mass_per_length() * scene.beam.length)));
}

TEST(RomBeamSystem, RefusesTimeStepAboveTwoOverOmegaMax)
{
  const Scene scene = mueller_scene();
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
  const double limit = 2. / rom.model().basis().omega[4];
  EXPECT_DOUBLE_EQ(rom.max_stable_time_step(), limit);

  Eigen::VectorXd q = Eigen::VectorXd::Zero(5), u_free;
  EXPECT_NO_THROW(rom.free_velocity(0., q, q, 0.99 * limit, u_free));
  try
    {
      rom.free_velocity(0., q, q, 1.01 * limit, u_free);
      FAIL() << "a time step above 2/omega_max was accepted";
    }
  catch (const std::invalid_argument &e)
    {
      const std::string what = e.what();
      EXPECT_NE(what.find("time step Delta t"), std::string::npos) << what;
      EXPECT_NE(what.find("2/omega_max"), std::string::npos) << what;
    }
  // The whole run refuses it too, before the first step.
  Scene bad                    = scene;
  bad.time_stepping.time_step = 1.01 * limit;
  EXPECT_THROW(AdaptationRun(bad, rom, RunOptions::from_scene(bad)), std::invalid_argument);
}

TEST(RomBeamSystem, FreeVibrationOfOneModeMatchesCosine)
{
  // Linear (no cubic term), undamped, unforced: q_1(t) = q0 cos ω_1 t. The
  // explicit midpoint (leapfrog) step has a phase error (ωΔt)²/24 per radian.
  const Scene scene = linear_free_scene();
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 3));
  const double w1 = rom.model().basis().omega[0], dt = 1e-6;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3), u = Eigen::VectorXd::Zero(3);
  q[0]               = 1e-4;
  const unsigned int n = std::lround(2 * M_PI / w1 / dt); // one period
  for (unsigned int k = 0; k < n; ++k)
    free_step(rom, k * dt, dt, q, u);
  const double t = n * dt;
  EXPECT_NEAR(q[0], 1e-4 * std::cos(w1 * t), 1e-4 * 1e-4);
  EXPECT_NEAR(u[0], -1e-4 * w1 * std::sin(w1 * t), 1e-4 * w1 * 1e-4);
  EXPECT_EQ(q[1], 0.);
}

// The implicit ROM (reduced/rom_implicit_beam_system.h) on a linear,
// undamped, unforced mode is the trapezoidal rule, whose discrete solution is
// known exactly: q_k = q0 cos(k θ) with tan(θ/2) = ωΔt/2 (no amplitude error,
// period elongation only). Checked at ωΔt = 3, beyond the explicit step's
// limit of 2, where the explicit ROM refuses the step.
TEST(RomImplicitBeamSystem, LinearModeFollowsTheTrapezoidalRuleExactlyBeyondTheExplicitLimit)
{
  const Scene scene = linear_free_scene();
  RomImplicitBeamSystem rom = RomImplicitBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 1));
  const double w1 = rom.model().basis().omega[0], dt = 3. / w1;
  EXPECT_GT(dt, RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 1)).max_stable_time_step());
  const double theta = 2. * std::atan(0.5 * w1 * dt);
  Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 1e-4), u = Eigen::VectorXd::Zero(1), u_E;
  for (unsigned int k = 1; k <= 199; ++k)
    {
      free_step(rom, (k - 1) * dt, dt, q, u);
      ASSERT_NEAR(q[0], 1e-4 * std::cos(k * theta), 1e-4 * 1e-10) << "step " << k;
    }
  // Impulses go through the same iteration matrix: S = 1 + Δt²/4 ω².
  const Eigen::VectorXd q_M = q + 0.5 * dt * u;
  const BeamStep last       = rom.free_velocity(199.5 * dt, q_M, u, dt, u_E);
  q                         = q_M + 0.5 * dt * u_E;
  EXPECT_NEAR(q[0], 1e-4 * std::cos(200 * theta), 1e-4 * 1e-10) << "step 200";
  Eigen::MatrixXd B = Eigen::MatrixXd::Ones(1, 2), X(1, 2);
  last.solve_iteration_matrix(B, X);
  EXPECT_NEAR(X(0, 0), 1. / (1. + 0.25 * dt * dt * w1 * w1), 1e-15);
}

namespace
{
  // A state of a few thicknesses of amplitude, where the membrane tangent
  // couples the modes: mode n at 3h/(n+1) (alternating sign, h of mode 1 at
  // L/2), velocities a tenth of ω_n times that.
  void large_state(const RomBeamSystem &rom, const Scene &scene, Eigen::VectorXd &q_M, Eigen::VectorXd &u_B)
  {
    const Eigen::Index N     = rom.n_dofs();
    const Eigen::VectorXd &w = rom.model().basis().omega;
    BeamPointKinematics centre;
    rom.evaluate(0.5 * scene.beam.length, Eigen::VectorXd::Unit(N, 0), centre);
    const double q_h = scene.beam.thickness / centre.w; // mode 1's q for w(L/2) = h
    q_M.resize(N);
    u_B.resize(N);
    for (Eigen::Index n = 0; n < N; ++n)
      {
        q_M[n] = 3. * q_h / (n + 1) * (n % 2 ? -1. : 1.);
        u_B[n] = 0.1 * q_M[n] * w[n] * (n % 3 ? 1. : -0.5);
      }
  }
} // namespace

// The implicit step's iteration matrix S = I + Δt/2 C + Δt²/4 (Ω² + ∂f/∂q)
// is solved through its structure (an eigenbasis and a rank-one update, see
// rom_implicit_beam_system.h). Checked against S built here from the
// model's own tangent, on 8 modes at several thicknesses of amplitude and a
// time step far beyond the explicit limit: Newton's u_free makes the
// residual vanish, and S X = B for the impulse solve.
TEST(RomImplicitBeamSystem, StructuredSolveInvertsTheIterationMatrix)
{
  const Scene scene = mueller_scene();
  const unsigned int N = 8;
  RomImplicitBeamSystem rom = RomImplicitBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, N));
  const ReducedOrderModel &model = rom.model();
  const Eigen::ArrayXd w         = model.basis().omega.array();
  const double dt                = 0.5 / w[0]; // ω_8 Δt ≈ 16: far beyond the explicit limit 2
  Eigen::VectorXd q_M, u_B, u_E;
  large_state(rom, scene, q_M, u_B);
  const double t_M = 0.3e-3;
  const BeamStep step = rom.free_velocity(t_M, q_M, u_B, dt, u_E);

  const double a          = rom.excitation().acceleration(t_M);
  const Eigen::VectorXd q = q_M + 0.25 * dt * (u_E - u_B);
  const Eigen::VectorXd c = (2. * scene.damping_ratio * w).matrix();
  const Eigen::VectorXd R = (u_E - u_B) + dt * (0.5 * c.cwiseProduct(u_B + u_E) + (w * w).matrix().cwiseProduct(q) +
                                                model.nonlinear_force(q) - a * model.basis().gamma);
  EXPECT_LT(R.norm(), 1e-9 * (u_E.norm() + q.norm() / dt)) << "Newton's u_free does not solve the step";

  Eigen::MatrixXd S = (0.25 * dt * dt) * model.nonlinear_tangent(q);
  S.diagonal() += (1. + 0.5 * dt * c.array() + 0.25 * dt * dt * w * w).matrix();
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(N, 3), X(N, 3);
  for (unsigned int n = 0; n < N; ++n)
    {
      B(n, 0) = 1.;
      B(n, 1) = std::cos(0.7 * n);
      B(n, 2) = n == 3 ? 1. : 0.;
    }
  step.solve_iteration_matrix(B, X);
  // S above is at the converged q̄, the solve at the last iterate's: the
  // two differ by Newton's last correction (≤ 1e-10 relative).
  EXPECT_LT((S * X - B).norm(), 1e-8 * B.norm());
  EXPECT_GT((S.diagonal().asDiagonal().inverse() * B - X).norm(), 1e-3 * X.norm())
    << "the membrane tangent should couple the modes at this amplitude";
}

// The step order is carried by the BeamStep that free_velocity returns: a
// step object kept past the next free_velocity is refused (its iteration
// matrix may no longer be the one factorised), the current one works.
TEST(BeamStep, AStepObjectOfAnEarlierStepIsRefused)
{
  const Scene scene = mueller_scene();
  RomImplicitBeamSystem rom = RomImplicitBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 2));
  const double dt           = 1e-4;
  Eigen::VectorXd q = Eigen::VectorXd::Constant(2, 1e-9), u = Eigen::VectorXd::Zero(2), u_E; // nearly linear
  const BeamStep first  = rom.free_velocity(0.5 * dt, q, u, dt, u_E);
  const BeamStep second = rom.free_velocity(1.5 * dt, q, u_E, dt, u);
  Eigen::MatrixXd B = Eigen::MatrixXd::Identity(2, 2), X(2, 2);
  double damping = 0, excitation = 0;
  EXPECT_THROW(first.solve_iteration_matrix(B, X), std::logic_error);
  EXPECT_THROW(first.work(u, damping, excitation), std::logic_error);
  EXPECT_THROW(first.finish(q, q, u), std::logic_error);
  EXPECT_THROW(first.iteration_matrix_is_identity(), std::logic_error);
  EXPECT_FALSE(second.iteration_matrix_is_identity()) << "the implicit ROM's S holds damping and stiffness";
  EXPECT_NO_THROW(second.solve_iteration_matrix(B, X));
  EXPECT_NEAR(X(0, 0), 1. / (1. + 0.5 * dt * 2 * scene.damping_ratio * rom.model().basis().omega[0] +
                              0.25 * dt * dt * std::pow(rom.model().basis().omega[0], 2)),
              1e-6)
    << "S⁻¹ of the second step (the membrane tangent is negligible at this amplitude)";
  EXPECT_DOUBLE_EQ(second.time_step(), dt);
}

namespace
{
  // The explicit ROM, but declaring a general iteration matrix: the stepper
  // then solves S X = W_b (for S = I, a copy) and forms G with Eigen's
  // product, the path an FE beam takes.
  class RomThroughTheGeneralPath : public RomBeamSystem
  {
  public:
    using RomBeamSystem::RomBeamSystem;
    bool iteration_matrix_is_identity() const override { return false; }
  };
} // namespace

// The explicit ROM's S = I lets the Moreau step use W_b for S⁻¹W_b and form
// G's beam part from half its dot products (moreau_stepper.cc). That must
// not change a result in any bit: over 0.3 s of the signature move, the
// slider rattling on the beam, the shortcut and the general path give the
// same state after every step. N = 5 keeps G below Eigen's threshold for its
// blocked product; N = 12 crosses it when two corners touch.
TEST(MoreauStep, TheUnitIterationMatrixShortcutKeepsTheGeneralPathsBits)
{
  const Scene scene = mueller_scene();
  for (const unsigned int N : {5u, 12u})
    {
      const ModalBasis basis = clamped_clamped_basis(scene.beam, N);
      const ReducedOrderModel model(basis, scene.damping_ratio, scene.discretisation.geometric_nonlinearity);
      const BaseExcitation base = BaseExcitation::from_scene(scene.excitation);
      RomBeamSystem shortcut(model, scene.beam.thickness_profile(), base);
      RomThroughTheGeneralPath general(model, scene.beam.thickness_profile(), base);
      double dt = scene.time_stepping.time_step;
      while (dt > shortcut.max_stable_time_step())
        dt /= 2;
      const SliderParameters slider = SliderParameters::from_scene(scene);
      const ContactLaw law          = ContactLaw::from_scene(scene);
      MoreauStepper fast(shortcut, slider, law, base, dt), slow(general, slider, law, base, dt);
      const double x_C = scene.initial.slider_position_over_L * scene.beam.length;
      fast.set_state(fast.resting_state(x_C));
      slow.set_state(slow.resting_state(x_C));

      const unsigned long n_steps = std::lround(0.3 / dt);
      unsigned long contact_steps = 0, two_corner_steps = 0;
      for (unsigned long k = 0; k < n_steps; ++k)
        {
          const StepReport &r = fast.step();
          slow.step();
          contact_steps += r.n_active > 0;
          two_corner_steps += r.n_active > 1;
          const SystemState &a = fast.state(), &b = slow.state();
          ASSERT_TRUE(a.q == b.q && a.u == b.u && a.s == b.s && a.v == b.v)
            << "N = " << N << ": the paths differ after step " << k << " (t = " << a.t << " s)";
        }
      EXPECT_GT(contact_steps, n_steps / 2) << "N = " << N << ": the slider must rattle for the check to mean anything";
      EXPECT_GT(two_corner_steps, 0u) << "N = " << N;
    }
}

// The damped set: a ROM damping only its first mode (as the FE damps only
// the scene's N modes of its mesh) lets mode 1 decay as e^{−Dω₁t} while
// modes 2 and 3 ring at constant amplitude (linear, undriven, implicit
// step: no numerical damping).
TEST(RomImplicitBeamSystem, OnlyTheDampedSetDecays)
{
  const Scene scene = linear_free_scene(0.02);
  ReducedOrderModel model(clamped_clamped_basis(scene.beam, 3), scene.damping_ratio, false);
  model.set_damped_modes(1);
  EXPECT_EQ(model.n_damped_modes(), 1u);
  RomImplicitBeamSystem rom(std::move(model), scene.beam.thickness, BaseExcitation::from_scene(scene.excitation));
  const Eigen::VectorXd w = rom.model().basis().omega;
  const double dt         = 0.01 / w[2];
  Eigen::VectorXd q = Eigen::VectorXd::Constant(3, 1e-4), u = Eigen::VectorXd::Zero(3);
  auto energy       = [&](const unsigned int n) { return 0.5 * (u[n] * u[n] + w[n] * w[n] * q[n] * q[n]); };
  const double E0[3] = {energy(0), energy(1), energy(2)};
  const long steps   = std::lround(20. * 2. * M_PI / w[0] / dt); // 20 periods of mode 1
  for (long k = 0; k < steps; ++k)
    free_step(rom, k * dt, dt, q, u);
  const double t = steps * dt;
  // Energy decays as e^{−2Dωt} up to the oscillating part of O(D).
  EXPECT_NEAR(std::log(energy(0) / E0[0]) / (-2. * scene.damping_ratio * w[0] * t), 1., 0.05);
  EXPECT_NEAR(energy(1) / E0[1], 1., 1e-9);
  EXPECT_NEAR(energy(2) / E0[2], 1., 1e-9);
}

// One rung of the error ladder against its neighbour where they must agree:
// the implicit and the explicit ROM (the same reduction, two second-order
// integrators) on the beam alone — von Kármán stiffening at about one
// thickness of amplitude, driven at 124 Hz — over 12 excitation
// periods. With the slider they cannot be compared step by step: its
// rattling parts any two integrations within two periods (measured: 3e-6 L
// after the second period at Δt = 1e-6 s, not shrinking with Δt), which is
// why adaptation runs are compared as ensembles. Without it the two must
// agree, and their difference must be a discretisation difference: about
// four times smaller at half the step. Undamped: the explicit step takes the
// damping force at u_B, which is first order in Δt (with D = 0.1 % the ratio
// measured 3.2 instead of 4).
TEST(RomImplicitBeamSystem, AgreesWithTheExplicitRomOnTheBeamAloneToSecondOrder)
{
  Scene scene         = mueller_scene();
  scene.damping_ratio = 0.;
  const double t_end = 12. / scene.excitation.frequency_hz;
  auto run = [&](BeamSystem &beam, const double dt) {
    const unsigned int n = beam.n_dofs();
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n), u = Eigen::VectorXd::Zero(n);
    BeamPointKinematics centre;
    beam.evaluate(0.5 * scene.beam.length, Eigen::VectorXd::Unit(n, 0), centre);
    q[0] = scene.beam.thickness / centre.w; // w(L/2) = h at the start
    std::vector<double> w;
    const long steps = std::lround(t_end / dt);
    for (long k = 0; k < steps; ++k)
      {
        free_step(beam, k * dt, dt, q, u);
        if ((k + 1) % std::lround(1e-4 / dt) == 0) // every 0.1 ms
          {
            beam.evaluate(0.5 * scene.beam.length, q, centre);
            w.push_back(centre.w / scene.beam.thickness);
          }
      }
    return w;
  };
  double difference[2] = {0, 0};
  const double steps[2] = {2e-6, 1e-6};
  for (int k = 0; k < 2; ++k)
    {
      RomBeamSystem explicit_rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
      RomImplicitBeamSystem implicit_rom =
        RomImplicitBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
      const std::vector<double> a = run(explicit_rom, steps[k]), b = run(implicit_rom, steps[k]);
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < a.size(); ++i)
        difference[k] = std::max(difference[k], std::abs(a[i] - b[i]));
      std::cout << "dt = " << steps[k] << " s: largest difference in w(L/2) " << difference[k] << " h\n";
    }
  EXPECT_LT(difference[1], 1e-3);
  EXPECT_NEAR(difference[0] / difference[1], 4., 0.4); // second order
}

TEST(ContactGeometry, NormalForceDirectionsAreGapGradients)
{
  // W_N = ∂g_N/∂(q, s) and ∂g_N/∂t = imposed velocity, by central differences
  // on a deformed ROM beam with base motion. The slider part neglects the
  // beam curvature term w''·∂g/∂w' (slider_contact.h): it must agree up to
  // that term, computed here from a finite-difference w''.
  const Scene scene = mueller_scene();
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
  const SliderGeometry geometry(SliderParameters::from_scene(scene), scene.beam.thickness);
  const BaseExcitation base = BaseExcitation::from_scene(scene.excitation);
  Eigen::VectorXd q(5);
  q << 3e-4, -1e-4, 5e-5, 2e-5, -1e-5; // w ~ 0.1 mm, slopes ~ 1e-2
  const Eigen::Vector3d s(0.06, -4e-3, 0.01);
  const double t = 1.3e-3;
  CornerKinematics k0, kp, km;
  // Central difference of a corner's gap in entry j of x (the beam's q or the
  // slider's s), the corner evaluated by `at`.
  auto gap_slope = [&](auto x, const int j, const double e, const auto &at) {
    auto xp = x, xm = x;
    xp[j] += e;
    xm[j] -= e;
    at(xp, kp);
    at(xm, km);
    return (kp.gap - km.gap) / (2 * e);
  };
  for (unsigned int corner = 0; corner < n_slider_corners; ++corner)
    {
      geometry.evaluate(corner, t, rom, base, q, s, k0);
      auto at_q = [&](const Eigen::VectorXd &x, CornerKinematics &k) { geometry.evaluate(corner, t, rom, base, x, s, k); };
      auto at_s = [&](const Eigen::Vector3d &x, CornerKinematics &k) { geometry.evaluate(corner, t, rom, base, q, x, k); };
      for (int j = 0; j < 5; ++j)
        EXPECT_NEAR(gap_slope(q, j, 1e-7, at_q), k0.beam_normal[j], 1e-6 * k0.beam_normal.norm())
          << "corner " << corner << " mode " << j;
      // Bound of the neglected term ∂g/∂w' · w'' ∂x_P/∂s_j with
      // |∂g/∂w'| ≤ |w'| (|Δz| + h/2) and |∂x_P/∂s| ≤ 1 + |r_z|.
      BeamPointKinematics bp, bm, b0;
      rom.evaluate(k0.x + 1e-6, q, bp);
      rom.evaluate(k0.x - 1e-6, q, bm);
      rom.evaluate(k0.x, q, b0);
      const Eigen::Vector2d r = geometry.corner_offset(corner, s[2]);
      const double curvature  = (bp.dw - bm.dw) / 2e-6;
      const double dz         = s[1] + r[1] - base.displacement(t) - b0.w;
      const double neglected =
        std::abs(b0.dw * curvature) * (std::abs(dz) + 0.5 * scene.beam.thickness) * (1. + std::abs(r[1]));
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(gap_slope(s, j, 1e-8, at_s), k0.slider_normal[j], neglected + 1e-7 * k0.slider_normal.norm())
          << "corner " << corner << " slider coordinate " << j;
      const double e = 1e-8;
      geometry.evaluate(corner, t + e, rom, base, q, s, kp);
      geometry.evaluate(corner, t - e, rom, base, q, s, km);
      EXPECT_NEAR((kp.gap - km.gap) / (2 * e), k0.imposed_normal, 1e-6 * std::abs(k0.imposed_normal) + 1e-12);
    }
}

TEST(ContactGeometry, MovingTheSliderCarriesItsWindowAlongTheVibratingBeam)
{
  // A prescribed-position sweep moves the slider by Δx_C = 0.025 L while the
  // beam vibrates. On a beam bent to a centre deflection of 3 h the beam under
  // the window moves by far more than the clearance R − h between 0.30 L and
  // 0.325 L, so the slider must follow w and w' there: the moved z_C differs
  // from the old by exactly Δw up to the lift for the curvature under the
  // window (here bounded by a hundredth of the clearance), the corner that
  // touched still touches, and none is through the beam.
  const Scene scene = mueller_scene();
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
  MoreauStepper stepper(rom, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene),
                        BaseExcitation::from_scene(scene.excitation), scene.time_stepping.time_step);
  const double L = scene.beam.length, h = scene.beam.thickness;
  const double clearance = scene.window_height() - h;

  SystemState state = stepper.resting_state(0.30 * L, 0.);
  BeamPointKinematics p;
  Eigen::VectorXd mode1 = Eigen::VectorXd::Zero(5);
  mode1[0]              = 1.;
  rom.evaluate(0.5 * L, mode1, p);
  state.q = (3. * h / p.w) * mode1; // centre deflection 3 h
  state.u = (-2. * h / p.w) * mode1;
  state.s = stepper.geometry().resting_position(0.30 * L, 0., rom, stepper.base(), state.q);
  stepper.set_state(state);

  const double x_new = 0.325 * L;
  BeamPointKinematics old_point, new_point;
  rom.evaluate(0.30 * L, state.q, old_point);
  rom.evaluate(x_new, state.q, new_point);
  ASSERT_GT(std::abs(new_point.w - old_point.w), 2. * clearance); // keeping z_C would put a corner through the beam

  // Smallest upper gap before the move: the resting slider touches (≤ 0).
  CornerKinematics corner;
  double upper_gap_before = std::numeric_limits<double>::infinity();
  for (unsigned int k = 0; k < 2; ++k)
    {
      stepper.geometry().evaluate(k, state.t, rom, stepper.base(), state.q, state.s, corner);
      upper_gap_before = std::min(upper_gap_before, corner.gap);
    }
  ASSERT_LE(upper_gap_before, 0.);

  // The z_C shift beyond Δw is the curvature under the window: the corners
  // sit at ±B/2, where w differs from its tangent line by w'' B²/8.
  auto curvature = [&](const double x) {
    BeamPointKinematics a, b;
    rom.evaluate(x + 1e-5, state.q, a);
    rom.evaluate(x - 1e-5, state.q, b);
    return (a.dw - b.dw) / 2e-5;
  };
  const double B               = scene.slider.window_width;
  const double curvature_shift = std::abs(curvature(x_new) - curvature(0.30 * L)) * B * B / 8.;

  const SystemState moved = stepper.slider_moved_to(x_new);
  EXPECT_EQ(moved.s[0], x_new);
  EXPECT_NEAR(moved.s[1] - state.s[1], new_point.w - old_point.w, 1.5 * curvature_shift + 1e-3 * clearance);
  EXPECT_NEAR(moved.s[2] - state.s[2], std::atan(new_point.dw) - std::atan(old_point.dw), 1e-12);
  double upper_gap_after = std::numeric_limits<double>::infinity();
  for (unsigned int k = 0; k < n_slider_corners; ++k)
    {
      stepper.geometry().evaluate(k, moved.t, rom, stepper.base(), moved.q, moved.s, corner);
      EXPECT_GE(corner.gap, upper_gap_before - 1e-15) << "corner " << k << " is through the beam";
      if (corner_zeta(k) > 0)
        upper_gap_after = std::min(upper_gap_after, corner.gap);
    }
  EXPECT_NEAR(upper_gap_after, upper_gap_before, 1e-15); // still resting on the beam

  // The slider moves with the beam: its vertical velocity changes by Δẇ.
  BeamPointKinematics old_rate, new_rate;
  rom.evaluate(0.30 * L, state.u, old_rate);
  rom.evaluate(x_new, state.u, new_rate);
  EXPECT_NEAR(moved.v[1] - state.v[1], new_rate.w - old_rate.w, 1e-12);

  // Off the beam is refused, naming where.
  EXPECT_THROW(stepper.slider_moved_to(0.), std::invalid_argument);
}

namespace
{
  struct EnergyTotals
  {
    double delta_energy = 0, gravity = 0, damping = 0, excitation = 0, impact = 0, friction = 0, base_contact = 0,
           residual = 0, largest_term = 0;
    unsigned int periods = 0;
    double contact_fraction = 0;
  };
} // namespace

namespace
{
  EnergyTotals run_energy_balance(const double dt)
  {
    Scene scene                        = mueller_scene();
    scene.contact.friction_coefficient = 0.;
    scene.damping_ratio                = 0.;
    scene.time_stepping.end_time       = 0.5;
    scene.time_stepping.time_step      = dt;
    RomBeamSystem rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
    AdaptationRun run(scene, rom, RunOptions::from_scene(scene));
    EnergyTotals tot;
    run.on_period = [&](const PeriodRecord &p) {
      tot.delta_energy += p.energy_end - p.energy_start;
      tot.gravity += p.work_gravity;
      tot.damping += p.work_damping;
      tot.excitation += p.work_excitation;
      tot.impact += p.work_impact;
      tot.friction += p.work_friction;
      tot.base_contact += p.work_base_contact;
      tot.residual += p.energy_residual;
      tot.contact_fraction += p.contact_fraction;
      tot.largest_term = std::max({tot.largest_term, std::abs(p.work_excitation), std::abs(p.work_gravity),
                                   std::abs(p.work_impact), std::abs(p.work_base_contact), p.energy_end});
      ++tot.periods;
    };
    const RunResult result = run.run();
    EXPECT_EQ(result.status, RunStatus::completed) << result.message;
    std::cout << "dt = " << dt << " s, energy over " << tot.periods << " periods [J]: dE = " << tot.delta_energy
              << ", W_gravity = " << tot.gravity << ", W_excitation = " << tot.excitation
              << ", W_impact = " << tot.impact << ", W_base_contact = " << tot.base_contact
              << ", residual = " << tot.residual << ", mean contact fraction = "
              << tot.contact_fraction / tot.periods << "\n";
    return tot;
  }
} // namespace

TEST(EnergyBalance, ClosesWithoutFrictionAndDamping)
{
  // μ = 0, D = 0, the signature-move excitation (124 Hz, 14 m/s²), 0.5 s:
  // ΔE = W_gravity + W_excitation + W_impact + W_base-contact per period up to
  // the midpoint scheme's strain-energy error (the strain energy is evaluated
  // at q_M, not along q_B → q_E). Friction and damping work are exactly 0.
  const EnergyTotals tot = run_energy_balance(2e-5);
  EXPECT_GT(tot.periods, 60u);
  EXPECT_EQ(tot.friction, 0.);
  EXPECT_EQ(tot.damping, 0.);
  EXPECT_LT(tot.impact, 0.); // e_N = 0.5 dissipates
  EXPECT_GT(tot.excitation, 0.);
  // Stated tolerance: the summed residual below 1e-3 of the work the base put
  // in (measured: 4e-4 at Δt = 2e-5 s) ...
  EXPECT_LT(std::abs(tot.residual), 1e-3 * std::abs(tot.excitation));
  // ... and it is a discretisation error: it shrinks when Δt is halved.
  const EnergyTotals fine = run_energy_balance(1e-5);
  EXPECT_LT(std::abs(fine.residual), 0.6 * std::abs(tot.residual));
}

TEST(EndStop, RomRunStopsAtTheSupportWithoutNaN)
{
  // μ = 0 and a push toward x = 0: the run must stop when a corner would
  // leave [0, L], with everything before kept finite (the ROM's evaluate
  // throws outside [0, L], so a stray evaluation would fail the run).
  Scene scene                          = mueller_scene();
  scene.contact.friction_coefficient   = 0.;
  scene.initial.slider_position_over_L = 0.2;
  scene.time_stepping.end_time         = 2.;
  RomBeamSystem rom = RomBeamSystem::from_scene(scene, clamped_clamped_basis(scene.beam, 5));
  AdaptationRun run(scene, rom, RunOptions::from_scene(scene));
  SystemState s = run.state();
  s.v[0]        = -0.5; // [m/s]
  run.set_state(s);
  std::vector<TraceRow> rows;
  run.on_trace_row = [&](const TraceRow &r) { rows.push_back(r); };
  const RunResult result = run.run();
  EXPECT_EQ(result.status, RunStatus::slider_at_support) << result.message;
  EXPECT_NE(result.message.find("x = 0"), std::string::npos) << result.message;
  EXPECT_LT(result.t_end, 0.1);
  EXPECT_GT(result.slider_x_over_L, 0.);
  ASSERT_FALSE(rows.empty());
  for (const auto &r : rows)
    for (double v : {r.t, r.slider_x_over_L, r.slider_z, r.slider_beta, r.w_center, r.w_probe, r.amplitude_over_h})
      ASSERT_TRUE(std::isfinite(v));
  std::cout << result.message << "\n";
}

// θ > ½ (family (d) of issue 58): on a linear, undamped, unforced mode the
// implicit ROM is the θ-method of the Moreau–Jean structure, whose step
// follows here from its two equations solved by hand:
//   u_E (1 + θ²h²ω²) = u_B (1 − θ(1 − θ)h²ω²) − hω² q_B,
//   q_E = q_B + h((1 − θ)u_B + θ u_E).
// At ωΔt = 3 the step damps the mode (spectral radius < 1), where θ = ½
// keeps its amplitude; far beyond (ωΔt = 1000) the radius tends to
// (1 − θ)/θ per step.
TEST(RomImplicitBeamSystem, ThetaAboveOneHalfIsTheThetaMethodAndDampsUnresolvedModes)
{
  const Scene scene = linear_free_scene();
  for (const double theta : {0.51, 0.6, 1.0})
    for (const double w_dt : {3., 1000.})
      {
        ReducedOrderModel model(clamped_clamped_basis(scene.beam, 1), scene.damping_ratio, false);
        RomImplicitBeamSystem rom(std::move(model), scene.beam.thickness, BaseExcitation::from_scene(scene.excitation),
                                  theta);
        EXPECT_EQ(rom.theta(), theta);
        const double w = rom.model().basis().omega[0], h = w_dt / w;
        Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 1e-4), u = Eigen::VectorXd::Zero(1);
        double q_ref = 1e-4, u_ref = 0;
        const auto energy = [&](const double q_, const double u_) { return 0.5 * (u_ * u_ + w * w * q_ * q_); };
        const double E0 = energy(q_ref, u_ref);
        for (unsigned int k = 1; k <= 50; ++k)
          {
            free_step(rom, (k - 1) * h, h, q, u);
            const double u_E = (u_ref * (1. - theta * (1. - theta) * w_dt * w_dt) - h * w * w * q_ref) /
                               (1. + theta * theta * w_dt * w_dt);
            q_ref = q_ref + h * ((1. - theta) * u_ref + theta * u_E);
            u_ref = u_E;
            ASSERT_NEAR(q[0], q_ref, 1e-4 * 1e-10) << "θ = " << theta << ", ωΔt = " << w_dt << ", step " << k;
            ASSERT_NEAR(u[0], u_ref, 1e-4 * w * 1e-10) << "θ = " << theta << ", ωΔt = " << w_dt << ", step " << k;
          }
        const double ratio = std::sqrt(energy(q[0], u[0]) / E0); // amplitude after 50 steps
        EXPECT_LT(ratio, 1.) << "θ = " << theta << ", ωΔt = " << w_dt;
        if (w_dt == 1000.)
          {
            EXPECT_NEAR(std::pow(ratio, 1. / 50), (1. - theta) / theta, 0.01) << "θ = " << theta;
          }
      }
  // θ outside [½, 1] is refused.
  ReducedOrderModel model(clamped_clamped_basis(scene.beam, 1), scene.damping_ratio, false);
  EXPECT_THROW(RomImplicitBeamSystem(model, scene.beam.thickness, BaseExcitation::from_scene(scene.excitation), 0.4),
               std::invalid_argument);
}

// The θ-method's Newton step and iteration matrix on the nonlinear beam:
// the residual with q̄ = q_M + θ²Δt(u − u_B) + (2θ − 1)Δt u_B, the damping
// on θu + (1 − θ)u_B and the load at t_M + (2θ − 1)Δt vanishes at u_free,
// and the structured solve inverts S = I + θΔt C + θ²Δt²(Ω² + ∂f/∂q).
TEST(RomImplicitBeamSystem, ThetaStepSolvesItsResidualAndInvertsItsIterationMatrix)
{
  const Scene scene    = mueller_scene();
  const unsigned int N = 6;
  const double theta   = 0.6;
  ReducedOrderModel reduced(clamped_clamped_basis(scene.beam, N), scene.damping_ratio, true);
  RomImplicitBeamSystem rom(std::move(reduced), scene.beam.thickness, BaseExcitation::from_scene(scene.excitation),
                            theta);
  const ReducedOrderModel &model = rom.model();
  const Eigen::ArrayXd w         = model.basis().omega.array();
  const double dt                = 0.5 / w[0];
  Eigen::VectorXd q_M, u_B, u_E;
  large_state(rom, scene, q_M, u_B);
  const double t_M    = 0.3e-3;
  const BeamStep step = rom.free_velocity(t_M, q_M, u_B, dt, u_E);
  const double a      = rom.excitation().acceleration(t_M + (2. * theta - 1.) * dt);
  const Eigen::VectorXd q = q_M + theta * theta * dt * (u_E - u_B) + (2. * theta - 1.) * dt * u_B;
  const Eigen::VectorXd c = (2. * scene.damping_ratio * w).matrix();
  const Eigen::VectorXd R =
    (u_E - u_B) + dt * (c.cwiseProduct(theta * u_E + (1. - theta) * u_B) + (w * w).matrix().cwiseProduct(q) +
                        model.nonlinear_force(q) - a * model.basis().gamma);
  EXPECT_LT(R.norm(), 1e-9 * (u_E.norm() + q.norm() / dt)) << "Newton's u_free does not solve the θ step";
  Eigen::MatrixXd S = (theta * theta * dt * dt) * model.nonlinear_tangent(q);
  S.diagonal() += (1. + theta * dt * c.array() + theta * theta * dt * dt * w * w).matrix();
  const Eigen::MatrixXd B = Eigen::MatrixXd::Identity(N, N);
  Eigen::MatrixXd X(N, N);
  step.solve_iteration_matrix(B, X);
  EXPECT_LT((S * X - B).norm(), 1e-8 * B.norm());
}
