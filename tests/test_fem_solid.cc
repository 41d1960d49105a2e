// The St. Venant–Kirchhoff solid strip (fem/solid_model, fem/solid_modes):
// its tangent against finite differences of its internal force, and its
// modes against the von Kármán beam's and against the thin strip's torsion,
// and the animation of its reduced model on it.
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "fem/solid_coefficients.h"
#include "fem/solid_modal_basis.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "output/solid_rom_animation.h"
#include "fem/solid_statics.h"
#include "fem/fe_modal_basis.h"
#include "scene/scene.h"
#include "reduced/rom_operator.h"
#include "tests/solid_tangent_check.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <regex>

#include <unistd.h>

using namespace beamslider;
using dealii::PETScWrappers::MPI::SparseMatrix;
using dealii::PETScWrappers::MPI::Vector;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  Scene solid_scene(const std::string &continuum, const double nu, const unsigned int nx, const unsigned int ny,
                    const unsigned int nz, const unsigned int degree)
  {
    return read_scene(scene_dir + "mueller2023-ideal.prm",
                      {"Solid/Continuum=" + continuum, "Solid/Poisson's ratio=" + std::to_string(nu),
                       "Solid/Elements along length=" + std::to_string(nx),
                       "Solid/Elements across width=" + std::to_string(ny),
                       "Solid/Elements through thickness=" + std::to_string(nz),
                       "Solid/Degree=" + std::to_string(degree)});
  }

  // The clamped–clamped Timoshenko beam (shear coefficient κ, rotary
  // inertia ρI), independently of every FE code here:
  //   κGA (w'' − ψ') + ρA ω² w = 0,   EI ψ'' + κGA (w' − ψ) + ρI ω² ψ = 0,
  //   w = ψ = 0 at x = 0 and x = L.
  // With y = (w, w', ψ, ψ') the equations are y' = A(ω) y; the transfer
  // matrix T = exp(A L) maps the free start values (w'(0), ψ'(0)) to the end
  // values (w(L), ψ(L)), and ω is a frequency where that 2×2 block is
  // singular: found by bisection around the Euler–Bernoulli frequency.
  //
  // On rotational springs k_r at both ends (w = 0 there, the bending moment
  // EI ψ' = k_r ψ at x = 0 and = −k_r ψ at x = L) the free start values are
  // w'(0) and ψ(0) (with ψ'(0) = k_r ψ(0)/EI), the end conditions w(L) = 0
  // and ψ'(L) + k_r ψ(L)/EI = 0. k_r = ∞ is the clamp.
  struct TimoshenkoBeam
  {
    double E, G, kappa, rho, b, h, L;
    double k_r = std::numeric_limits<double>::infinity(); // [N m/rad]

    double determinant(const double omega) const
    {
      const double A = b * h, I = b * h * h * h / 12, kGA = kappa * G * A;
      Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
      M(0, 1)           = 1;
      M(1, 0)           = -rho * A * omega * omega / kGA;
      M(1, 3)           = 1;
      M(2, 3)           = 1;
      M(3, 1)           = -kGA / (E * I);
      M(3, 2)           = (kGA - rho * I * omega * omega) / (E * I);
      const Eigen::Matrix4d T = (M * L).exp();
      if (std::isinf(k_r))
        return T(0, 1) * T(2, 3) - T(0, 3) * T(2, 1);
      const double s = k_r / (E * I);
      const Eigen::Vector4d start1(0, 1, 0, 0), start2(0, 0, 1, s);
      const Eigen::Vector4d end_w(1, 0, 0, 0), end_moment(0, 0, s, 1);
      const Eigen::Vector4d y1 = T * start1, y2 = T * start2;
      return end_w.dot(y1) * end_moment.dot(y2) - end_w.dot(y2) * end_moment.dot(y1);
    }

    // The n-th frequency [rad/s], n = 1 …: shear and rotary inertia lower
    // the Euler–Bernoulli frequency λ_n² / L² sqrt(EI/ρA) by less than 1 %.
    // `upper`: an Euler–Bernoulli frequency of the same supports, if not
    // the clamp's.
    double omega(const unsigned int n, double upper = 0) const
    {
      const double roots[] = {4.730040745, 7.853204624, 10.995607838, 14.137165491, 17.278759657};
      const double euler_bernoulli =
        upper > 0 ? upper : roots[n - 1] * roots[n - 1] / (L * L) * std::sqrt(E * h * h / (12 * rho));
      double lo = 0.99 * euler_bernoulli, hi = euler_bernoulli * (1 + 1e-9);
      const double sign_lo = std::copysign(1., determinant(lo));
      EXPECT_NE(sign_lo, std::copysign(1., determinant(hi))) << "no root bracketed for mode " << n;
      for (int i = 0; i < 100; ++i)
        {
          const double mid = 0.5 * (lo + hi);
          (std::copysign(1., determinant(mid)) == sign_lo ? lo : hi) = mid;
        }
      return 0.5 * (lo + hi);
    }
  };

  // Bending frequencies [Hz] of the solid.
  template <int dim>
  std::vector<double> bending_frequencies(const Scene &scene, const unsigned int n)
  {
    const SolidModel<dim> model(scene, MPI_COMM_WORLD);
    const SolidModes modes = compute_solid_modes(model, n);
    std::vector<double> f;
    for (const unsigned int i : modes.bending)
      f.push_back(modes.all[i].omega / (2 * M_PI));
    return f;
  }
} // namespace

