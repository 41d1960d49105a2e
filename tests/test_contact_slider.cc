// Tests of the contact code (contact/) on rigid beams, where every answer is
// known in closed form: a slider at rest stays at rest, Coulomb's block on an
// incline, Newton's impact law, the prox solver on a single contact, the
// solver's failure path and the end stop at a support.
//
// The rigid beam is a BeamSystem with no coordinates: w(x) = x tan α relative
// to a base that does not move, so the Delassus matrix is the slider's alone.
#include "runs/adaptation_run.h"
#include "numerics/spring_dashpot_restitution.h"
#include "contact/contact_products.h"
#include "contact/moreau_stepper.h"
#include "contact/prox_solver.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <utility>

using namespace beamslider;

namespace
{
  // A beam that never moves: w(x) = slope · x [m], no coordinates.
  class RigidBeam : public BeamSystem
  {
  public:
    RigidBeam(const double length, const double thickness, const double slope = 0.)
      : length_(length)
      , thickness_(thickness)
      , slope_(slope)
    {}
    unsigned int n_dofs() const override { return 0; }
    double length() const override { return length_; }
    double thickness() const override { return thickness_; }
    void evaluate(const double x, const Eigen::VectorXd &, BeamPointKinematics &out) const override
    {
      if (!(x >= 0. && x <= length_))
        throw std::out_of_range("rigid beam evaluated outside [0, L]");
      out.w  = slope_ * x;
      out.dw = slope_;
      out.grad_w.resize(0);
      out.grad_dw.resize(0);
    }
    double max_stable_time_step() const override { return std::numeric_limits<double>::infinity(); }
    double energy(const Eigen::VectorXd &, const Eigen::VectorXd &) const override { return 0.; }

  protected:
    void compute_free_velocity(double, const Eigen::VectorXd &, const Eigen::VectorXd &u_B, double,
                               Eigen::VectorXd &u_free) override
    {
      u_free = u_B;
    }
    void apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                        Eigen::Ref<Eigen::MatrixXd> X) const override
    {
      X = B;
    }
    void compute_step_work(const Eigen::VectorXd &, double &d, double &e) const override { d = e = 0.; }

  private:
    double length_, thickness_, slope_;
  };

  // The mueller2023 slider (scene.h defaults) without base motion.
  Scene static_scene()
  {
    Scene scene;
    scene.excitation.acceleration_amplitude = 0.;
    return scene;
  }
} // namespace

TEST(ProxSolver, SingleContactMatchesClosedForm)
{
  // One contact, G = diag(2, 3): P_N = −c_N/2 if c_N < 0; P_T = −c_T/3 if that
  // lies inside ±μ P_N (stick), else ∓μ P_N (slip).
  const ProxSolver solver;
  Eigen::MatrixXd G = Eigen::Vector2d(2., 3.).asDiagonal();
  Eigen::VectorXd mu(1);
  mu << 0.3;
  Eigen::VectorXd P = Eigen::VectorXd::Zero(2);

  auto result = solver.solve(G, Eigen::Vector2d(-1., 0.5), mu, P); // slip: −0.5/3 beyond 0.15
  ASSERT_TRUE(result.converged);
  EXPECT_NEAR(P[0], 0.5, 1e-14);
  EXPECT_NEAR(P[1], -0.15, 1e-14);

  P.setZero();
  result = solver.solve(G, Eigen::Vector2d(-1., 0.3), mu, P); // stick: −0.1
  ASSERT_TRUE(result.converged);
  EXPECT_NEAR(P[0], 0.5, 1e-14);
  EXPECT_NEAR(P[1], -0.1, 1e-14);

  P << 1., 1.; // warm start from a wrong guess; separating contact
  result = solver.solve(G, Eigen::Vector2d(0.2, 1.), mu, P);
  ASSERT_TRUE(result.converged);
  EXPECT_EQ(P[0], 0.);
  EXPECT_EQ(P[1], 0.);
}

