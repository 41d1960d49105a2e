// Cubic modal coefficients from the FE model (fem/fe_statics + reduced/cubic_fit)
// against the analytic seed Eq. 3 on the same FE modes, and plain STEP's
// membrane over-prediction against an independent quadrature of the analytic
// clamped–clamped mode.
#include "fem/fe_beam.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/fe_statics.h"
#include "scene/scene.h"
#include "reduced/cubic_fit.h"
#include "reduced/rom_operator.h"
#include "verification/studies/coefficient_methods.h"

#include "test_reduced_clamped_beam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace beamslider;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  struct CoefficientSetup
  {
    Scene scene;
    std::unique_ptr<FEBeam> beam;
    FEModes modes;
    ModalBasis basis;
    std::vector<CubicTerm> analytic;
    Eigen::VectorXd amplitudes;

    CoefficientSetup(const std::string &file, const unsigned int N)
      : scene(read_scene(scene_dir + file))
    {
      beam     = std::make_unique<FEBeam>(scene);
      modes    = compute_bending_modes(*beam, N);
      basis    = make_modal_basis(*beam, modes, N);
      analytic = ReducedOrderModel(basis, 0.).analytic_cubic_terms();
      amplitudes = step_amplitudes(max_abs_deflection(*beam, modes, N), scene.beam.thickness);
    }
    Eigen::MatrixXd omega2() const { return basis.omega.array().square().matrix().asDiagonal(); }
  };

  // The terms whose magnitude is at least 1e-3 of the largest.
  std::vector<CubicTerm> dominant(const std::vector<CubicTerm> &terms)
  {
    double largest = 0;
    for (const auto &t : terms)
      largest = std::max(largest, std::abs(t.value));
    std::vector<CubicTerm> d;
    for (const auto &t : terms)
      if (std::abs(t.value) >= 1e-3 * largest)
        d.push_back(t);
    return d;
  }

  void expect_agree(const std::vector<CubicTerm> &reference, const CubicFit &fit, const double tolerance, const std::string &what)
  {
    const auto terms = dominant(reference);
    ASSERT_GE(terms.size(), 1u);
    for (const auto &t : terms)
      EXPECT_NEAR(fit.cubic_coefficient(t.n, t.j, t.k, t.l) / t.value, 1., tolerance)
        << what << ": c^(" << t.n + 1 << ")_" << t.j + 1 << t.k + 1 << t.l + 1;
  }
} // namespace

TEST(CondensedStep, AgreesWithAnalyticCoefficientsForTheIdealClamp)
{
  CoefficientSetup s("mueller2023-ideal.prm", 3);
  FEStatics statics(*s.beam, s.modes, 3);
  const CubicFit fit = identify_cubic_step([&](const Eigen::VectorXd &q) { return statics.modal_force_condensed(q); },
                                           {s.amplitudes, s.omega2()});
  expect_agree(s.analytic, fit, 1e-3, "step-condensed");
  EXPECT_LT(fit.max_abs_quadratic(), 1e-8 * std::abs(s.analytic[0].value) * s.amplitudes[0]);
}

// The published clamping (Müller, Beck & Krack 2023): k_t = 1.93e7 N/m is the
// total axial stiffness of both supports, in series with the beam, so
//   k_ax = (L/EA + 1/k_t)^-1 = 1.007e7 N/m   for mueller2023,
// computed here by hand from the published numbers, not through the code's
// formula. b_111 = (k_ax/2) (∫φ₁'²)² from it is the reference for the three
// FE routes: condensed STEP and ICE (static FE solves) and the b_111 implied
// by the FE's own backbone. The FE model with the axial spring k_t at each
// end instead (k_ax = 6.6e6 N/m) is 34 % softer and fails all three.
TEST(PublishedClamping, FERoutesToB111AgreeWithTheTotalAxialStiffness)
{
  const double L = 0.14, b = 14.04e-3, h = 1e-3, E = 210e9, k_t = 1.93e7; // mueller2023, published
  const double k_ax = 1. / (L / (E * b * h) + 1. / k_t);
  EXPECT_NEAR(k_ax, 1.007e7, 0.001e7);

  CoefficientSetup s("mueller2023.prm", 3);
  EXPECT_NEAR(s.basis.membrane_stiffness / k_ax, 1., 1e-12) << "the scene's k_ax";
  const double K11  = s.basis.stretch(0, 0); // ∫φ₁'² dx on the FE mode [1/(kg m)]
  const double b111 = 0.5 * k_ax * K11 * K11;

  FEStatics statics(*s.beam, s.modes, 3);
  const CubicFit condensed = identify_cubic_step(
    [&](const Eigen::VectorXd &q) { return statics.modal_force_condensed(q); }, {s.amplitudes, s.omega2()});
  EXPECT_NEAR(condensed.cubic_coefficient(0, 0, 0, 0) / b111, 1., 1e-3) << "step-condensed";
  expect_agree(s.analytic, condensed, 1e-3, "step-condensed, elastic supports");

  IceSettings ice;
  ice.omega      = s.basis.omega;
  ice.amplitudes = 0.03 * s.amplitudes; // load level: see ImplicitCondensation below
  const CubicFit implicit =
    identify_cubic_ice([&](const Eigen::VectorXd &f) { return statics.modal_static_response(f); }, ice);
  EXPECT_NEAR(implicit.cubic_coefficient(0, 0, 0, 0) / b111, 1., 1e-3) << "ice";

  CoefficientSetup one("mueller2023.prm", 1);
  const FEImpliedCoefficient implied = fe_implied_b111(*one.beam, one.modes);
  EXPECT_NEAR(implied.b_111 / b111, 1., 1e-3) << "FE-implied";
  std::cout << "k_ax = " << k_ax << " N/m, b_111 = " << b111 << "; condensed STEP / b_111 = "
            << condensed.cubic_coefficient(0, 0, 0, 0) / b111
            << ", ICE / b_111 = " << implicit.cubic_coefficient(0, 0, 0, 0) / b111
            << ", FE-implied / b_111 = " << implied.b_111 / b111 << std::endl;
}

