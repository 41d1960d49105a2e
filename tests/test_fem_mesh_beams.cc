// Beams from Gmsh meshes (meshes/*.msh, doc/scenes.md "Beams from a mesh"):
// the uniform mesh equals the generated beam, the stepped beam's frequencies
// converge to an exact transfer-matrix solution written here, the generalised
// analytic b_111 agrees with condensed STEP and ICE on the stepped beam, and a
// point mass lowers the first frequency as the Rayleigh quotient of seed
// Eq. 5 predicts. The mode table a graded mesh's modes live in finds the
// right interval everywhere.
#include "fem/fe_beam.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/mode_table_basis.h"
#include "contact/hermite_shape.h"
#include "scene/scene.h"
#include "verification/studies/coefficient_methods.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <iostream>

using namespace beamslider;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  // b_111 by the analytic route (seed Eq. 3 with the generalised k_ax).
  double analytic_b111(const ModalBasis &basis) { return 0.5 * basis.membrane_stiffness * std::pow(basis.stretch(0, 0), 2); }

  // One Euler–Bernoulli segment: length, EI, rho A.
  struct Segment
  {
    double length, EI, rhoA;
  };

  // Field transfer matrix of a uniform segment at circular frequency ω, for
  // the state (w, w', M = EI w'', Q = EI w''') with Krylov's functions
  // S = (ch + cos)/2, T = (sh + sin)/2, U = (ch − cos)/2, V = (sh − sin)/2
  // of z = β ℓ, β⁴ = ρA ω²/EI: exact for the segment.
  Eigen::Matrix4d segment_transfer(const Segment &s, const double omega)
  {
    const double beta = std::pow(s.rhoA * omega * omega / s.EI, 0.25), z = beta * s.length, EI = s.EI;
    const double S = 0.5 * (std::cosh(z) + std::cos(z)), T = 0.5 * (std::sinh(z) + std::sin(z));
    const double U = 0.5 * (std::cosh(z) - std::cos(z)), V = 0.5 * (std::sinh(z) - std::sin(z));
    const double b = beta, b2 = b * b, b3 = b2 * b;
    Eigen::Matrix4d t;
    t << S, T / b, U / (EI * b2), V / (EI * b3), //
      b * V, S, T / (EI * b), U / (EI * b2),     //
      EI * b2 * U, EI * b * V, S, T / b,         //
      EI * b3 * T, EI * b2 * U, b * V, S;
    return t;
  }

  // The frequency determinant of segments in a row between two supports with
  // w = 0 and rotational springs k_r (natural conditions EI w''(0) = k_r w'(0),
  // EI w''(L) = −k_r w'(L)): the start state is θ0 (0, 1, k_r, 0) + Q0 (0, 0, 0, 1).
  double frequency_determinant(const std::vector<Segment> &segments, const double k_r, const double omega)
  {
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (const Segment &s : segments)
      T = segment_transfer(s, omega) * T;
    const Eigen::Vector4d a = T * Eigen::Vector4d(0, 1, k_r, 0), b = T * Eigen::Vector4d(0, 0, 0, 1);
    // End conditions w_L = 0 and M_L + k_r θ_L = 0 on a and b.
    const double a1 = a[0], a2 = a[2] + k_r * a[1], b1 = b[0], b2 = b[2] + k_r * b[1];
    return a1 * b2 - a2 * b1;
  }

  // The root of f in [lo, hi] where it changes sign once, by bisection.
  double bisect(const std::function<double(double)> &f, double lo, double hi)
  {
    double f_lo = f(lo);
    for (unsigned int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
      {
        const double mid = 0.5 * (lo + hi), f_mid = f(mid);
        if ((f_mid < 0) == (f_lo < 0))
          lo = mid, f_lo = f_mid;
        else
          hi = mid;
      }
    return 0.5 * (lo + hi);
  }
} // namespace

