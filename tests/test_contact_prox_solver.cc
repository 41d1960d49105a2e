// The two contact-solver methods (contact/prox_solver.h) on constructed
// Delassus problems: one contact with its analytic sticking and sliding
// solutions, and random problems of the system's kind (2 and 4 contacts, μ =
// 0.2) where both methods must reach the same relative velocities and satisfy
// Signorini–Coulomb.
#include "contact/prox_solver.h"

#include <gtest/gtest.h>

#include <random>

using namespace beamslider;

namespace
{
  ProxSolver solver(const ProxSolverSettings::Method method)
  {
    ProxSolverSettings s;
    s.method    = method;
    s.tolerance = 1e-12;
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
