// The FE beam (fem/fe_beam, fem/fe_modes) against independent facts:
// analytic frequencies of clamped–clamped and spring-supported beams, their
// O(h⁴) convergence, symmetry of M and K, the tangent against finite
// differences of the internal force, seed Eq. 5 for a bonded slider, and the
// modal damping matrix.
#include "fem/fe_beam.h"
#include "fem/fe_modal_damping.h"
#include "fem/fe_modes.h"
#include "scene/scene.h"
#include "verification/studies/analytic_beam.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>

using namespace beamslider;
using dealii::SparseMatrix;
using dealii::Vector;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  double relative_error(const double computed, const double exact)
  {
    return std::abs(computed - exact) / std::abs(exact);
  }

  std::vector<double> analytic_frequencies(const Scene &s, const unsigned int n)
  {
    const double k_r = s.supports.ideal_clamp ? std::numeric_limits<double>::infinity() : s.supports.rotational_stiffness;
    std::vector<double> omega;
    for (const double bL : analytic::spring_supported_beta_L(n, s.beam.bending_stiffness(), s.beam.length, k_r))
      omega.push_back(analytic::frequency_from_beta_L(bL, s.beam.bending_stiffness(), s.beam.mass_per_length(), s.beam.length));
    return omega;
  }

  // A random displacement of the size of the beam thickness on the free DoFs.
  Vector<double> random_state(const FEBeam &beam, const unsigned int seed)
  {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> d(-1, 1);
    Vector<double> q(beam.n_dofs());
    const double h = beam.beam_data().thickness, L = beam.length();
    for (unsigned int i = 0; i < q.size(); ++i)
      q[i] = d(gen) * (beam.axial_dofs()[i] ? 1e-2 * h : beam.slope_dofs()[i] ? 10 * h / L : h);
    beam.constraints().set_zero(q);
    return q;
  }
} // namespace

TEST(ClampedClampedFrequencies, TextbookRootsOfTheCharacteristicEquation)
{
  // The classical values (e.g. Blevins): an independent check of the solver
  // the other tests rely on.
  const std::vector<double> published{4.730041, 7.853205, 10.995608, 14.137165, 17.278760, 20.420352, 23.561945};
  const auto roots = analytic::clamped_clamped_beta_L(7);
  for (unsigned int k = 0; k < 7; ++k)
    EXPECT_NEAR(roots[k], published[k], 1e-6);
}

TEST(ClampedClampedFrequencies, FirstSevenModesWithin1e6OnARefinedMesh)
{
  const Scene s = read_scene(scene_dir + "mueller2023-ideal.prm");
  const FEBeam beam(s, 256);
  const FEModes modes  = compute_bending_modes(beam, 7);
  const auto reference = analytic_frequencies(s, 7);
  for (unsigned int k = 0; k < 7; ++k)
    EXPECT_LT(relative_error(modes.omega[k], reference[k]), 1e-6) << "mode " << k + 1;
}

TEST(ClampedClampedFrequencies, ConvergeAtOrderFour)
{
  // Hermite cubics: energy-norm error O(h²), so eigenvalue error O(h⁴).
  const Scene s        = read_scene(scene_dir + "mueller2023-ideal.prm");
  const auto reference = analytic_frequencies(s, 5);
  std::vector<std::vector<double>> errors;
  for (const unsigned int n : {8u, 16u, 32u})
    {
      const FEModes modes = compute_bending_modes(FEBeam(s, n), 5);
      errors.emplace_back();
      for (unsigned int k = 0; k < 5; ++k)
        errors.back().push_back(relative_error(modes.omega[k], reference[k]));
    }
  for (unsigned int k = 0; k < 5; ++k)
    {
      const double order = std::log2(errors[1][k] / errors[2][k]);
      EXPECT_NEAR(order, 4.0, 0.15) << "mode " << k + 1 << ": errors " << errors[1][k] << ", " << errors[2][k];
    }
}

