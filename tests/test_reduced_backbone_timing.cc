// Cost of the harmonic-balance backbone (reduced/harmonic_balance.h), H = 10,
// ŵ_{L/2}/h from 0.01 to 4, on the mueller2023 beam with an ideal clamp:
// the ROM with N = 5 and N = 7 modes (M = I, K = diag ω²), and a 70-DOF dense
// system standing in for a condensed FE model (the 70-mode ROM written in
// non-modal coordinates q = P x, so M = PᵀP and K = PᵀΩ²P are full). Prints
// the timings; checks only that every returned point is converged and that
// each run ends with a reason. The numbers depend on the machine and on the
// build flags (the library must be compiled with optimisation).
#include "reduced/harmonic_balance.h"
#include "reduced/rom_operator.h"
#include "tests/test_reduced_clamped_beam.h"

#include <gtest/gtest.h>

#include <iostream>

using namespace beamslider;
using beamslider_test::ClampedBeam;

namespace
{
  void report(const std::string &what, const Backbone &bb, const double h)
  {
    double a_max = 0;
    for (const auto &p : bb.points)
      {
        EXPECT_LT(p.relative_residual, 1e-8);
        a_max = std::max(a_max, p.amplitude);
      }
    EXPECT_FALSE(bb.message.empty());
    const unsigned int n_unknowns = bb.points.front().harmonics.size() + 1;
    std::cout << "  " << what << ": " << n_unknowns << " unknowns, " << bb.points.size() << " points, "
              << bb.n_newton_iterations << " Newton iterations, " << bb.seconds << " s ("
              << 1e3 * bb.seconds / std::max(1u, bb.n_newton_iterations) << " ms/iteration), reached ŵ/h = "
              << a_max / h << (bb.completed ? " (completed)" : "") << "; " << bb.message << '\n';
  }
} // namespace

TEST(BackboneTiming, RomWithFiveAndSevenModes)
{
  const ClampedBeam beam;
  for (const unsigned int N : {5u, 7u})
    for (const bool odd : {false, true})
      {
        const auto modes = beam.modes(N);
        const ReducedOrderModel rom(modes.basis, 0.);
        BackboneSettings settings;
        Eigen::VectorXd dphi;
        modes.basis.evaluate(beam.L / 2, settings.output, dphi);
        settings.hb.n_harmonics        = 10;
        settings.hb.odd_harmonics_only = odd;
        settings.start_amplitude       = 0.01 * beam.h;
        settings.end_amplitude         = 4 * beam.h;
        const Backbone bb = compute_backbone(make_conservative_system(rom), settings);
        report("ROM N = " + std::to_string(N) + ", H = 10" + (odd ? " odd" : " all"), bb, beam.h);
      }
}

TEST(BackboneTiming, DenseSeventyDofSystem)
{
  const ClampedBeam beam;
  const unsigned int n = 70;
  const auto modes     = beam.modes(n, 2000);
  const ReducedOrderModel rom(modes.basis, 0.);
  // A fixed well-conditioned dense P = I + 0.1 S (S with entries in [−1, 1]/√n).
  Eigen::MatrixXd S(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      S(i, j) = std::sin(1.7 * i + 0.3 * j * j + 0.1) / std::sqrt(double(n));
  const Eigen::MatrixXd P  = Eigen::MatrixXd::Identity(n, n) + 0.1 * S;
  const Eigen::MatrixXd W2 = modes.basis.omega.array().square().matrix().asDiagonal();
  ConservativeSystem dense;
  dense.mass      = P.transpose() * P;
  dense.stiffness = P.transpose() * W2 * P;
  dense.force     = [&](const Eigen::VectorXd &x) -> Eigen::VectorXd { return P.transpose() * rom.nonlinear_force(P * x); };
  dense.tangent   = [&](const Eigen::VectorXd &x) -> Eigen::MatrixXd {
    return P.transpose() * rom.nonlinear_tangent(P * x) * P;
  };
  Eigen::VectorXd phi, dphi;
  modes.basis.evaluate(beam.L / 2, phi, dphi);
  for (const bool odd : {true, false})
    {
      BackboneSettings settings;
      settings.output                = P.transpose() * phi;
      settings.hb.n_harmonics        = 10;
      settings.hb.odd_harmonics_only = odd;
      settings.start_amplitude       = 0.01 * beam.h;
      settings.end_amplitude         = 4 * beam.h;
      const Backbone bb = compute_backbone(dense, settings);
      report(std::string("dense n = 70, H = 10") + (odd ? " odd" : " all"), bb, beam.h);
    }
}