TEST(MeshBeam, UniformMeshEqualsTheGeneratedBeam)
{
  const Scene generated = read_scene(scene_dir + "mueller2023.prm");
  const Scene meshed    = read_scene(scene_dir + "uniform.prm");
  ASSERT_TRUE(meshed.beam.from_mesh());
  ASSERT_FALSE(generated.beam.from_mesh());
  const FEBeam a(generated), b(meshed);
  ASSERT_EQ(a.n_dofs(), b.n_dofs());
  const FEModes ma = compute_bending_modes(a, 5), mb = compute_bending_modes(b, 5);
  for (unsigned int k = 0; k < 5; ++k)
    EXPECT_NEAR(mb.omega[k] / ma.omega[k], 1., 1e-10) << "mode " << k + 1;
  const double b111_a = analytic_b111(make_modal_basis(a, ma, 1)), b111_b = analytic_b111(make_modal_basis(b, mb, 1));
  EXPECT_NEAR(b111_b / b111_a, 1., 1e-10);
}

// Frequencies of the stepped beam (meshes/stepped.prm) against the exact
// transfer-matrix solution: the FE error falls as h⁴ (Hermite cubics) when
// every mesh element is split in 2 and 4.
TEST(MeshBeam, SteppedFrequenciesConvergeToTransferMatrixAtOrderFour)
{
  const Scene scene = read_scene(scene_dir + "stepped.prm");
  const BeamSection thin = scene.beam.sections.at(1), thick = scene.beam.sections.at(2);
  // The geometry of stepped.geo: thin on [0, 0.05], thick on [0.05, 0.09], thin on [0.09, 0.14] m.
  const std::vector<Segment> segments{{0.05, thin.bending_stiffness(), thin.mass_per_length()},
                                      {0.04, thick.bending_stiffness(), thick.mass_per_length()},
                                      {0.05, thin.bending_stiffness(), thin.mass_per_length()}};
  const double k_r = scene.supports.rotational_stiffness;
  ASSERT_TRUE(scene.supports.elastic());

  const unsigned int n_modes = 3;
  std::vector<std::vector<double>> errors;
  std::vector<double> exact(n_modes);
  for (const unsigned int parts : {1u, 2u, 4u})
    {
      const FEBeam beam(scene, parts * scene.beam.mesh_cells.size());
      const FEModes modes = compute_bending_modes(beam, n_modes);
      if (parts == 1)
        for (unsigned int k = 0; k < n_modes; ++k)
          {
            // The determinant's sign change nearest the FE frequency.
            const auto D = [&](const double w) { return frequency_determinant(segments, k_r, w); };
            const double w_fe = modes.omega[k];
            double lo = 0.97 * w_fe, step = 0.0005 * w_fe;
            while ((D(lo) < 0) == (D(lo + step) < 0) && lo < 1.03 * w_fe)
              lo += step;
            ASSERT_LT(lo, 1.03 * w_fe) << "no root of the transfer-matrix determinant near mode " << k + 1;
            exact[k] = bisect(D, lo, lo + step);
          }
      std::vector<double> e;
      for (unsigned int k = 0; k < n_modes; ++k)
        e.push_back(std::abs(modes.omega[k] - exact[k]) / exact[k]);
      errors.push_back(e);
    }
  for (unsigned int k = 0; k < n_modes; ++k)
    {
      std::cout << "mode " << k + 1 << ": exact " << exact[k] / (2 * M_PI) << " Hz, relative errors " << errors[0][k]
                << ", " << errors[1][k] << ", " << errors[2][k] << '\n';
      EXPECT_LT(errors[0][k], 1e-4) << "mode " << k + 1 << " on the gallery mesh";
      for (unsigned int r = 0; r + 1 < errors.size(); ++r)
        {
          const double order = std::log2(errors[r][k] / errors[r + 1][k]);
          EXPECT_NEAR(order, 4., 0.3) << "mode " << k + 1 << ", refinement " << r + 1;
        }
    }
}