TEST(SpringSupportedFrequencies, MatchTheCharacteristicEquation)
{
  const Scene s = read_scene(scene_dir + "mueller2023.prm");
  ASSERT_FALSE(s.supports.ideal_clamp);
  const FEModes modes  = compute_bending_modes(FEBeam(s, 256), 7);
  const auto reference = analytic_frequencies(s, 7);
  for (unsigned int k = 0; k < 7; ++k)
    EXPECT_LT(relative_error(modes.omega[k], reference[k]), 1e-6) << "mode " << k + 1;
  // The springs soften the beam: every frequency lies below the clamped one
  // and above the pinned one (k_r = 0: βL = kπ).
  const auto clamped = analytic::clamped_clamped_beta_L(7);
  for (unsigned int k = 0; k < 7; ++k)
    {
      const double EI = s.beam.bending_stiffness(), rhoA = s.beam.mass_per_length(), L = s.beam.length;
      EXPECT_LT(modes.omega[k], analytic::frequency_from_beta_L(clamped[k], EI, rhoA, L));
      EXPECT_GT(modes.omega[k], analytic::frequency_from_beta_L((k + 1) * M_PI, EI, rhoA, L));
    }
}

// The two eigensolver routes of compute_bending_modes (fem/fe_modes.h): the
// dense generalised solver on the free DoFs (every small mesh) and SLEPc's
// shift-invert Krylov–Schur (large meshes), each against an independent
// reference: the same free-DoF problem solved densely in 80-bit long double.
// Both work relative to the lowest eigenvalue (the dense route inverts the
// problem, SLEPc shifts and inverts): measured in ω_1, dense 1e-12 and
// SLEPc 6e-14, where a plain dense solve of K φ = λ M φ is off by about
// ε λ_max/λ_1, 5e-11 on this mesh. Bound: 1e-11, six orders below the
// discretisation error; the shapes must agree too.
TEST(BendingModes, DenseAndSlepcRoutesAgreeWithAnExtendedPrecisionReference)
{
  const Scene s = read_scene(scene_dir + "mueller2023.prm");
  const FEBeam beam(s, 32);
  const auto &constraints = beam.bending_constraints();
  SparseMatrix<double> M, K;
  beam.assemble_mass_matrix(M, constraints);
  beam.assemble_internal_force(Vector<double>(beam.n_dofs()), nullptr, &K, constraints);
  std::vector<unsigned int> free_dofs;
  for (unsigned int i = 0; i < beam.n_dofs(); ++i)
    if (!constraints.is_constrained(i))
      free_dofs.push_back(i);
  const int n = free_dofs.size();
  using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  LongMatrix K_free(n, n), M_free(n, n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      {
        K_free(a, b) = K.el(free_dofs[a], free_dofs[b]);
        M_free(a, b) = M.el(free_dofs[a], free_dofs[b]);
      }
  const Eigen::GeneralizedSelfAdjointEigenSolver<LongMatrix> reference(K_free, M_free);
  const double stiffness_spread = reference.eigenvalues()[n - 1] / reference.eigenvalues()[0];

  const FEModes dense  = compute_bending_modes(beam, 7, std::nullopt, EigenSolverMethod::dense);
  const FEModes slepc  = compute_bending_modes(beam, 7, std::nullopt, EigenSolverMethod::slepc);
  const FEModes chosen = compute_bending_modes(beam, 7);
  for (unsigned int k = 0; k < 7; ++k)
    {
      const double omega = std::sqrt(reference.eigenvalues()[k]);
      const double error_dense = std::abs(dense.omega[k] / omega - 1.), error_slepc = std::abs(slepc.omega[k] / omega - 1.);
      std::cout << "mode " << k + 1 << ": relative error in omega, dense " << error_dense << ", SLEPc " << error_slepc
                << "\n";
      EXPECT_LT(error_dense, 1e-11) << "mode " << k + 1;
      EXPECT_LT(error_slepc, 1e-11) << "mode " << k + 1;
      Vector<double> difference = dense.shapes[k];
      difference -= slepc.shapes[k];
      EXPECT_LT(difference.linfty_norm(), 1e-6 * slepc.shapes[k].linfty_norm()) << "mode " << k + 1;
      EXPECT_EQ(chosen.omega[k], dense.omega[k]) << "a 32-element mesh is solved densely";
    }
  std::cout << "lambda_max / lambda_1 = " << stiffness_spread << "\n";
}

TEST(FEBeamMatrices, MassAndTangentAreSymmetric)
{
  const Scene s = read_scene(scene_dir + "mueller2023.prm");
  const FEBeam beam(s, 12);
  SparseMatrix<double> M, K;
  beam.assemble_mass_matrix(M, beam.constraints());
  beam.assemble_internal_force(random_state(beam, 1), nullptr, &K, beam.constraints());
  for (const SparseMatrix<double> *A : {&M, &K})
    {
      double asymmetry = 0;
      for (unsigned int i = 0; i < A->m(); ++i)
        for (auto it = A->begin(i); it != A->end(i); ++it)
          asymmetry = std::max(asymmetry, std::abs(it->value() - A->el(it->column(), i)));
      EXPECT_LE(asymmetry, 1e-14 * A->linfty_norm());
    }
}

TEST(FEBeamMatrices, TangentMatchesFiniteDifferencesOfTheInternalForce)
{
  for (const std::string scene : {"mueller2023.prm", "mueller2023-ideal.prm"})
    {
      const Scene s = read_scene(scene_dir + scene);
      const FEBeam beam(s, 10);
      const Vector<double> q = random_state(beam, 2);
      SparseMatrix<double> K;
      Vector<double> f0;
      beam.assemble_internal_force(q, &f0, &K, beam.constraints());

      // Central differences along a random direction: O(ε²) accurate.
      const Vector<double> dq = random_state(beam, 3);
      const double eps        = 1e-4;
      Vector<double> q_plus(q), q_minus(q), f_plus, f_minus;
      q_plus.add(eps, dq);
      q_minus.add(-eps, dq);
      beam.assemble_internal_force(q_plus, &f_plus, nullptr, beam.constraints());
      beam.assemble_internal_force(q_minus, &f_minus, nullptr, beam.constraints());
      Vector<double> fd(f_plus);
      fd.add(-1., f_minus);
      fd /= 2 * eps;
      Vector<double> Kdq(beam.n_dofs());
      K.vmult(Kdq, dq);
      // Constrained rows carry K's diagonal filler, not a derivative.
      beam.constraints().set_zero(Kdq);
      Vector<double> diff(fd);
      diff.add(-1., Kdq);
      EXPECT_LT(diff.l2_norm(), 1e-7 * Kdq.l2_norm()) << scene;
      // The nonlinearity matters at this amplitude (not a vacuous check).
      SparseMatrix<double> K0;
      beam.assemble_internal_force(Vector<double>(beam.n_dofs()), nullptr, &K0, beam.constraints());
      Vector<double> K0dq(beam.n_dofs());
      K0.vmult(K0dq, dq);
      beam.constraints().set_zero(K0dq);
      K0dq.add(-1., Kdq);
      EXPECT_GT(K0dq.l2_norm(), 1e-3 * Kdq.l2_norm()) << scene;
    }
}

TEST(FEBeamMatrices, InternalForceIsTheGradientOfTheStrainEnergy)
{
  // Without the nonlinearity f is linear: f(q) = K q exactly.
  Scene s                                 = read_scene(scene_dir + "mueller2023.prm");
  s.discretisation.geometric_nonlinearity = false;
  const FEBeam beam(s, 10);
  const Vector<double> q = random_state(beam, 4);
  SparseMatrix<double> K;
  Vector<double> f, Kq(beam.n_dofs());
  beam.assemble_internal_force(q, &f, &K, beam.constraints());
  K.vmult(Kq, q);
  Kq.add(-1., f);
  EXPECT_LT(Kq.l2_norm(), 1e-12 * f.l2_norm());
}

TEST(BondedSlider, FirstFrequencyAgreesWithSeedEquation5AsARayleighQuotient)
{
  // Eq. 5 is the Rayleigh quotient with the bare beam's first mode as trial
  // function. Rayleigh–Ritz on the first n bare modes (which are FE vectors,
  // so the subspaces are nested in the FE space) gives upper bounds that
  // decrease monotonically with n toward the FE value: FE ≤ RR(7) ≤ RR(3) ≤
  // Eq. 5 = RR(1). How far Eq. 5 lies above is the accuracy of a one-mode
  // Rayleigh quotient; for the mueller2023 slider (3 times the beam mass) it
  // reaches about 12 % near x_C/L = 0.2 (see the report).
  const Scene s = read_scene(scene_dir + "mueller2023.prm");
  const FEBeam beam(s, 64);
  const unsigned int n_bare = 7;
  const FEModes bare = compute_bending_modes(beam, n_bare);
  for (const double x_over_L : {0.1, 0.2, 0.3, 0.4, 0.5})
    {
      const double x = x_over_L * s.beam.length;
      Eigen::VectorXd phi(n_bare), dphi(n_bare), omega2(n_bare);
      for (unsigned int k = 0; k < n_bare; ++k)
        {
          phi[k]    = beam.deflection(bare.shapes[k], x);
          dphi[k]   = beam.slope(bare.shapes[k], x);
          omega2[k] = bare.omega[k] * bare.omega[k];
        }
      auto rayleigh_ritz = [&](const unsigned int n) {
        const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n) + s.slider.mass * phi.head(n) * phi.head(n).transpose() +
                                  s.slider.inertia * dphi.head(n) * dphi.head(n).transpose();
        const Eigen::MatrixXd K = omega2.head(n).asDiagonal();
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
        return std::sqrt(es.eigenvalues()[0]);
      };
      const double eq5 = bare.omega[0] / std::sqrt(1 + s.slider.mass * phi[0] * phi[0] + s.slider.inertia * dphi[0] * dphi[0]);
      const double fe  = compute_bending_modes(beam, 1, BondedBody{x, s.slider.mass, s.slider.inertia}).omega[0];
      const double tol = 1e-10 * eq5;
      EXPECT_NEAR(rayleigh_ritz(1), eq5, tol);
      EXPECT_LE(rayleigh_ritz(3), eq5 + tol) << "x_C/L = " << x_over_L;
      EXPECT_LE(rayleigh_ritz(7), rayleigh_ritz(3) + tol) << "x_C/L = " << x_over_L;
      EXPECT_LE(fe, rayleigh_ritz(7) + tol) << "x_C/L = " << x_over_L;
      // Seven modes recover at least 90 % of Eq. 5's error: the Ritz bounds
      // converge to the FE value, so the FE value is the limit Eq. 5
      // approximates.
      EXPECT_LT(relative_error(rayleigh_ritz(7), fe), 0.1 * relative_error(eq5, fe)) << "x_C/L = " << x_over_L;
      EXPECT_LT(relative_error(eq5, fe), 0.15) << "x_C/L = " << x_over_L;
    }
}

TEST(ModalDamping, GivesRatioDOnKeptModesAndNothingOnOthers)
{
  const Scene s = read_scene(scene_dir + "mueller2023.prm");
  const FEBeam beam(s, 24);
  const FEModes modes = compute_bending_modes(beam, 7);
  SparseMatrix<double> M;
  beam.assemble_mass_matrix(M, beam.constraints());
  const unsigned int kept = 5;
  const ModalDamping C(M, modes, kept, s.damping_ratio);
  Vector<double> Cphi(beam.n_dofs()), Mphi(beam.n_dofs());
  for (unsigned int m = 0; m < 7; ++m)
    {
      C.vmult(Cphi, modes.shapes[m]);
      for (unsigned int n = 0; n < 7; ++n)
        {
          const double modal = modes.shapes[n] * Cphi;
          const double expected = (m == n && m < kept) ? 2 * s.damping_ratio * modes.omega[m] : 0.;
          EXPECT_NEAR(modal, expected, 1e-9 * 2 * s.damping_ratio * modes.omega[kept - 1]) << m << "," << n;
        }
    }
}