TEST(SolidModel, TangentIsTheDerivativeOfTheInternalForce)
{
  for (const std::string continuum : {"plane stress", "3d"})
    {
      const Scene scene = solid_scene(continuum, 0.3, 6, 2, 1, 2);
      if (continuum == "3d")
        EXPECT_LT(beamslider::testing::tangent_defect(SolidModel<3>(scene, MPI_COMM_WORLD), 7), 1e-10) << continuum;
      else
        EXPECT_LT(beamslider::testing::tangent_defect(SolidModel<2>(scene, MPI_COMM_WORLD), 7), 1e-10) << continuum;
    }
  // On the elastic supports the springs and the plates' constraints are part of it.
  Scene elastic = solid_scene("plane stress", 0.3, 6, 1, 1, 3);
  elastic.supports = read_scene(scene_dir + "mueller2023.prm").supports;
  ASSERT_TRUE(elastic.supports.elastic());
  EXPECT_LT(beamslider::testing::tangent_defect(SolidModel<2>(elastic, MPI_COMM_WORLD), 7), 1e-10) << "elastic supports";
}

// Without Poisson's ratio the plane-stress strip is what a shear-deformable
// beam idealises: its bending frequencies converge, in h at the rate of Q2
// (ω error O(h⁴)) and in p, to the clamped Timoshenko beam's (κ = 5/6 for the
// rectangle at ν = 0), which lie 0.03 % (mode 1) to 0.26 % (mode 5) below
// the Euler–Bernoulli beam's. The converged difference is below 0.2 % of that
// shear and rotary-inertia correction: what remains of the continuum beyond
// Timoshenko's kinematics (warping, the clamped faces) is of order (h/L)⁴.
TEST(SolidModes, PlaneStressStripWithoutPoissonConvergesToTheTimoshenkoBeam)
{
  const Scene scene = solid_scene("plane stress", 0, 1, 1, 1, 2);
  const BeamData &d = scene.beam;
  const TimoshenkoBeam timoshenko{d.youngs_modulus, d.youngs_modulus / 2, 5. / 6, d.density, d.width, d.thickness, d.length};
  const double roots[] = {4.730040745, 7.853204624, 10.995607838, 14.137165491, 17.278759657};
  std::vector<double> f_T, correction;
  for (unsigned int k = 1; k <= 5; ++k)
    {
      f_T.push_back(timoshenko.omega(k) / (2 * M_PI));
      const double f_EB = roots[k - 1] * roots[k - 1] / (2 * M_PI * d.length * d.length) *
                          std::sqrt(d.bending_stiffness() / d.mass_per_length());
      correction.push_back(f_T.back() / f_EB - 1);
    }

  // h-refinement of Q2, halving the element size in both directions: the
  // observed order from three meshes, log2 |f_h − f_h/2| / |f_h/2 − f_h/4|
  // (→ 4). Measured against the continuum's own limit, not against the
  // Timoshenko beam: the two differ by the O((h/L)⁴) remainder above, which
  // on the finest mesh is no longer small beside the discretisation error of
  // mode 1 and bent its rate against f_T to 3.48–3.5 (round-off decided on
  // which side). That the limit is the Timoshenko beam is the p = 3 check below.
  std::vector<std::vector<double>> frequencies;
  for (const unsigned int r : {1u, 2u, 4u})
    frequencies.push_back(bending_frequencies<2>(solid_scene("plane stress", 0, 70 * r, 1, r, 2), 5));
  for (unsigned int k = 0; k < 5; ++k)
    {
      const double coarse = std::abs(frequencies[0][k] - frequencies[1][k]);
      const double fine   = std::abs(frequencies[1][k] - frequencies[2][k]);
      const double order  = std::log2(coarse / fine);
      EXPECT_GT(order, 3.5) << "mode " << k + 1;
      EXPECT_LT(order, 4.5) << "mode " << k + 1;
      // and the error against the Timoshenko beam falls with the mesh
      EXPECT_LT(std::abs(frequencies[2][k] / f_T[k] - 1), std::abs(frequencies[1][k] / f_T[k] - 1)) << "mode " << k + 1;
    }

  // p = 3: converged to the Timoshenko beam.
  const auto f = bending_frequencies<2>(solid_scene("plane stress", 0, 140, 1, 1, 3), 5);
  for (unsigned int k = 0; k < 5; ++k)
    {
      EXPECT_LT(correction[k], -1e-4) << "mode " << k + 1 << ": the Timoshenko beam is softer";
      EXPECT_LT(std::abs(f[k] / f_T[k] - 1), 2e-3 * std::abs(correction[k])) << "mode " << k + 1;
    }
}