TEST(ProxSolver, CoupledContactsSatisfyComplementarity)
{
  // Two coupled frictionless-direction contacts: check the solution of the
  // LCP directly, ξ = G P + c ≥ 0, P ≥ 0, ξ·P = 0 (μ = 0 zeroes P_T).
  Eigen::MatrixXd G(4, 4);
  G << 2.0, 0.1, 0.8, 0.0, //
    0.1, 1.0, 0.0, 0.2,    //
    0.8, 0.0, 1.5, 0.1,    //
    0.0, 0.2, 0.1, 1.2;
  const Eigen::Vector4d c(-1.0, 0.3, -0.2, -0.5);
  const Eigen::Vector2d mu(0., 0.);
  Eigen::VectorXd P = Eigen::VectorXd::Zero(4);
  const auto result = ProxSolver().solve(G, c, mu, P);
  ASSERT_TRUE(result.converged);
  const Eigen::VectorXd xi = G * P + c;
  EXPECT_EQ(P[1], 0.);
  EXPECT_EQ(P[3], 0.);
  for (int i : {0, 2})
    {
      EXPECT_GE(P[i], 0.);
      EXPECT_GE(xi[i], -1e-9);
      EXPECT_NEAR(P[i] * xi[i], 0., 1e-9);
    }
  // Contact 0 pushes contact 2 off: P_N2 = 0, P_N0 = 1/2.
  EXPECT_NEAR(P[0], 0.5, 1e-9);
  EXPECT_EQ(P[2], 0.);
}

TEST(ProxSolver, IterationCapIsReportedAsFailure)
{
  Eigen::MatrixXd G(2, 2);
  G << 1., 0.9, 0.9, 1.;
  Eigen::MatrixXd G4 = Eigen::MatrixXd::Identity(4, 4);
  G4.block(0, 0, 2, 2) = G; // normals of two contacts strongly coupled
  G4(0, 2) = G4(2, 0) = 0.9;
  G4(0, 1) = G4(1, 0) = 0.;
  Eigen::VectorXd P = Eigen::VectorXd::Zero(4);
  ProxSolverSettings settings;
  settings.max_iterations = 3;
  settings.guess_modes    = false; // the sweeps' own cap (a mode guess solves this at once)
  const auto result = ProxSolver(settings).solve(G4, Eigen::Vector4d(-1., 0., -1., 0.), Eigen::Vector2d(0.2, 0.2), P);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 3u);
  EXPECT_GT(result.residual, settings.tolerance);
}

TEST(RestingSlider, StaysPutOnStaticBeamFor1e5Steps)
{
  // Placed with zero gap, the slider is held from the first step; it may
  // settle at most by the midpoint scheme's penetration g Δt² (Moreau's scheme
  // has no position correction); after that it must not move at all.
  const Scene scene = static_scene();
  const double dt   = scene.time_stepping.time_step;
  RigidBeam beam(scene.beam.length, scene.beam.thickness);
  MoreauStepper stepper(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene), BaseExcitation{},
                        dt);
  const SystemState start = stepper.resting_state(0.3 * scene.beam.length);
  stepper.set_state(start);
  for (unsigned int k = 0; k < 100; ++k)
    stepper.step();
  const SystemState settled = stepper.state();
  EXPECT_LT(std::abs(settled.s[1] - start.s[1]), scene.contact.gravity * dt * dt);
  unsigned int max_active = 0, max_iterations = 0;
  for (unsigned int k = 0; k < 100000; ++k)
    {
      const StepReport &r = stepper.step();
      max_active          = std::max(max_active, r.n_active);
      max_iterations      = std::max(max_iterations, r.iterations);
    }
  const SystemState &end = stepper.state();
  EXPECT_EQ(max_active, 2u); // the two upper corners carry the slider
  EXPECT_NEAR(end.t, 100100 * dt, 1e-12);
  EXPECT_NEAR(end.s[0], start.s[0], 1e-15);
  EXPECT_NEAR(end.s[1], settled.s[1], 1e-15);
  EXPECT_NEAR(end.s[2], start.s[2], 1e-15);
  EXPECT_LT(end.v.norm(), 1e-12);
  // The corners' normal impulses carry the weight: Σ P_N = m g Δt.
  const double weight_impulse = scene.slider_mass() * scene.contact.gravity * dt;
  EXPECT_NEAR(stepper.corner_impulses()[0][0] + stepper.corner_impulses()[1][0], weight_impulse,
              1e-9 * weight_impulse);
  std::cout << "resting slider: at most " << max_iterations << " Gauss-Seidel sweeps per step\n";
}