// On a non-uniform beam the membrane force without axial inertia is still
// uniform, so k_ax = (∫dx/EA + 1/k_t)⁻¹; condensed STEP and ICE, which solve
// the axial equilibrium on the mesh, must agree with b_111 from that k_ax.
TEST(MeshBeam, GeneralisedAnalyticB111AgreesWithCondensedStepAndIceOnTheSteppedBeam)
{
  const Scene scene = read_scene(scene_dir + "stepped.prm");
  const FEBeam beam(scene);
  const FEModes modes     = compute_bending_modes(beam, 3);
  const ModalBasis basis  = make_modal_basis(beam, modes, 3);
  const BeamSection thin  = scene.beam.sections.at(1), thick = scene.beam.sections.at(2);
  const double compliance = 0.10 / thin.axial_stiffness() + 0.04 / thick.axial_stiffness() + 1. / scene.supports.axial_stiffness;
  EXPECT_NEAR(basis.membrane_stiffness * compliance, 1., 1e-12);

  const double analytic = analytic_b111(basis);
  for (const auto &[method, level] : {std::pair{"step-condensed", 1.0}, std::pair{"ice", 0.03}})
    {
      const CoefficientResult r = compute_coefficients(beam, modes, basis, method, level);
      const double b111         = r.fit.cubic_coefficient(0, 0, 0, 0);
      std::cout << method << ": b_111 / analytic = " << b111 / analytic << '\n';
      EXPECT_NEAR(b111 / analytic, 1., 1e-3) << method;
    }
  // The uniform formula with the thickest section's EA would be off by more
  // than the tolerance: the check above can tell the two apart.
  const double uniform_k_ax = 1. / (scene.beam.length / thick.axial_stiffness() + 1. / scene.supports.axial_stiffness);
  EXPECT_GT(std::abs(uniform_k_ax / basis.membrane_stiffness - 1.), 1e-2);
}

// A point mass (meshes/tip-mass.prm) lowers the first frequency below the bare
// beam's; seed Eq. 5, ω̃² = ω₁²/(1 + m φ₁² + J φ₁'²), is its Rayleigh quotient on
// the bare mode: an upper bound whose error is second order in the mass. The
// scene's point mass must also equal the bonded-body route of the slider check.
TEST(MeshBeam, PointMassLowersTheFrequencyAsSeedEquationFivePredicts)
{
  const std::string file = scene_dir + "tip-mass.prm";
  const Scene bare_scene = read_scene(file, {"Point masses/Masses=", "Point masses/Rotary inertias="});
  const FEBeam bare_beam(bare_scene);
  const FEModes bare  = compute_bending_modes(bare_beam, 1);
  const double x      = 0.126;
  const double phi    = bare_beam.deflection(bare.shapes[0], x), dphi = bare_beam.slope(bare.shapes[0], x);
  const double J_over_m = 2e-8 / 0.005; // the gallery body's ratio, kept while the mass shrinks

  std::vector<double> eq5_errors;
  for (const double m : {0.02, 0.01, 0.005})
    {
      const double J    = J_over_m * m;
      std::ostringstream masses, inertias;
      masses << std::setprecision(17) << "Point masses/Masses=0.126: " << m;
      inertias << std::setprecision(17) << "Point masses/Rotary inertias=0.126: " << J;
      const Scene scene = read_scene(file, {masses.str(), inertias.str()});
      ASSERT_EQ(scene.beam.point_masses.size(), 1u);
      const FEBeam beam(scene);
      const double omega  = compute_bending_modes(beam, 1).omega[0];
      const double bonded = compute_bending_modes(bare_beam, 1, BondedBody{x, m, J}).omega[0];
      EXPECT_NEAR(omega / bonded, 1., 1e-12) << "the scene's point mass and the bonded body, m = " << m;
      EXPECT_LT(omega, bare.omega[0]);
      const double eq5 = bare.omega[0] / std::sqrt(1 + m * phi * phi + J * dphi * dphi);
      EXPECT_GE(eq5, omega * (1 - 1e-12)) << "Eq. 5 is a Rayleigh quotient: an upper bound";
      eq5_errors.push_back((eq5 - omega) / omega);
      std::cout << "m = " << m << " kg: FE " << omega / (2 * M_PI) << " Hz, Eq. 5 " << eq5 / (2 * M_PI)
                << " Hz, relative difference " << eq5_errors.back() << '\n';
    }
  for (std::size_t i = 0; i + 1 < eq5_errors.size(); ++i)
    EXPECT_NEAR(std::log2(eq5_errors[i] / eq5_errors[i + 1]), 2., 0.25) << "second order in the mass";
}

namespace
{
  // A table of strongly graded intervals (1 mm next to 25 cm) without coefficients.
  HermiteModeTable graded_table(const unsigned int n_modes)
  {
    HermiteModeTable table;
    table.vertices    = {0., 0.001, 0.002, 0.05, 0.051, 0.3, 0.31};
    table.length      = table.vertices.back();
    table.n_intervals = table.vertices.size() - 1;
    table.n_modes     = n_modes;
    return table;
  }
} // namespace