// On the published elastic supports (mueller2023-solid: each end face a
// rigid plate on the springs k_r and 2 k_t) the ν = 0 strip converges to the
// Timoshenko beam on rotational springs k_r (the axial spring does not enter
// the linear modes), as on the clamp: within 0.2 % of the shear and
// rotary-inertia correction, which the supports shrink a little.
TEST(SolidModes, StripOnTheElasticSupportsConvergesToTheTimoshenkoBeamOnThem)
{
  const Scene scene = read_scene(scene_dir + "mueller2023-solid.prm",
                                 {"Solid/Continuum=plane stress", "Solid/Poisson's ratio=0",
                                  "Solid/Elements along length=140", "Solid/Elements across width=1",
                                  "Solid/Degree=3"});
  ASSERT_TRUE(scene.supports.elastic());
  const BeamData &d = scene.beam;
  TimoshenkoBeam timoshenko{d.youngs_modulus, d.youngs_modulus / 2, 5. / 6, d.density, d.width, d.thickness, d.length};
  timoshenko.k_r = scene.supports.rotational_stiffness;
  // The Euler–Bernoulli beam on the same springs, the FE beam of the published scene.
  const FEBeam beam(read_scene(scene_dir + "mueller2023.prm"));
  const FEModes beam_modes = compute_bending_modes(beam, 5);
  const auto f = bending_frequencies<2>(scene, 5);
  for (unsigned int k = 0; k < 5; ++k)
    {
      const double f_T        = timoshenko.omega(k + 1, beam_modes.omega[k]) / (2 * M_PI);
      const double correction = f_T / (beam_modes.omega[k] / (2 * M_PI)) - 1;
      std::cout << "elastic supports, mode " << k + 1 << ": solid " << f[k] << " Hz, Timoshenko " << f_T
                << " Hz (solid - Timoshenko " << f[k] / f_T - 1 << "), correction against the beam " << correction << "\n";
      EXPECT_LT(correction, -1e-5) << "mode " << k + 1 << ": the Timoshenko beam is softer";
      EXPECT_LT(std::abs(f[k] / f_T - 1), 2e-3 * std::abs(correction)) << "mode " << k + 1;
    }
}

// The 3D strip without Poisson's ratio bends as the plane-stress strip does
// (the same frequencies on the same x-z mesh), and between its bending modes
// lies the first torsion mode, classified by its twist across the width
// near the St. Venant frequency of the clamped thin strip,
//   f_t = 1/(2L) sqrt(G J / (ρ I_p)),  J = b h³/3 (1 − 0.630 h/b),
//   I_p = (b h³ + h b³)/12,
// and above it by the warping the clamped faces prevent (~1 %) and the
// coarse mesh across the width.
TEST(SolidModes, ThreeDimensionalStripBendsAsThePlaneStressStripAndTwistsAsAThinStrip)
{
  const Scene scene3 = solid_scene("3d", 0, 70, 4, 1, 2);
  const SolidModel<3> model(scene3, MPI_COMM_WORLD);
  const SolidModes modes = compute_solid_modes(model, 5);
  const auto f2          = bending_frequencies<2>(solid_scene("plane stress", 0, 70, 1, 1, 2), 5);
  ASSERT_EQ(modes.bending.size(), 5u);
  for (unsigned int k = 0; k < 5; ++k)
    {
      const SolidMode &m = modes.all[modes.bending[k]];
      EXPECT_NEAR(m.omega / (2 * M_PI) / f2[k], 1., 1e-5) << "bending mode " << k + 1;
      EXPECT_GT(m.energy_share[2], 0.99) << "bending mode " << k + 1;
      EXPECT_LT(m.twist_correlation, 1e-10) << "bending mode " << k + 1;
    }

  const BeamData &d = scene3.beam;
  const double G = d.youngs_modulus / 2, J = d.width * std::pow(d.thickness, 3) / 3 * (1 - 0.630 * d.thickness / d.width);
  const double I_p = (d.width * std::pow(d.thickness, 3) + d.thickness * std::pow(d.width, 3)) / 12;
  const double f_t = std::sqrt(G * J / (d.density * I_p)) / (2 * d.length);
  unsigned int n_torsion = 0;
  for (const SolidMode &m : modes.all)
    if (m.shape == "torsion")
      {
        ++n_torsion;
        const double ratio = m.omega / (2 * M_PI) / f_t;
        EXPECT_GT(ratio, 1.) << "torsion at " << m.omega / (2 * M_PI) << " Hz, St. Venant " << f_t;
        EXPECT_LT(ratio, 1.1) << "torsion at " << m.omega / (2 * M_PI) << " Hz, St. Venant " << f_t;
      }
  EXPECT_EQ(n_torsion, 1u) << "below the fifth bending mode (3.65 kHz) the strip has one torsion mode (~1.9 kHz)";
}