namespace
{
  // Block on a rigid beam with slope tan α: displacement along x after time T.
  double incline_displacement(const double tan_alpha, const double mu, const double T, const double dt)
  {
    Scene scene                         = static_scene();
    scene.contact.friction_coefficient = mu;
    RigidBeam beam(scene.beam.length, scene.beam.thickness, tan_alpha);
    MoreauStepper stepper(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene),
                          BaseExcitation{}, dt);
    const SystemState start = stepper.resting_state(0.1);
    stepper.set_state(start);
    const unsigned int n = std::lround(T / dt);
    for (unsigned int k = 0; k < n; ++k)
      stepper.step();
    // Slides without tipping (Moreau leaves O(g Δt²) penetrations, so the two
    // corners may differ by 1e-11 m).
    EXPECT_NEAR(stepper.state().s[2], start.s[2], 1e-7);
    return stepper.state().s[0] - start.s[0];
  }
} // namespace

TEST(InclinedRigidBeam, SlidesWithCoulombAccelerationWhenSteeperThanFriction)
{
  // tan α = 0.3 > μ = 0.2: a = g (sin α − μ cos α) down the slope, so
  // Δx = −½ a T² cos α (the beam rises with x).
  const double tan_alpha = 0.3, mu = 0.2, g = 9.81, T = 0.2;
  const double alpha = std::atan(tan_alpha);
  const double a     = g * (std::sin(alpha) - mu * std::cos(alpha));
  const double dx    = incline_displacement(tan_alpha, mu, T, 1e-5);
  const double expected = -0.5 * a * T * T * std::cos(alpha);
  EXPECT_NEAR(dx / expected, 1., 1e-4) << "dx = " << dx << " m, expected " << expected << " m";
}

TEST(InclinedRigidBeam, SticksWhenFlatterThanFriction)
{
  // tan α = 0.1 < μ = 0.2: the block stays.
  const double dx = incline_displacement(0.1, 0.2, 0.2, 1e-5);
  EXPECT_LT(std::abs(dx), 1e-12) << "dx = " << dx << " m";
}

TEST(DroppedSlider, LosesOneMinusRestitutionSquaredOfNormalKineticEnergy)
{
  // The slider falls onto the flat beam with both upper corners at once; the
  // Newton law gives v_E = −e_N v_B in the impact step, so the kinetic energy
  // after is e_N² of that before.
  Scene scene               = static_scene();
  scene.contact.restitution = 0.5;
  RigidBeam beam(scene.beam.length, scene.beam.thickness);
  MoreauStepper stepper(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene), BaseExcitation{},
                        1e-6);
  SystemState start = stepper.resting_state(0.07);
  start.s[1] += 2e-5; // 20 µm above contact (the clearance R − h is 50 µm)
  start.v[1] = -0.05; // [m/s]
  stepper.set_state(start);
  for (unsigned int k = 0; k < 100000; ++k)
    {
      const SystemState before = stepper.state();
      const StepReport &report = stepper.step();
      if (report.n_active == 0)
        continue;
      const SystemState &after = stepper.state();
      const double m          = scene.slider_mass();
      const double T_before   = 0.5 * m * before.v.squaredNorm();
      const double T_after    = 0.5 * m * after.v.squaredNorm();
      EXPECT_EQ(report.n_active, 2u);
      EXPECT_NEAR(after.v[1] / before.v[1], -0.5, 1e-9);
      EXPECT_NEAR((T_before - T_after) / T_before, 1. - 0.5 * 0.5, 1e-9);
      // The step's energy identity: ΔT = work of gravity + work of the impact.
      EXPECT_NEAR(T_after - T_before, report.work_gravity + report.work_impact, 1e-12 * T_before);
      EXPECT_LT(report.work_impact, 0.);
      return;
    }
  FAIL() << "the slider never reached the beam";
}

