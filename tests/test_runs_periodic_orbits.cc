// Shooting and arclength continuation (numerics/periodic_orbits.h) on systems
// with known answers: the damped linear oscillator (multipliers in closed
// form), the forced Duffing oscillator continued in frequency through both
// turning points against its harmonic-balance response curve, and a ball
// bouncing on a vibrating table, whose one-impact-per-period orbit and its
// stability are known in closed form.
#include "numerics/periodic_orbits.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>

namespace beamslider
{
  namespace
  {
    // ẍ + 2ζẋ + x + γx³ = F cos Ωt over one period 2π/Ω, classical RK4 on
    // `steps` steps. Observables: the first harmonic's amplitude and the
    // largest |x| over the period.
    struct Duffing
    {
      double zeta = 0.02, gamma = 0.04, force = 0.1;
      unsigned int steps = 400;

      PeriodMapValue operator()(const Eigen::VectorXd &y, const double omega) const
      {
        const double T = 2. * M_PI / omega, h = T / steps;
        auto f         = [&](const double t, const Eigen::Vector2d &s) {
          return Eigen::Vector2d(s[1], force * std::cos(omega * t) - 2. * zeta * s[1] - s[0] - gamma * std::pow(s[0], 3));
        };
        Eigen::Vector2d s(y[0], y[1]);
        double a1 = 0, b1 = 0, peak = 0;
        for (unsigned int i = 0; i < steps; ++i)
          {
            const double t = i * h;
            // First-harmonic coefficients by the trapezoidal rule (exact for a
            // trigonometric polynomial of low degree on a uniform grid).
            a1 += s[0] * std::cos(omega * t);
            b1 += s[0] * std::sin(omega * t);
            peak                   = std::max(peak, std::abs(s[0]));
            const Eigen::Vector2d k1 = f(t, s), k2 = f(t + h / 2, s + h / 2 * k1), k3 = f(t + h / 2, s + h / 2 * k2),
                                  k4 = f(t + h, s + h * k3);
            s += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
          }
        PeriodMapValue v;
        v.end         = Eigen::Vector2d(s[0], s[1]);
        v.observables = Eigen::Vector2d(2. / steps * std::hypot(a1, b1), peak);
        return v;
      }
    };

    // Harmonic balance with one harmonic, x = A cos(Ωt − φ):
    // [(1 + ¾γA² − Ω²)² + (2ζΩ)²] A² = F². The larger root Ω₊(A) in Ω.
    double hb_upper_frequency(const Duffing &d, const double A)
    {
      const double p = 1. + 0.75 * d.gamma * A * A, z2 = 2. * d.zeta * d.zeta;
      const double disc = (p - z2) * (p - z2) - p * p + d.force * d.force / (A * A);
      return disc < 0 ? std::nan("") : std::sqrt(p - z2 + std::sqrt(disc));
    }

    // A ball bouncing on a table that moves as s(t) = A sin Ωt, impacts with
    // restitution e (v⁺ − ṡ = −e (v⁻ − ṡ)), free flight under g between:
    // the stroboscopic map of (x, v) at t = 0 over one period, impacts found
    // exactly (a sign change of x − s on a fine grid, then bisection to
    // round-off). Observables: the last impact's time in the period and the
    // ball's velocity after it.
    struct BouncingBall
    {
      double g = 9.81, A = 0.003, omega = 2. * M_PI * 10., e = 0.5;

      double table(const double t) const { return A * std::sin(omega * t); }
      double table_velocity(const double t) const { return A * omega * std::cos(omega * t); }

      PeriodMapValue operator()(const Eigen::VectorXd &y, double) const
      {
        const double T = 2. * M_PI / omega;
        double t0 = 0, x0 = y[0], v0 = y[1], t_impact = -1, v_after = 0;
        auto gap = [&](const double t) { return x0 + v0 * (t - t0) - 0.5 * g * (t - t0) * (t - t0) - table(t); };
        const unsigned int n = 4000;
        for (unsigned int i = 1; i <= n; ++i)
          {
            double a = T * (i - 1) / n, b = T * i / n;
            if (b <= t0 + 1e-12 || !(gap(std::max(a, t0 + 1e-12)) > 0. && gap(b) <= 0.))
              continue;
            a = std::max(a, t0 + 1e-12);
            for (int k = 0; k < 200 && b - a > 1e-15; ++k)
              (gap(0.5 * (a + b)) > 0. ? a : b) = 0.5 * (a + b);
            const double t = b, v_before = v0 - g * (t - t0), w = table_velocity(t);
            x0 = table(t);
            v0 = w - e * (v_before - w);
            t0 = t_impact = t;
            v_after = v0;
          }
        PeriodMapValue out;
        out.end         = Eigen::Vector2d(x0 + v0 * (T - t0) - 0.5 * g * (T - t0) * (T - t0), v0 - g * (T - t0));
        out.observables = Eigen::Vector2d(t_impact, v_after);
        return out;
      }
    };