// STEP on the solid (u = Φ q prescribed, the modal force evaluated by the
// assembled internal force) equals the reduced SVK polynomial integrated
// exactly from the cubic law: two independent routes through the same
// modes. The linear part is diag ω² (the modes are M-orthonormal), and the
// quadratic coefficients of the flat strip vanish (w → −w symmetry).
TEST(SolidCoefficients, StepEqualsTheExactReducedPolynomial)
{
  for (const std::string continuum : {"plane stress", "3d"})
    {
      const Scene scene = solid_scene(continuum, 0.3, 40, 2, 1, 2);
      auto check        = [&](auto model) {
        const SolidModes modes = compute_solid_modes(*model, 3);
        SolidModalCoefficients coefficients(*model, modes, 3);
        const CubicFit exact   = coefficients.exact_polynomial();
        const Eigen::VectorXd omega = coefficients.omega();
        const Eigen::MatrixXd omega2 = omega.array().square().matrix().asDiagonal();
        EXPECT_LT((exact.linear - omega2).norm(), 1e-8 * omega2.norm()) << continuum;
        const CubicFit step = identify_cubic_step([&](const Eigen::VectorXd &q) { return coefficients.modal_force(q); },
                                                  {coefficients.amplitudes(scene.beam.thickness), omega2});
        double largest = 0;
        for (const auto &t : exact.cubic)
          largest = std::max(largest, std::abs(t.value));
        ASSERT_EQ(step.cubic.size(), exact.cubic.size());
        for (std::size_t i = 0; i < exact.cubic.size(); ++i)
          EXPECT_NEAR(step.cubic[i].value, exact.cubic[i].value, 1e-6 * largest)
            << continuum << " c(" << exact.cubic[i].n << exact.cubic[i].j << exact.cubic[i].k << exact.cubic[i].l << ")";
        const double a = coefficients.amplitudes(scene.beam.thickness).maxCoeff();
        for (std::size_t i = 0; i < exact.quadratic.size(); ++i)
          {
            EXPECT_LT(std::abs(exact.quadratic[i].value), 1e-8 * largest * a) << continuum;
            EXPECT_LT(std::abs(step.quadratic[i].value), 1e-6 * largest * a) << continuum;
          }
      };
      if (continuum == "3d")
        check(std::make_unique<SolidModel<3>>(scene, MPI_COMM_WORLD));
      else
        check(std::make_unique<SolidModel<2>>(scene, MPI_COMM_WORLD));
    }
}

// ICE on the plane-stress strip without Poisson's ratio (the membrane free to
// relax, as in the beam's axial equilibrium) gives the von Kármán beam's b_111
// (seed Eq. 3 on the FE beam's modes) within 0.2 % (measured 0.04 %), to a
// fit residual at round-off (the condensed force is cubic to within 1e-14 at
// 0.03 h).
TEST(SolidCoefficients, IceOnTheStripWithoutPoissonGivesTheBeamsHardening)
{
  const Scene scene = solid_scene("plane stress", 0., 70, 1, 1, 2);
  const SolidModel<2> model(scene, MPI_COMM_WORLD);
  const SolidModes modes = compute_solid_modes(model, 1);
  SolidModalCoefficients coefficients(model, modes, 1);
  IceSettings ice;
  ice.omega      = coefficients.omega();
  ice.amplitudes = coefficients.amplitudes(0.03 * scene.beam.thickness);
  const CubicFit fit =
    identify_cubic_ice([&](const Eigen::VectorXd &f) { return coefficients.modal_static_response(f); }, ice);
  EXPECT_LT(fit.relative_fit_residual, 1e-10);

  const Scene beam_scene = read_scene(scene_dir + "mueller2023-ideal.prm");
  const FEBeam beam(beam_scene);
  const FEModes beam_modes = compute_bending_modes(beam, 1);
  const double beam_b111   = ReducedOrderModel(make_modal_basis(beam, beam_modes, 1), 0.).analytic_cubic_terms()[0].value;
  EXPECT_NEAR(fit.cubic[0].value / beam_b111, 1., 2e-3);
}

namespace
{
  // The ICE reduced model on bending modes 1 … N of a plane-stress solid and
  // what it needs to answer a line load: the modal load p = Φᵀ F and the
  // modes' mid-span deflections (w = w_phiᵀ q).
  struct IceRomOnLineLoad
  {
    CubicFit fit;
    Eigen::VectorXd p, w_phi;
  };

