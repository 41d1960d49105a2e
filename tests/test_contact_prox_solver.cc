// The two contact-solver sweep methods (contact/prox_solver.h) on
// constructed Delassus problems: one contact with its analytic sticking and
// sliding solutions, and random problems of the system's kind (2 and 4
// contacts, μ = 0.2) where both methods must reach the same relative
// velocities and satisfy Signorini–Coulomb. Then the mode guess that runs
// before the sweeps: on slowly drifting problems warm-started like Moreau
// steps it must solve most of them exactly and agree with the sweeps.
#include "contact/prox_solver.h"

#include <gtest/gtest.h>

#include <random>

using namespace beamslider;

namespace
{
  ProxSolver solver(const ProxSolverSettings::Method method)
  {
    ProxSolverSettings s;
    s.method      = method;
    s.tolerance   = 1e-12;
    s.guess_modes = false; // the sweeps themselves
    return ProxSolver(s);
  }

  constexpr ProxSolverSettings::Method both[] = {ProxSolverSettings::Method::projected,
                                                 ProxSolverSettings::Method::exact_local};
} // namespace

// One contact, G = [[2, 0.5], [0.5, 1]], μ = 0.2. Approaching (c_N = −1) with
// a small tangential velocity it sticks: ξ = 0, P = −G⁻¹c. With a large one
// it slides: P_T = −μ P_N sign, ξ_N = 0 → P_N = −c_N/(G_NN + s μ G_NT).
TEST(ProxSolver, OneContactSticksOrSlidesAsTheClosedFormSays)
{
  Eigen::MatrixXd G(2, 2);
  G << 2., 0.5, 0.5, 1.;
  const Eigen::VectorXd mu = Eigen::VectorXd::Constant(1, 0.2);
  for (const auto method : both)
    {
      Eigen::VectorXd c(2), P = Eigen::VectorXd::Zero(2);
      c << -1., -0.2;
      ASSERT_TRUE(solver(method).solve(G, c, mu, P).converged);
      const Eigen::VectorXd stick = -G.ldlt().solve(c);
      EXPECT_NEAR((P - stick).norm(), 0., 1e-9) << "sticking";
      EXPECT_LE(std::abs(stick[1]), 0.2 * stick[0]);

      c << -1., 2.;
      P.setZero();
      ASSERT_TRUE(solver(method).solve(G, c, mu, P).converged);
      const double s = -1.; // slides toward +T, friction impulse toward −T
      const double P_N = 1. / (2. + s * 0.2 * 0.5);
      EXPECT_NEAR(P[0], P_N, 1e-9) << "sliding";
      EXPECT_NEAR(P[1], s * 0.2 * P_N, 1e-9);
    }
}

// The same sliding contact warm-started in its sliding mode: the mode guess
// has one unknown, P_N, and one equation, ξ_N = 0 with P_T = −μ P_N, so
// P_N = −c_N/(G_NN − μ G_NT) exactly, found without a sweep.
TEST(ProxSolver, ModeGuessSolvesASlidingContactsSingleEquationExactly)
{
  Eigen::MatrixXd G(2, 2);
  G << 2., 0.5, 0.5, 1.;
  const Eigen::VectorXd mu = Eigen::VectorXd::Constant(1, 0.2);
  for (const double c_N : {-1., -3e-7, -4e5})
    {
      Eigen::VectorXd c(2), P(2);
      c << c_N, 2.;
      P << 0.5, -0.1; // on the cone's edge, toward −T: the sliding mode
      const ProxSolverResult r = ProxSolver().solve(G, c, mu, P);
      ASSERT_TRUE(r.converged);
      EXPECT_TRUE(r.by_modes) << "c_N = " << c_N;
      EXPECT_EQ(r.iterations, 0u);
      EXPECT_DOUBLE_EQ(P[0], -c_N / (2. - 0.2 * 0.5)) << "c_N = " << c_N;
      EXPECT_DOUBLE_EQ(P[1], -0.2 * P[0]);
    }
}