    ShootingSettings duffing_settings()
    {
      ShootingSettings s;
      s.scale     = Eigen::Vector2d(1., 1.);
      s.tolerance = 1e-10;
      return s;
    }
  } // namespace

  TEST(PeriodicOrbits, LinearOscillatorMultipliersAreTheClosedForm)
  {
    // γ = 0: the multipliers are exp((−ζ ± i√(1 − ζ²)) T), |μ| = exp(−ζT).
    Duffing d;
    d.gamma            = 0.;
    const double omega = 0.8, T = 2. * M_PI / omega;
    const ShootingOutcome out = shoot(d, Eigen::Vector2d(0., 0.), omega, duffing_settings());
    ASSERT_TRUE(out.converged) << out.reason;
    EXPECT_LE(out.point.iterations, 3u); // a linear map: one Newton step (and one to confirm)
    const std::complex<double> expected = std::exp(std::complex<double>(-d.zeta, std::sqrt(1. - d.zeta * d.zeta)) * T);
    ASSERT_EQ(out.point.multipliers.size(), 2);
    for (const auto &mu : out.point.multipliers)
      {
        EXPECT_NEAR(std::abs(mu), std::abs(expected), 1e-6);
        EXPECT_NEAR(std::abs(std::arg(mu)), std::abs(std::arg(expected)), 1e-5);
      }
    // The amplitude against the linear response F / √((1 − Ω²)² + (2ζΩ)²).
    EXPECT_NEAR(out.point.observables[0],
                d.force / std::hypot(1. - omega * omega, 2. * d.zeta * omega), 1e-7);
    EXPECT_LT(out.point.jacobian_change, 1e-4); // a linear map: both difference steps agree
  }

  TEST(PeriodicOrbits, LyapunovExponentOfAStableOrbitIsItsLargestMultiplier)
  {
    // On the stable lower branch of the Duffing oscillator the separation
    // shrinks by |μ₁| per period: the exponent is ln |μ₁| (a complex pair
    // rotates the separation, so the average needs many periods).
    const Duffing d;
    const ShootingOutcome out = shoot(d, Eigen::Vector2d(0., 0.), 0.8, duffing_settings());
    ASSERT_TRUE(out.converged) << out.reason;
    const double exponent =
      largest_lyapunov_exponent(d, out.point.y, 0.8, Eigen::Vector2d(1., 1.), 400, 1e-7);
    EXPECT_NEAR(exponent, std::log(out.point.largest_multiplier()), 0.01 * std::abs(std::log(out.point.largest_multiplier())));
    EXPECT_LT(exponent, 0.);
  }