  IceRomOnLineLoad ice_rom_on_line_load(const SolidModel<2> &model, SolidStatics<2> &statics, const unsigned int N,
                                        const Vector &F)
  {
    const SolidModes modes = compute_solid_modes(model, N);
    SolidModalCoefficients coefficients(model, modes, N);
    IceSettings ice;
    ice.omega      = coefficients.omega();
    ice.amplitudes = coefficients.amplitudes(0.03 * model.thickness());
    IceRomOnLineLoad rom;
    rom.fit = identify_cubic_ice([&](const Eigen::VectorXd &f) { return coefficients.modal_static_response(f); }, ice);
    rom.p.resize(N);
    rom.w_phi.resize(N);
    for (unsigned int j = 0; j < N; ++j)
      {
        Vector phi;
        model.reinit_vector(phi);
        phi          = modes.all[modes.bending[j]].vector;
        rom.p[j]     = phi * F;
        rom.w_phi[j] = statics.mid_span_deflection(modes.all[modes.bending[j]].vector);
      }
    return rom;
  }

  // The reduced model's static response: K q + Σ a q_j q_k + Σ c q_j q_k q_l = p,
  // by Newton's method with a finite-difference Jacobian (N is small),
  // continued from q_start.
  Eigen::VectorXd rom_static_response(const CubicFit &fit, const Eigen::MatrixXd &K, const Eigen::VectorXd &p,
                                      Eigen::VectorXd q)
  {
    auto force = [&](const Eigen::VectorXd &x) {
      Eigen::VectorXd f = K * x;
      for (const auto &t : fit.quadratic)
        f[t.n] += t.value * x[t.j] * x[t.k];
      for (const auto &t : fit.cubic)
        f[t.n] += t.value * x[t.j] * x[t.k] * x[t.l];
      return f;
    };
    for (int it = 0; it < 50; ++it)
      {
        const Eigen::VectorXd r = p - force(q);
        if (r.norm() < 1e-13 * p.norm())
          break;
        Eigen::MatrixXd J(q.size(), q.size());
        for (Eigen::Index j = 0; j < q.size(); ++j)
          {
            const double d   = 1e-7 * std::max(std::abs(q[j]), 1e-3 * q.norm() + 1e-300);
            Eigen::VectorXd e = q;
            e[j] += d;
            J.col(j) = (force(e) - force(q)) / d;
          }
        q += J.partialPivLu().solve(r);
      }
    return q;
  }
} // namespace

// The solid's load path under a uniform line load: without Poisson's ratio
// it follows the von Kármán beam's closed form (test_fem_statics.cc's
// equations, solved here again) within 1e-3 up to 4 h (the difference at small
// load is the shear deflection, 5e-4 of the bending one at L/h = 140); and the
// ICE reduced model of the strip with ν = 0.3 (modes 1–5) reproduces the
// full static solve at w = h and 2 h within 1 %. Its error up to 4 h is printed.
// STEP with the other DoFs relaxed (the solid's condensed STEP) lets every
// DoF outside the kept modes find its equilibrium, as ICE does: the two
// give the same b_111 (within 1e-3; they differ by their fits' aliasing at
// 0.03 h), while plain STEP, which holds those DoFs, is several times stiffer
// (the membrane cannot shorten nor the section contract).
TEST(SolidCoefficients, RelaxedStepGivesIcesHardening)
{
  const Scene scene = solid_scene("plane stress", 0.3, 70, 1, 1, 2);
  const SolidModel<2> model(scene, MPI_COMM_WORLD);
  const SolidModes modes = compute_solid_modes(model, 2);
  SolidModalCoefficients<2> coefficients(model, modes, 2);
  const double h = scene.beam.thickness;
  const double relaxed = solid_cubic_fit(coefficients, "step-relaxed", h).cubic.at(0).value;
  const double ice     = solid_cubic_fit(coefficients, "ice", h).cubic.at(0).value;
  const double plain   = solid_cubic_fit(coefficients, "step", h).cubic.at(0).value;
  std::cout << "b_111: relaxed STEP " << relaxed << ", ICE " << ice << ", plain STEP " << plain << "\n";
  EXPECT_NEAR(relaxed / ice, 1., 1e-3);
  EXPECT_GT(plain / relaxed, 3.);
}