TEST(ProxSolver, BothMethodsReachTheSameSolutionOnRandomProblems)
{
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  for (const int contacts : {2, 4})
    for (int trial = 0; trial < 50; ++trial)
      {
        const int n = 2 * contacts;
        // G = J Jᵀ + small diagonal, J of a few beam modes and the slider's
        // three rigid-body directions: SPD, nearly singular like the real one.
        Eigen::MatrixXd J(n, 8);
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < 8; ++k)
            J(i, k) = normal(random);
        const Eigen::MatrixXd G = J * J.transpose() + 1e-3 * Eigen::MatrixXd::Identity(n, n);
        Eigen::VectorXd c(n);
        for (int i = 0; i < n; ++i)
          c[i] = normal(random);
        const Eigen::VectorXd mu = Eigen::VectorXd::Constant(contacts, 0.2);
        Eigen::VectorXd xi[2];
        for (int m = 0; m < 2; ++m)
          {
            Eigen::VectorXd P = Eigen::VectorXd::Zero(n);
            ProxSolverSettings s;
            s.method         = both[m];
            s.guess_modes    = false;
            s.tolerance      = 1e-12;
            s.max_iterations = 200000;
            ASSERT_TRUE(ProxSolver(s).solve(G, c, mu, P).converged) << contacts << " contacts, trial " << trial;
            xi[m] = G * P + c;
            for (int i = 0; i < contacts; ++i)
              {
                const double scale = std::max(1., c.cwiseAbs().maxCoeff());
                EXPECT_GE(P[2 * i], 0.);
                EXPECT_GE(xi[m][2 * i], -1e-8 * scale);
                EXPECT_NEAR(P[2 * i] * xi[m][2 * i], 0., 1e-8 * scale * scale);
                EXPECT_LE(std::abs(P[2 * i + 1]), 0.2 * P[2 * i] + 1e-12);
              }
          }
        EXPECT_LT((xi[0] - xi[1]).norm(), 1e-6 * std::max(1., c.norm())) << contacts << " contacts, trial " << trial;
      }
}

// Random problems that drift slowly from one "step" to the next, each warm-
// started with the previous solution as the Moreau stepper does. The mode
// guess must (a) satisfy Signorini–Coulomb to round-off whenever it accepts,
// (b) give the same relative velocities as the sweeps (to the sweeps' own
// tolerance), and (c) accept most steps: the point of guessing. Failed
// guesses fall back to the sweeps and still converge.
TEST(ProxSolver, ModeGuessIsExactWhenItAcceptsAndAcceptsMostDriftingProblems)
{
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  for (const int contacts : {2, 4})
    {
      const int n = 2 * contacts;
      Eigen::MatrixXd J(n, 8), dJ(n, 8);
      Eigen::VectorXd c(n), dc(n);
      for (int i = 0; i < n; ++i)
        {
          c[i] = normal(random);
          dc[i] = normal(random);
          for (int k = 0; k < 8; ++k)
            J(i, k) = normal(random), dJ(i, k) = normal(random);
        }
      const Eigen::VectorXd mu = Eigen::VectorXd::Constant(contacts, 0.2);
      ProxSolverSettings guess, sweeps;
      guess.tolerance = sweeps.tolerance = 1e-12;
      sweeps.guess_modes                 = false;
      sweeps.max_iterations              = 200000;
      Eigen::VectorXd P_guess = Eigen::VectorXd::Zero(n), P_sweeps = Eigen::VectorXd::Zero(n);
      unsigned int accepted = 0;
      const unsigned int steps = 400;
      for (unsigned int step = 0; step < steps; ++step)
        {
          // 0.5 % drift per step, a full turn of the tangential velocity sign
          // over the run: modes change now and then, as between Moreau steps.
          const double phase = 2. * M_PI * step / steps;
          const Eigen::MatrixXd Js = J + 0.3 * std::sin(phase) * dJ;
          const Eigen::MatrixXd G  = Js * Js.transpose() + 1e-3 * Eigen::MatrixXd::Identity(n, n);
          const Eigen::VectorXd cs = c + std::sin(phase) * dc;
          const ProxSolverResult r = ProxSolver(guess).solve(G, cs, mu, P_guess);
          ASSERT_TRUE(r.converged) << contacts << " contacts, step " << step;
          ASSERT_TRUE(ProxSolver(sweeps).solve(G, cs, mu, P_sweeps).converged);
          const Eigen::VectorXd xi = G * P_guess + cs, xi_sweeps = G * P_sweeps + cs;
          const double scale       = std::max(1., cs.cwiseAbs().maxCoeff());
          EXPECT_LT((xi - xi_sweeps).cwiseAbs().maxCoeff(), 1e-7 * scale) << contacts << " contacts, step " << step;
          if (!r.by_modes)
            continue;
          ++accepted;
          EXPECT_EQ(r.iterations, 0u);
          for (int i = 0; i < contacts; ++i)
            {
              const double tol = 1e-11 * scale;
              EXPECT_GE(P_guess[2 * i], 0.);
              EXPECT_GE(xi[2 * i], -tol);
              EXPECT_NEAR(P_guess[2 * i] * xi[2 * i], 0., tol * scale);
              const double bound = 0.2 * P_guess[2 * i];
              EXPECT_LE(std::abs(P_guess[2 * i + 1]), bound);
              // Sticking: no tangential slip; sliding: slip against the impulse.
              if (std::abs(P_guess[2 * i + 1]) < bound * (1. - 1e-9))
                EXPECT_NEAR(xi[2 * i + 1], 0., tol);
              else if (bound > 0.)
                EXPECT_LE(P_guess[2 * i + 1] * xi[2 * i + 1], tol * scale);
            }
        }
      std::cout << contacts << " contacts: the mode guess solved " << accepted << " of " << steps
                << " drifting problems\n";
      EXPECT_GT(accepted, 0.8 * steps) << contacts << " contacts";
    }
}