// A mesh's intervals need not be equal, and the table must find the one
// holding x by its vertices. With values that jump at each
// vertex (no mode does, but the jump shows which interval answered), x at a
// vertex takes the interval to its right, x just below it the one to its
// left, and x = L the last one, on a strongly graded table.
TEST(ModeTable, GradedIntervalsAnswerFromTheIntervalHoldingX)
{
  HermiteModeTable table = graded_table(1);
  // Interval e: w = 10 e at its left end, 10 e + 1 at its right end, slopes 0.
  for (unsigned int e = 0; e < table.n_intervals; ++e)
    table.coefficients.insert(table.coefficients.end(), {10. * e, 0., 10. * e + 1., 0.});
  Eigen::VectorXd phi, dphi;
  for (unsigned int e = 0; e < table.n_intervals; ++e)
    {
      const double left = table.vertices[e], right = table.vertices[e + 1];
      table.evaluate(left, phi, dphi);
      EXPECT_EQ(phi[0], 10. * e) << "x = " << left;
      table.evaluate(std::nextafter(right, 0.), phi, dphi);
      EXPECT_NEAR(phi[0], 10. * e + 1., 1e-9) << "just below x = " << right;
      // The cubic's midpoint value (w0 + w1)/2 for zero end slopes.
      table.evaluate(0.5 * (left + right), phi, dphi);
      EXPECT_NEAR(phi[0], 10. * e + 0.5, 1e-12) << "interval " << e;
    }
  table.evaluate(table.length, phi, dphi);
  EXPECT_EQ(phi[0], 10. * (table.n_intervals - 1) + 1.);
  EXPECT_THROW(table.evaluate(std::nextafter(table.length, 1.), phi, dphi), std::out_of_range);
  EXPECT_THROW(table.evaluate(-1e-12, phi, dphi), std::out_of_range);
}

// The deflection of coordinates q from the interval's nodal values,
// Σ_n q_n φ_n(x) summed before the shape functions (what the reduced model's
// contact detection takes, HermiteModeTable::displacement), equals φ(x)·q and
// φ'(x)·q to round-off, on random mode coefficients over a graded table.
TEST(ModeTable, DisplacementFromNodalValuesEqualsTheModalSum)
{
  HermiteModeTable table = graded_table(7);
  std::srand(3);
  const Eigen::VectorXd c = Eigen::VectorXd::Random(4 * table.n_modes * table.n_intervals);
  table.coefficients.assign(c.data(), c.data() + c.size());
  const Eigen::VectorXd q = Eigen::VectorXd::Random(table.n_modes);
  Eigen::VectorXd phi, dphi;
  for (unsigned int i = 0; i <= 62; ++i)
    {
      const double x = table.length * i / 62.;
      table.evaluate(x, phi, dphi);
      double w = 0, dw = 0;
      table.displacement(x, q, w, dw);
      // The round-off scale: Σ_n Σ_a |N_a c_na q_n| (and with N_a'), on the
      // interval that holds x.
      unsigned int e = 0;
      while (e + 1 < table.n_intervals && table.vertices[e + 1] <= x)
        ++e;
      const double h = table.vertices[e + 1] - table.vertices[e];
      std::array<double, 4> N, dN;
      hermite_shape(std::min((x - table.vertices[e]) / h, 1.), h, N, dN);
      double w_scale = 0, dw_scale = 0;
      for (unsigned int n = 0; n < table.n_modes; ++n)
        for (unsigned int a = 0; a < 4; ++a)
          {
            const double cq = std::abs(table.coefficients[4 * (table.n_modes * e + n) + a] * q[n]);
            w_scale += std::abs(N[a]) * cq;
            dw_scale += std::abs(dN[a]) * cq;
          }
      EXPECT_NEAR(w, phi.dot(q), 1e-14 * w_scale) << "x = " << x;
      EXPECT_NEAR(dw, dphi.dot(q), 1e-14 * dw_scale) << "x = " << x;
    }
  double w = 0, dw = 0;
  EXPECT_THROW(table.displacement(std::nextafter(table.length, 1.), q, w, dw), std::out_of_range);
}