namespace
{
  // The restitution of the force-limited spring–dashpot by an independent
  // route: RK4 on ẍ = −x − 2ζẋ (unit mass and stiffness) from x = 0, ẋ = 1,
  // until the force x + 2ζẋ changes sign, the crossing interpolated: the
  // velocity ratio and the time of the crossing (in units of 1/ω).
  std::pair<double, double> integrated_restitution(const double zeta)
  {
    const double h = 1e-4;
    Eigen::Vector2d y(0., 1.);
    auto f = [&](const Eigen::Vector2d &z) { return Eigen::Vector2d(z[1], -z[0] - 2. * zeta * z[1]); };
    for (double t = 0; t < 10.; t += h)
      {
        const Eigen::Vector2d k1 = f(y), k2 = f(y + 0.5 * h * k1), k3 = f(y + 0.5 * h * k2), k4 = f(y + h * k3);
        const Eigen::Vector2d next = y + h / 6. * (k1 + 2. * k2 + 2. * k3 + k4);
        const double F0 = y[0] + 2. * zeta * y[1], F1 = next[0] + 2. * zeta * next[1];
        if (F1 <= 0.)
          return {-(y[1] + (next[1] - y[1]) * F0 / (F0 - F1)), t + h * F0 / (F0 - F1)};
        y = next;
      }
    return {std::numeric_limits<double>::quiet_NaN(), 0.};
  }

  // The slider dropped flat on the rigid beam, without gravity, onto
  // compliant corners: its velocity ratio after the contact and the number
  // of steps the contact lasted.
  std::pair<double, unsigned int> compliant_drop(const Scene &scene, const double dt)
  {
    RigidBeam beam(scene.beam.length, scene.beam.thickness);
    MoreauStepper stepper(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene), BaseExcitation{},
                          dt);
    SystemState start = stepper.resting_state(0.07);
    start.s[1] += 2e-5; // 20 µm above contact (the clearance R − h is 50 µm)
    start.v[1] = -0.05; // [m/s]
    stepper.set_state(start);
    unsigned int in_contact = 0;
    for (unsigned int k = 0; k < 1000000; ++k)
      {
        const StepReport &report = stepper.step();
        if (report.n_active > 0 && report.slider_impulse.norm() > 0.)
          ++in_contact;
        else if (in_contact > 0)
          return {stepper.state().v[1] / start.v[1], in_contact};
      }
    return {std::numeric_limits<double>::quiet_NaN(), 0};
  }
} // namespace

TEST(CompliantNormalLaw, DampingRatioGivesTheRestitutionOfAnIndependentIntegration)
{
  for (const double e : {0.95, 0.7, 0.5, 0.3, 0.2})
    {
      const double zeta = pushing_spring_dashpot_damping_ratio(e);
      EXPECT_NEAR(pushing_spring_dashpot_restitution(zeta), e, 1e-12);
      EXPECT_NEAR(integrated_restitution(zeta).first, e, 1e-6) << "zeta = " << zeta;
    }
  // Light damping: the corner leaves when the spring is nearly relaxed, so
  // the textbook exp(−ζπ/√(1 − ζ²)) holds to O(ζ²).
  const double zeta = 0.01;
  EXPECT_NEAR(pushing_spring_dashpot_restitution(zeta), std::exp(-zeta * M_PI / std::sqrt(1. - zeta * zeta)), 5e-4);
  // A dashpot that only pushes cannot return less than ~13.5 %.
  EXPECT_THROW(pushing_spring_dashpot_damping_ratio(0.1), std::invalid_argument);
  Scene scene                    = static_scene();
  scene.contact.normal_stiffness = 1e6;
  scene.contact.restitution      = 0.;
  try
    {
      ContactLaw::from_scene(scene);
      FAIL() << "e_N = 0 with a compliant law was accepted";
    }
  catch (const std::invalid_argument &error)
    {
      EXPECT_NE(std::string(error.what()).find("e_N = 0"), std::string::npos) << error.what();
    }
}