  TEST(PeriodicOrbits, BouncingBallOrbitAndStabilityAreTheClosedForm)
  {
    // The period-1 orbit (one impact per period T): the ball leaves with
    // u = gT/2 and lands after T, so the table's velocity at the impact is
    // w = gT(1 − e) / (2(1 + e)) = AΩ cos Ωt₀, at the root with the table
    // decelerating (s̈ = −AΩ² sin Ωt₀ < 0). Linearising the impact-to-impact
    // map there: det J = e², tr J = 1 + e² + (1 + e)² s̈/g; the stroboscopic
    // map has the same multipliers. With these numbers a stable complex
    // pair of modulus e.
    const BouncingBall ball;
    const double T = 2. * M_PI / ball.omega, u = 0.5 * ball.g * T;
    const double w = ball.g * T * (1. - ball.e) / (2. * (1. + ball.e));
    const double t0 = std::acos(w / (ball.A * ball.omega)) / ball.omega;
    const double acceleration = -ball.A * ball.omega * ball.omega * std::sin(ball.omega * t0);
    const double trace = 1. + ball.e * ball.e + (1. + ball.e) * (1. + ball.e) * acceleration / ball.g;
    const std::complex<double> root = std::sqrt(std::complex<double>(trace * trace - 4. * ball.e * ball.e));
    const std::complex<double> mu1 = 0.5 * (trace + root), mu2 = 0.5 * (trace - root);

    // The orbit's state at t = 0 (T − t₀ after the impact), 1 % off.
    const double tau = T - t0;
    const Eigen::Vector2d on_orbit(ball.table(t0) + u * tau - 0.5 * ball.g * tau * tau, u - ball.g * tau);
    ShootingSettings s;
    s.scale     = Eigen::Vector2d(ball.A, u);
    s.tolerance = 1e-11;
    const ShootingOutcome out = shoot(ball, 1.01 * on_orbit, 0., s);
    ASSERT_TRUE(out.converged) << out.reason;
    EXPECT_NEAR(out.point.y[0], on_orbit[0], 1e-9 * ball.A);
    EXPECT_NEAR(out.point.y[1], on_orbit[1], 1e-9 * u);
    EXPECT_NEAR(out.point.observables[0], t0, 1e-10 * T);
    EXPECT_NEAR(out.point.observables[1], u, 1e-9 * u);
    // The multipliers by differences of whole periods through the impact.
    ASSERT_EQ(out.point.multipliers.size(), 2);
    const bool order = std::abs(out.point.multipliers[0] - mu1) < std::abs(out.point.multipliers[0] - mu2);
    EXPECT_LT(std::abs(out.point.multipliers[0] - (order ? mu1 : mu2)), 1e-5);
    EXPECT_LT(std::abs(out.point.multipliers[1] - (order ? mu2 : mu1)), 1e-5);
    std::cout << "bouncing ball: multipliers " << out.point.multipliers.transpose() << ", closed form " << mu1 << " "
              << mu2 << ", " << out.point.iterations << " corrections" << std::endl;
    EXPECT_NEAR(std::abs(out.point.multipliers[0]), ball.e, 1e-5);
    EXPECT_TRUE(out.point.stable());
  }

  TEST(PeriodicOrbits, ShootingReportsWhyItFails)
  {
    // A map with no fixed point (a translation): Newton's matrix M̃ − I is
    // zero, the iteration cannot go on, and the reason says so.
    const PeriodMap shift = [](const Eigen::VectorXd &y, double) {
      PeriodMapValue v;
      v.end         = y + Eigen::VectorXd::Ones(y.size());
      v.observables = Eigen::VectorXd::Zero(0);
      return v;
    };
    ShootingSettings s = duffing_settings();
    s.max_iterations   = 5;
    const ShootingOutcome out = shoot(shift, Eigen::Vector2d(0., 0.), 1., s);
    EXPECT_FALSE(out.converged);
    EXPECT_FALSE(out.reason.empty());
    // A map that throws: the reason carries its message.
    const PeriodMap failing = [](const Eigen::VectorXd &, double) -> PeriodMapValue {
      throw PeriodMapFailure("contact solver failed at t = 0.1 s");
    };
    const ShootingOutcome failed = shoot(failing, Eigen::Vector2d(0., 0.), 1., s);
    EXPECT_FALSE(failed.converged);
    EXPECT_NE(failed.reason.find("contact solver failed at t = 0.1 s"), std::string::npos) << failed.reason;
  }