TEST(SolidStatics, LoadPathFollowsTheBeamAndTheIceModelFollowsTheLoadPath)
{
  const double q_4h = 12240.1; // N/m: the beam's 4 h (test_fem_statics.cc)
  for (const double nu : {0., 0.3})
    {
      const Scene scene = solid_scene("plane stress", nu, 70, 1, 1, 2);
      const SolidModel<2> model(scene, MPI_COMM_WORLD);
      SolidStatics<2> statics(model);
      const auto F = statics.line_load(-q_4h);
      // Full solves at 1/64 … 64/64 of the load (w from 0.4 h to 4 h).
      std::vector<double> loads, w_full;
      Vector u, F_k, F_previous, u_ghosted;
      model.reinit_vector(u);
      model.reinit_vector(F_previous);
      model.reinit_ghosted_vector(u_ghosted);
      for (unsigned int k = 1; k <= 64; ++k)
        {
          F_k = F;
          F_k *= k / 64.;
          statics.solve(F_k, u, &F_previous);
          F_previous = F_k;
          u_ghosted  = u;
          loads.push_back(q_4h * k / 64.);
          w_full.push_back(statics.mid_span_deflection(u_ghosted));
        }
      const double h = scene.beam.thickness;
      EXPECT_NEAR(w_full.back() / h, -4., 0.01) << "nu = " << nu;
      if (nu == 0.)
        {
          // The beam's closed form: the mid-span deflection under q with
          // N = EA/(2L)∫w'² (see test_fem_statics.cc for the derivation).
          const BeamData &d = scene.beam;
          const long double EI = d.bending_stiffness(), EA = d.axial_stiffness(), L = d.length, a = L / 2;
          for (std::size_t k = 0; k < loads.size(); ++k)
            {
              const long double q = loads[k];
              long double lo = 1e-20L * EA, hi = EA;
              for (int i = 0; i < 200; ++i)
                {
                  const long double N = std::sqrt(lo * hi), kk = std::sqrt(N / EI), p = q / N;
                  const long double A = p * a / (kk * std::sinh(kk * a));
                  const long double I = A * A * kk * kk * (std::sinh(kk * L) / (2 * kk) - a) -
                                        4 * A * p * (a * std::cosh(kk * a) - std::sinh(kk * a) / kk) + p * p * L * L * L / 12;
                  (N - EA / (2 * L) * I < 0 ? lo : hi) = N;
                }
              const long double z = a * std::sqrt(std::sqrt(lo * hi) / EI);
              const double w_beam = double(q * a * a * a * a / EI * (0.5L - std::tanh(z / 2) / z) / (z * z));
              EXPECT_NEAR(-w_full[k] / w_beam, 1., 1e-3) << "q = " << loads[k];
            }
          // The whole load in one solve from the flat strip reaches the same
          // state: the line search keeps the first correction (on a tangent
          // without membrane stiffness: the linear deflection, many h) from
          // diverging: 4 factorisations and 16 back-substitutions, against
          // 25 and 80 without it (increments cut back, 2026-11-29).
          SolidStatics<2> one_solve(model);
          Vector u_one;
          model.reinit_vector(u_one);
          one_solve.solve(F, u_one);
          u_ghosted = u_one;
          EXPECT_NEAR(one_solve.mid_span_deflection(u_ghosted) / w_full.back(), 1., 1e-8);
          EXPECT_LE(one_solve.n_factorisations(), 5u);
          continue;
        }

      // ICE on modes 1–5 and its static response to the projected load.
      const unsigned int N         = 5;
      const IceRomOnLineLoad rom   = ice_rom_on_line_load(model, statics, N, F);
      const CubicFit &fit          = rom.fit;
      const Eigen::MatrixXd K      = fit.linear;
      const Eigen::VectorXd &p     = rom.p, &w_phi = rom.w_phi;
      Eigen::VectorXd q            = Eigen::VectorXd::Zero(N);
      for (std::size_t k = 0; k < loads.size(); ++k)
        {
          q                  = rom_static_response(fit, K, p * (loads[k] / q_4h), q);
          const double w_rom = w_phi.dot(q);
          const double error = w_rom / w_full[k] - 1;
          if (k % 8 == 7)
            std::cout << "ICE ROM (modes 1-5), nu = 0.3: w = " << w_full[k] / h << " h, relative error " << error << "\n";
          if (std::abs(w_full[k]) <= 2.05 * h)
            {
              EXPECT_LT(std::abs(error), 0.01) << "w = " << w_full[k] / h << " h";
            }
        }
    }
}