TEST(DroppedSlider, OnCompliantCornersLeavesWithRestitutionWithinTheStepsBound)
{
  // k_N = 1e6 N/m per corner, m/2 on each: ω = √(2 k_N / m), the contact
  // lasts t_leave/ω ≈ 0.41 ms. The step is first order where a contact
  // starts: the dashpot's force jumps to c_N v there, and the step applies
  // it from the step's start, an impulse error of at most c_N v Δt, so the
  // velocity ratio is e_N to within 2ζωΔt (relative); without the dashpot
  // (e_N = 1) the spring alone errs by O((ωΔt)²) at its kink, and the
  // trapezoidal rule keeps its energy in between.
  Scene scene                    = static_scene();
  scene.contact.gravity          = 0.;
  scene.contact.normal_stiffness = 1e6;
  const double omega = std::sqrt(2. * scene.contact.normal_stiffness / scene.slider_mass());
  for (const double e : {0.5, 1.})
    {
      scene.contact.restitution = e;
      const double zeta         = pushing_spring_dashpot_damping_ratio(e);
      const double duration     = (e < 1. ? integrated_restitution(zeta).second : M_PI) / omega;
      for (unsigned int i = 0; i < 5; ++i)
        {
          const double dt           = duration / (10 << i);
          const auto [ratio, steps] = compliant_drop(scene, dt);
          const double bound = e < 1. ? 2. * zeta * omega * dt : std::pow(omega * dt, 2);
          EXPECT_LT(std::abs(-ratio / e - 1.), bound) << "e_N = " << e << ", dt = " << dt << " s";
          EXPECT_NEAR(steps * dt, duration, 2. * dt) << "e_N = " << e << ", dt = " << dt << " s";
        }
    }
}

TEST(MoreauStepper, SolverIterationCapThrowsWithTimeAndContacts)
{
  const Scene scene = static_scene();
  RigidBeam beam(scene.beam.length, scene.beam.thickness);
  ProxSolverSettings settings;
  settings.max_iterations = 1; // two coupled corners need more than one sweep
  settings.guess_modes    = false; // (a mode guess would solve them without sweeping)
  MoreauStepper stepper(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene), BaseExcitation{},
                        scene.time_stepping.time_step, settings);
  const SystemState start = stepper.resting_state(0.05);
  stepper.set_state(start);
  // The first steps may be contact-free (zero gap up to round-off); the first
  // step with the two corners active must throw.
  for (unsigned int k = 0; k < 10; ++k)
    {
      const SystemState before = stepper.state();
      try
        {
          stepper.step();
        }
      catch (const ContactSolverFailure &e)
        {
          EXPECT_EQ(e.t, before.t);
          EXPECT_LT(e.t, 10 * scene.time_stepping.time_step);
          EXPECT_EQ(e.n_active, 2u);
          EXPECT_EQ(e.iterations, 1u);
          EXPECT_GT(e.residual, 0.);
          EXPECT_NE(std::string(e.what()).find("upper-left, upper-right"), std::string::npos) << e.what();
          EXPECT_EQ(stepper.state().t, before.t); // nothing accepted
          EXPECT_EQ(stepper.state().s, before.s);
          return;
        }
    }
  FAIL() << "the capped solver was accepted";
}