TEST(ImplicitCondensation, AgreesWithAnalyticCoefficients)
{
  CoefficientSetup s("mueller2023-ideal.prm", 3);
  FEStatics statics(*s.beam, s.modes, 3);
  IceSettings settings;
  settings.omega      = s.basis.omega;
  // Linear displacements of 0.03 h. The static response also excites the
  // modes outside the basis, whose condensed effect enters the fit as
  // quintic and higher terms aliased into the cubic ones: the error grows as
  // the load squared (2e-3 at 0.1 h; the report's load-level study).
  settings.amplitudes = 0.03 * s.amplitudes;
  const CubicFit fit =
    identify_cubic_ice([&](const Eigen::VectorXd &f) { return statics.modal_static_response(f); }, settings);
  expect_agree(s.analytic, fit, 1e-3, "ice");
  EXPECT_NEAR(fit.linear(0, 0) / (s.basis.omega[0] * s.basis.omega[0]), 1., 1e-6);
}

TEST(PlainStep, OverPredictsMode1ByTheMembraneFactor)
{
  // Holding u = 0 makes the axial strain ½w'² pointwise instead of its mean,
  // so b_111 becomes (EA/2) ∫φ'⁴ instead of (EA/2L)(∫φ'²)²: the ratio is
  // L ∫φ'⁴ / (∫φ'²)², here from the analytic mode by independent quadrature.
  CoefficientSetup s("mueller2023-ideal.prm", 1);
  FEStatics statics(*s.beam, s.modes, 1);
  const CubicFit fit = identify_cubic_step([&](const Eigen::VectorXd &q) { return statics.modal_force_plain(q); },
                                           {s.amplitudes, s.omega2()});
  const beamslider_test::ClampedBeam analytic;
  const auto m = analytic.modes(1);
  auto slope   = [&](double x) {
    Eigen::VectorXd p, d;
    m.basis.evaluate(x, p, d);
    return d[0];
  };
  const double I2 = analytic.integrate([&](double x) { return std::pow(slope(x), 2); });
  const double I4 = analytic.integrate([&](double x) { return std::pow(slope(x), 4); });
  const double factor = analytic.L * I4 / (I2 * I2);
  EXPECT_NEAR(fit.cubic_coefficient(0, 0, 0, 0) / s.analytic[0].value, factor, 1e-4 * factor);
  EXPECT_GT(factor, 1.4); // a real over-prediction, not a vacuous match
}

// The b_111 implied by the FE model's own backbone (harmonic balance on the
// full FE model, axial DoFs with inertia, no modal fit) against seed Eq. 3 on
// the FE modes. The two differ by the axial inertia the ROM condenses out
// (of order (ω₁/ω_axial)² ≈ 2e-4: the first axial mode, (1/2L)√(E/ρ) ≈ 19 kHz,
// lies ~70× above f₁) and by what the a⁴ term of the fit does not absorb.
// Measured: 3e-5 (ideal clamp), 3e-4 (elastic supports); 1e-3 is the
// tolerance the issue sets for ICE and condensed STEP.
TEST(FEImplied, B111FromTheFEBackboneAgreesWithAnalytic)
{
  for (const std::string file : {"mueller2023-ideal.prm", "mueller2023.prm"})
    {
      CoefficientSetup s(file, 1);
      const FEImpliedCoefficient r = fe_implied_b111(*s.beam, s.modes);
      std::cout << file << ": FE-implied b_111 / analytic = " << r.b_111 / s.analytic[0].value << " (" << r.n_points
                << " HB points, H = " << r.n_harmonics << ", " << r.seconds << " s)" << std::endl;
      EXPECT_NEAR(r.b_111 / s.analytic[0].value, 1., 1e-3) << file;
    }
}