// A shallow arch (the strip's mid-surface at z₀ = a sin(πx/L), a = 2 h,
// plane stress, ν = 0.3) is stiffer pushed down than pulled up, at first
// order in the load: the quadratic modal coefficients carry that. The ICE
// reduced model on bending modes 1–5 reproduces the full static solve's
// mid-span deflection for both load signs within 2 % at the smallest load
// (w ≈ h/4) and the asymmetry w(+q) + w(−q) within 10 %; a model without its
// quadratic terms has no asymmetry at all. Larger loads are printed: at twice
// the load the downward one snaps the arch through (w ≈ −3.4 h), a branch the
// reduced model, solved from rest without continuation, does not follow.
TEST(SolidStatics, ArchQuadraticCoefficientsGiveTheAsymmetricLoadPath)
{
  Scene scene = solid_scene("plane stress", 0.3, 70, 1, 1, 2);
  scene.solid.arch_rise = 2 * scene.beam.thickness;
  const SolidModel<2> model(scene, MPI_COMM_WORLD);
  SolidStatics<2> statics(model);
  const double h = scene.beam.thickness;

  const unsigned int N       = 5;
  const double q_unit        = 1000; // N/m
  const auto F_unit          = statics.line_load(q_unit);
  const IceRomOnLineLoad rom = ice_rom_on_line_load(model, statics, N, F_unit);
  const CubicFit &fit        = rom.fit;
  const Eigen::VectorXd &p = rom.p, &w_phi = rom.w_phi;
  double largest_quadratic = 0;
  for (const auto &t : fit.quadratic)
    largest_quadratic = std::max(largest_quadratic, std::abs(t.value));
  EXPECT_GT(largest_quadratic, 0.);

  // The load of a linear mid-span deflection h/4.
  const double q_small = q_unit * 0.25 * h / std::abs(w_phi.dot(fit.linear.ldlt().solve(p)));

  for (const double factor : {1., 2., 4.})
    {
      double w_full[2], w_rom[2];
      for (const int sign : {1, -1})
        {
          const double q = sign * factor * q_small;
          Vector u, F = F_unit, u_ghosted;
          F *= q / q_unit;
          model.reinit_vector(u);
          model.reinit_ghosted_vector(u_ghosted);
          statics.solve(F, u);
          u_ghosted                   = u;
          w_full[sign > 0 ? 0 : 1] = statics.mid_span_deflection(u_ghosted);
          const Eigen::VectorXd qm  = rom_static_response(fit, fit.linear, p * (q / q_unit), Eigen::VectorXd::Zero(N));
          w_rom[sign > 0 ? 0 : 1]   = w_phi.dot(qm);
        }
      const double asymmetry_full = w_full[0] + w_full[1], asymmetry_rom = w_rom[0] + w_rom[1];
      std::cout << "arch, q = ±" << factor * q_small << " N/m: w_full = " << w_full[0] / h << " h, " << w_full[1] / h
                << " h; ICE ROM error " << w_rom[0] / w_full[0] - 1 << ", " << w_rom[1] / w_full[1] - 1
                << "; asymmetry " << asymmetry_full / h << " h (ROM " << asymmetry_rom / h << " h)\n";
      if (factor == 1.)
        {
          EXPECT_GT(std::abs(asymmetry_full), 0.02 * std::abs(w_full[0])) << "the arch's response is asymmetric";
          EXPECT_NEAR(w_rom[0] / w_full[0], 1., 0.02);
          EXPECT_NEAR(w_rom[1] / w_full[1], 1., 0.02);
          EXPECT_NEAR(asymmetry_rom / asymmetry_full, 1., 0.1);
        }
    }
}

// The solid's modes sampled along the beam line (fem/solid_modal_basis.h)
// are the beam's: with ν = 0 in plane stress, on the ideal clamp and on the
// published elastic supports, what separates them from the FE beam's modes
// 1–5 is Timoshenko's shear and rotary inertia, so every difference scales
// with the frequency shift c_n = ω_solid/ω_beam − 1 (−0.02 % … −0.22 %):
// |Δφ_n| ≤ |c_n| max|φ_n| (measured ≤ 0.5 |c_n|), |Δφ_n'| ≤ 3 |c_n| max|φ_n'|
// (measured 2.3 |c_n|: shear turns the slope w' away from the section's
// rotation), γ_n (modes 1, 3, 5) within |c_n|, and |c_n| < 0.3 %.
TEST(SolidModalBasis, TheSolidsBeamLineCarriesTheBeamsModes)
{
  for (const std::string name : {"mueller2023-ideal", "mueller2023"})
    {
      Scene scene = read_scene(scene_dir + (name == "mueller2023" ? "mueller2023-solid.prm" : "mueller2023-ideal-solid.prm"),
                               {"Solid/Continuum=plane stress", "Solid/Poisson's ratio=0", "Solid/Elements along length=140"});
      const SolidModel<2> model(scene, MPI_COMM_WORLD);
      const SolidModes modes = compute_solid_modes(model, 5);
      const ModalBasis solid = make_solid_modal_basis(model, modes, 5, scene);

      const FEBeam beam(read_scene(scene_dir + name + ".prm"));
      const ModalBasis fe = make_modal_basis(beam, compute_bending_modes(beam, 5), 5);
      Eigen::VectorXd p_s, dp_s, p_b, dp_b, max_p = Eigen::VectorXd::Zero(5), max_dp = Eigen::VectorXd::Zero(5),
                                                err_p = Eigen::VectorXd::Zero(5), err_dp = Eigen::VectorXd::Zero(5);
      for (unsigned int i = 0; i <= 200; ++i)
        {
          const double x = scene.beam.length * i / 200;
          solid.evaluate(x, p_s, dp_s);
          fe.evaluate(x, p_b, dp_b);
          max_p  = max_p.cwiseMax(p_b.cwiseAbs());
          max_dp = max_dp.cwiseMax(dp_b.cwiseAbs());
          err_p  = err_p.cwiseMax((p_s - p_b).cwiseAbs());
          err_dp = err_dp.cwiseMax((dp_s - dp_b).cwiseAbs());
        }
      for (unsigned int n = 0; n < 5; ++n)
        {
          std::cout << name << ", mode " << n + 1 << ": phi " << err_p[n] / max_p[n] << ", phi' "
                    << err_dp[n] / max_dp[n] << ", gamma " << solid.gamma[n] / fe.gamma[n] - 1 << ", omega "
                    << solid.omega[n] / fe.omega[n] - 1 << "\n";
          const double c = std::abs(solid.omega[n] / fe.omega[n] - 1);
          EXPECT_LT(c, 3e-3) << name << ", mode " << n + 1;
          EXPECT_LT(err_p[n], c * max_p[n]) << name << ", mode " << n + 1;
          EXPECT_LT(err_dp[n], 3 * c * max_dp[n]) << name << ", mode " << n + 1;
          if (n % 2 == 0) // the antisymmetric modes have γ = 0
            {
              EXPECT_NEAR(solid.gamma[n] / fe.gamma[n], 1., c) << name << ", mode " << n + 1;
            }
        }
    }
}