TEST(MoreauStepper, RefusesTimeStepAboveBeamLimit)
{
  struct LimitedBeam : RigidBeam
  {
    using RigidBeam::RigidBeam;
    double max_stable_time_step() const override { return 1e-5; }
  };
  const Scene scene = static_scene();
  LimitedBeam beam(scene.beam.length, scene.beam.thickness);
  try
    {
      MoreauStepper(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene), BaseExcitation{}, 2e-5);
      FAIL();
    }
  catch (const std::invalid_argument &e)
    {
      EXPECT_NE(std::string(e.what()).find("time step"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("1e-05"), std::string::npos) << e.what();
    }
}

TEST(EndStop, RunStopsCleanlyWhenTheWindowReachesTheSupport)
{
  // Frictionless flat beam, slider pushed toward x = L at 0.1 m/s: the right
  // corners (x_C + B/2) reach L after (L − B/2 − x_C0)/v. The run must stop
  // there with a message, keep the rows written, and never evaluate the beam
  // outside [0, L] (RigidBeam throws if it were).
  Scene scene                          = static_scene();
  scene.contact.friction_coefficient   = 0.;
  scene.time_stepping.time_step        = 1e-5;
  scene.time_stepping.end_time         = 1.;
  scene.initial.slider_position_over_L = 0.85;
  RigidBeam beam(scene.beam.length, scene.beam.thickness);
  AdaptationRun run(scene, beam, RunOptions::from_scene(scene));
  SystemState s = run.state();
  s.v[0]        = 0.1;
  run.set_state(s);

  std::vector<TraceRow> rows;
  run.on_trace_row = [&](const TraceRow &r) { rows.push_back(r); };
  const RunResult result = run.run();

  const double L = scene.beam.length, B = scene.slider.window_width;
  const double t_expected = (L - 0.5 * B - 0.85 * L) / 0.1;
  EXPECT_EQ(result.status, RunStatus::slider_at_support);
  EXPECT_NEAR(result.t_end, t_expected, 2e-5);
  EXPECT_NEAR(result.slider_x_over_L * L, L - 0.5 * B, 1e-5);
  EXPECT_NE(result.message.find("x = L"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("t = "), std::string::npos) << result.message;
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(rows.back().t, result.t_end, 1e-12); // the trace ends at the stop
  EXPECT_GT(rows.size(), 150u);                    // ~1000 rows/s for 0.16 s, all kept
  for (const auto &r : rows)
    for (double v : {r.t, r.slider_x_over_L, r.slider_z, r.slider_beta, r.w_center, r.w_probe, r.amplitude_over_h})
      ASSERT_TRUE(std::isfinite(v));
  EXPECT_LE(rows.back().slider_x_over_L * L + 0.5 * B, L);
}

TEST(PrescribedPosition, HorizontalContactForceHoldsSliderOnFrictionlessIncline)
{
  // x_C held fixed on a frictionless rigid incline (tan α = 0.2): z_C and β
  // free, so the vertical balance N cos α = m g gives N = m g / cos α, whose
  // horizontal part on the slider is −N sin α = −m g tan α. That is F̄_x in
  // every excitation period. Also: x_C never moves, and the trace has
  // output_rate · T + 1 rows.
  Scene scene                             = static_scene();
  scene.excitation.acceleration_amplitude = 0.; // periods of 1/124 s, no motion
  scene.contact.friction_coefficient      = 0.;
  scene.time_stepping.end_time            = 0.2;
  scene.initial.slider_position_over_L    = 0.5;
  const double tan_alpha                  = 0.2;
  RigidBeam beam(scene.beam.length, scene.beam.thickness, tan_alpha);
  RunOptions options                 = RunOptions::from_scene(scene);
  options.prescribed_slider_position = true;
  AdaptationRun run(scene, beam, options);
  const double x0 = run.state().s[0];
  unsigned int n_rows = 0;
  std::vector<PeriodRecord> periods;
  run.on_trace_row = [&](const TraceRow &) { ++n_rows; };
  run.on_period    = [&](const PeriodRecord &p) { periods.push_back(p); };
  const RunResult result = run.run();
  ASSERT_EQ(result.status, RunStatus::completed) << result.message;
  EXPECT_EQ(run.state().s[0], x0);
  EXPECT_EQ(n_rows, 201u);
  ASSERT_GE(periods.size(), 20u);
  const double expected = -scene.slider_mass() * scene.contact.gravity * tan_alpha;
  for (std::size_t i = 1; i < periods.size(); ++i) // the first period includes the settling step
    EXPECT_NEAR(periods[i].mean_horizontal_contact_force / expected, 1., 1e-6) << "period " << i;
}

// The contact step asks for w0 and ẇ0 together (one shared sine–cosine of
// the phase); they must be the separate formulas' values to the bit, over
// many periods and without excitation.
TEST(BaseExcitation, DisplacementAndVelocityTogetherAreTheSeparateValuesExactly)
{
  const BaseExcitation base{14., 2. * M_PI * 124.};
  for (unsigned int i = 0; i <= 100000; ++i)
    {
      const double t = 20. * i / 100000. + 1e-7 * (i % 7); // 0 to 20 s, off the grid too
      double w0 = NAN, dw0 = NAN;
      base.displacement_and_velocity(t, w0, dw0);
      ASSERT_EQ(w0, base.displacement(t)) << "t = " << t;
      ASSERT_EQ(dw0, base.velocity(t)) << "t = " << t;
    }
  // w0 = (â/Ω²) cos Ωt, ẇ0 = −(â/Ω) sin Ωt: at t = 0 the amplitude and zero rate.
  double w0 = NAN, dw0 = NAN;
  base.displacement_and_velocity(0., w0, dw0);
  EXPECT_DOUBLE_EQ(w0, 14. / std::pow(2. * M_PI * 124., 2));
  EXPECT_EQ(dw0, 0.);
  const BaseExcitation still{};
  still.displacement_and_velocity(3., w0, dw0);
  EXPECT_EQ(w0, 0.);
  EXPECT_EQ(dw0, 0.);
}

// The Moreau step's written-out products of the contact block
// (contact/contact_products.h) must return what the Eigen expressions they
// replace return, to the bit, for every size a step meets: beam coordinates
// from one to the FE's 131, one to four active corners. Random entries over
// six decades, so that every rounding shows.
//
// "To the bit" is a property of the baseline x86-64 instruction set (SSE2,
// no fused multiply-add), on which Eigen's kernels sum in one fixed order.
// Built for a machine with AVX or fused multiply-adds (BEAMSLIDER_NATIVE,
// CMakeLists.txt), Eigen's packets are wider and its products fused: there
// the two forms must agree within the rounding bound of a sum of k
// products, |Δ| ≤ 2 (k + 2) ε Σ|terms| (each form within (k + 2) ε Σ|terms|
// of the exact sum; Higham, Accuracy and Stability of Numerical Algorithms,
// §3.1), which a wrong index or a lost term exceeds by decades.
namespace
{
#if defined(__AVX__) || defined(__FP_FAST_FMA)
constexpr bool eigen_sums_in_a_fixed_order = false;
#else
constexpr bool eigen_sums_in_a_fixed_order = true;
#endif

::testing::AssertionResult same_sum(const double value, const double expected, const Eigen::Index k,
                                    const double sum_of_magnitudes)
{
  const double bound = 2. * (k + 2) * std::numeric_limits<double>::epsilon() * sum_of_magnitudes;
  if (eigen_sums_in_a_fixed_order ? value == expected : std::abs(value - expected) <= bound)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << value << " against " << expected << " (difference "
                                       << value - expected << ", allowed "
                                       << (eigen_sums_in_a_fixed_order ? 0. : bound) << ")";
}
} // namespace

TEST(ContactProducts, SumInTheOrderOfTheEigenExpressionsTheyReplace)
{
  std::mt19937_64 random(20261129);
  std::uniform_real_distribution<double> unit(-1., 1.);
  auto draw = [&]() { return unit(random) * std::pow(10., 3. * unit(random)); };
  for (const Eigen::Index n : {1, 2, 3, 5, 7, 10, 16, 131})
    for (const Eigen::Index m2 : {2, 4, 6, 8})
      for (int trial = 0; trial < 200; ++trial)
        {
          // The stepper's storage: blocks of n × 8 and 3 × 8 matrices.
          Eigen::MatrixXd W_b_store(n, 8), X_store(n, 8);
          Eigen::Matrix<double, 3, 8> W_s_store;
          Eigen::Matrix<double, 8, 1> imposed_store, P_store, out_store, expected_store;
          Eigen::Matrix<double, 8, 8> G_store, G_expected_store;
          for (double *x : {W_b_store.data(), X_store.data()})
            for (Eigen::Index i = 0; i < n * 8; ++i)
              x[i] = draw();
          for (Eigen::Index i = 0; i < 24; ++i)
            W_s_store.data()[i] = draw();
          for (Eigen::Index i = 0; i < 8; ++i)
            {
              imposed_store[i] = draw();
              P_store[i]       = draw();
            }
          for (Eigen::Index i = 0; i < 64; ++i)
            G_store.data()[i] = G_expected_store.data()[i] = draw();
          Eigen::VectorXd u(n), u_E(n);
          for (Eigen::Index i = 0; i < n; ++i)
            u[i] = u_E[i] = draw();
          const Eigen::Vector3d v(draw(), draw(), draw()), inv_mass(std::abs(draw()), std::abs(draw()), std::abs(draw()));

          const auto W_b = W_b_store.leftCols(m2);
          const auto X   = X_store.leftCols(m2);
          const auto W_s = W_s_store.leftCols(m2);
          const auto imp = imposed_store.head(m2);
          const auto P   = P_store.head(m2);

          // W_bᵀu + W_sᵀv + imposed, as the step wrote it before.
          auto expected = expected_store.head(m2);
          expected.noalias() = W_b.transpose() * u;
          expected.noalias() += W_s.transpose().lazyProduct(v);
          expected += imp;
          auto out = out_store.head(m2);
          relative_velocities(W_b, W_s, imp, u, v, out);
          const Eigen::Matrix<double, 8, 1> magnitude_store =
            (W_b_store.transpose().cwiseAbs() * u.cwiseAbs() + W_s_store.transpose().cwiseAbs() * v.cwiseAbs() +
             imposed_store.cwiseAbs());
          for (Eigen::Index k = 0; k < m2; ++k)
            ASSERT_TRUE(same_sum(out[k], expected[k], n + 4, magnitude_store[k]))
              << "W_bᵀu + W_sᵀv + imposed, n = " << n << ", 2m = " << m2;

          // G += W_sᵀ M_s⁻¹ W_s.
          auto G_expected = G_expected_store.topLeftCorner(m2, m2);
          const Eigen::Matrix<double, 8, 8> G_magnitude =
            G_store.cwiseAbs() + (W_s_store.transpose().cwiseAbs() * inv_mass.asDiagonal()) * W_s_store.cwiseAbs();
          G_expected.noalias() += (W_s.transpose() * inv_mass.asDiagonal()).lazyProduct(W_s);
          add_slider_part(W_s, inv_mass, G_store.topLeftCorner(m2, m2));
          for (Eigen::Index j = 0; j < m2; ++j)
            for (Eigen::Index i = 0; i < m2; ++i)
              ASSERT_TRUE(same_sum(G_store(i, j), G_expected(i, j), 2 * 3 + 1, G_magnitude(i, j)))
                << "G's slider part, 2m = " << m2;

          // u_E += X P.
          Eigen::VectorXd u_E_expected = u_E;
          const Eigen::VectorXd u_E_magnitude = u_E.cwiseAbs() + X.cwiseAbs() * P.cwiseAbs();
          u_E_expected.noalias() += X.lazyProduct(P);
          add_product(X, P, u_E);
          for (Eigen::Index r = 0; r < n; ++r)
            ASSERT_TRUE(same_sum(u_E[r], u_E_expected[r], m2 + 1, u_E_magnitude[r])) << "X P, n = " << n << ", 2m = " << m2;
        }
}