  TEST(PeriodicOrbits, DuffingContinuedThroughBothTurningPointsMatchesHarmonicBalance)
  {
    const Duffing d;
    // Start on the lower branch well below resonance.
    const double omega0 = 0.7;
    const ShootingOutcome start = shoot(d, Eigen::Vector2d(0., 0.), omega0, duffing_settings());
    ASSERT_TRUE(start.converged) << start.reason;
    ContinuationSettings c;
    c.shooting     = duffing_settings();
    c.lambda_scale = 0.05;
    c.lambda_min   = 0.6;
    c.lambda_max   = 1.4;
    c.initial_step = 0.05;
    c.max_step     = 0.5;
    c.max_points   = 2000;
    const Branch branch = continue_branch(d, start.point, c);
    EXPECT_EQ(branch.end_reason, "left the parameter range");

    // Two turning points, the upper (jump-down) at the larger Ω, and the
    // points between them unstable (one real multiplier > 1).
    std::vector<BranchEventRecord> folds;
    for (const auto &e : branch.events)
      if (e.kind == BranchEvent::turning_point)
        folds.push_back(e);
    ASSERT_EQ(folds.size(), 2u);
    const double omega_down = folds[0].lambda, omega_up = folds[1].lambda;
    EXPECT_GT(omega_down, omega_up);

    // Harmonic balance's turning points: the extrema of Ω₊(A), found on a
    // fine grid in A and refined by a parabola through the three samples.
    double hb_max = 0, hb_min = 10;
    const double dA = 1e-4;
    for (double A = 0.3; A < 6.; A += dA)
      {
        const double a = hb_upper_frequency(d, A - dA), b = hb_upper_frequency(d, A), e = hb_upper_frequency(d, A + dA);
        if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(e)))
          continue;
        const double extremum = b - (e - a) * (e - a) / (8. * (e - 2 * b + a));
        if (b > a && b > e)
          hb_max = std::max(hb_max, extremum);
        if (b < a && b < e)
          hb_min = std::min(hb_min, extremum);
      }
    std::cout << "turning points: shooting " << omega_down << ", " << omega_up << "; harmonic balance " << hb_max
              << ", " << hb_min << " (" << branch.points.size() << " points)" << std::endl;
    // One harmonic misses the third's feedback, O(γA²/32) of the shift.
    EXPECT_NEAR(omega_down, hb_max, 2e-3 * hb_max);
    EXPECT_NEAR(omega_up, hb_min, 2e-3 * hb_min);

    // The harmonic-balance curve, sampled finely in A on both roots
    // Ω±(A)² = p − 2ζ² ± √((p − 2ζ²)² − p² + F²/A²), p = 1 + ¾γA².
    std::vector<std::pair<double, double>> hb_curve;
    for (double A = 0.01; A < 6.; A += 2e-4)
      {
        const double q = 1. + 0.75 * d.gamma * A * A, z2 = 2. * d.zeta * d.zeta;
        const double disc = (q - z2) * (q - z2) - q * q + d.force * d.force / (A * A);
        if (disc < 0.)
          continue;
        for (const double sign : {-1., 1.})
          if (q - z2 + sign * std::sqrt(disc) > 0.)
            hb_curve.emplace_back(std::sqrt(q - z2 + sign * std::sqrt(disc)), A);
      }
    for (std::size_t i = 0; i < branch.points.size(); ++i)
      {
        const OrbitPoint &p = branch.points[i];
        const bool between  = i > folds[0].after_point && i <= folds[1].after_point;
        EXPECT_EQ(p.stable(), !between) << "at Omega = " << p.lambda << ", point " << i;
        if (between)
          {
            EXPECT_GT(p.multipliers[0].real(), 1.);
            EXPECT_NEAR(p.multipliers[0].imag(), 0., 1e-12);
          }
        // The verdict against time integration started on the orbit: a small
        // separation grows (or shrinks) by |μ₁| per period, measured over 40
        // periods after 20 (a complex pair rotates the separation, so its
        // norm's mean growth approaches |μ₁| as 1/periods). At a turning
        // point |μ₁| → 1 and no integration of finite length decides.
        if (i % 10 == 0 && std::abs(p.largest_multiplier() - 1.) > 0.01)
          {
            const double growth =
              std::exp(largest_lyapunov_exponent(d, p.y, p.lambda, Eigen::Vector2d(1., 1.), 40, 1e-7, 20));
            EXPECT_EQ(growth < 1., p.stable()) << "at Omega = " << p.lambda << ": growth " << growth;
            EXPECT_NEAR(growth, p.largest_multiplier(), 0.2 * std::abs(p.largest_multiplier() - 1.) + 1e-3)
              << "at Omega = " << p.lambda;
          }
        // The point (Ω, A₁) on the harmonic-balance curve: its relative
        // distance to the nearest sample of the curve (both roots in Ω),
        // within the same 0.2 % as the turning points.
        double nearest = 1e300;
        for (const auto &[W, A] : hb_curve)
          nearest = std::min(nearest, std::hypot((p.lambda - W) / W, (p.observables[0] - A) / A));
        EXPECT_LT(nearest, 2e-3) << "at Omega = " << p.lambda << ", A = " << p.observables[0];
      }
  }
} // namespace beamslider