// The animation of a solid-derived ROM run draws Σ q_n φ_n on the solid: its
// sections must deflect as the reduced model's beam line says, mode by mode
// (a wrong sign or order of the modes would be O(1) off). The two readings
// differ by the line's Hermite interpolation and by u_z's variation through
// the thickness (a section average against the mid-surface), both far below
// 1e-3. Frames are listed in solid.pvd with their times.
TEST(SolidRomAnimation, TheSolidFramesDeflectAsTheReducedModelsBeamLine)
{
  const Scene scene = read_scene(scene_dir + "mueller2023-solid.prm",
                                 {"Solid/Continuum=plane stress", "Solid/Elements along length=70"});
  const unsigned int N = 3;
  const SolidModel<2> model(scene, MPI_COMM_SELF);
  const ModalBasis line = make_solid_modal_basis(model, compute_solid_modes(model, N), N, scene);

  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("beamslider_solid_animation_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    SolidRomAnimation animation(scene, N, dir.string());
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-1e-3, 1e-3);
    Eigen::VectorXd phi, dphi;
    double worst = 0; // the largest difference, relative to the frame's deflection
    for (unsigned int trial = 0; trial <= N; ++trial)
      {
        // The unit coordinates e_1 … e_N, then a random combination.
        Eigen::VectorXd q = Eigen::VectorXd::Zero(N);
        if (trial < N)
          q[trial] = 1e-3;
        else
          for (unsigned int n = 0; n < N; ++n)
            q[n] = coordinate(random);
        double scale = 0;
        for (const double x_over_L : {0.25, 0.5, 0.7})
          {
            line.evaluate(x_over_L * scene.beam.length, phi, dphi);
            scale = std::max(scale, std::abs(phi.dot(q)));
          }
        for (const double x_over_L : {0.25, 0.5, 0.7})
          {
            const double x = x_over_L * scene.beam.length;
            line.evaluate(x, phi, dphi);
            const double w_solid = animation.section_deflection(q, x);
            worst                = std::max(worst, std::abs(w_solid - phi.dot(q)) / scale);
            EXPECT_NEAR(w_solid, phi.dot(q), 1e-3 * scale)
              << "trial " << trial << " at x/L = " << x_over_L;
          }
        animation.write(0.001 * trial, 1e-6 * trial, q);
      }
    std::cout << "solid frames against the beam line: largest difference " << worst << " of the deflection\n";
    animation.finish();
    EXPECT_EQ(animation.n_frames(), N + 1);
  }
  // solid.pvd lists every frame at its time, and every listed record exists.
  std::ifstream pvd(dir / "solid.pvd");
  const std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  const std::regex entry("timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"");
  unsigned int k = 0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), entry); it != std::sregex_iterator(); ++it, ++k)
    {
      EXPECT_NEAR(std::stod((*it)[1]), 0.001 * k, 1e-12);
      EXPECT_TRUE(fs::exists(dir / (*it)[2].str())) << (*it)[2];
    }
  EXPECT_EQ(k, N + 1);
  fs::remove_all(dir);
}
