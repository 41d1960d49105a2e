// Nonlinear statics of the FE beam (FEStatics::load_path) against an
// independent solution of the same von Kármán beam: the clamped–clamped beam
// under a uniform load q with immovable ends,
//
//   EI w'''' − N w'' = q,   w = w' = 0 at both ends,   N = EA/(2L) ∫₀ᴸ w'² dx,
//
// solved in closed form for given N (hyperbolic functions) and for N by
// bisection on the scalar compatibility equation. Nothing here uses the FE
// code's assembly, quadrature or Newton solver.
#include "fem/fe_beam.h"
#include "fem/fe_statics.h"
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace beamslider;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  // The von Kármán clamped–clamped beam under a uniform load q [N/m] (in +w):
  // mid-span deflection [m]. With s = x − L/2 and k² = N/EI the symmetric
  // solution is w = A cosh(ks) + C − q s²/(2N), where w'(±L/2) = 0 gives
  // A = qL / (2 N k sinh(kL/2)) and w(±L/2) = 0 gives C.
  struct ClampedBeamUnderUniformLoad
  {
    long double EI, EA, L;

    long double mid_deflection(const long double q) const { return solve(q).second; }

    // (N, w(L/2)) for load q. With z = kL/2 and a = L/2 the mid-span
    // deflection A + C is  q a⁴/EI · (½ − tanh(z/2)/z) / z²,  a form without
    // the cancellation of A and C at small z.
    std::pair<long double, long double> solve(const long double q) const
    {
      // g(N) = N − EA/(2L) ∫ w'² is negative for N → 0 and grows with N.
      long double lo = 1e-20L * EA, hi = EA;
      for (int i = 0; i < 200; ++i)
        {
          const long double mid = std::sqrt(lo * hi);
          (mid - EA / (2 * L) * slope_integral(q, mid) < 0 ? lo : hi) = mid;
        }
      const long double N = std::sqrt(lo * hi), a = L / 2, z = a * std::sqrt(N / EI);
      return {N, q * a * a * a * a / EI * (0.5L - std::tanh(z / 2) / z) / (z * z)};
    }

    // z = kL/2 at load q: the measure of the membrane force against bending.
    long double z(const long double q) const { return L / 2 * std::sqrt(solve(q).first / EI); }

    // ∫_{−L/2}^{L/2} w'² ds for w' = A k sinh(ks) − (q/N) s, in closed form.
    long double slope_integral(const long double q, const long double N) const
    {
      const long double k = std::sqrt(N / EI), a = L / 2, A = q * L / (2 * N * k * std::sinh(k * a)), p = q / N;
      const long double hyperbolic = A * A * k * k * (std::sinh(k * L) / (2 * k) - a);
      const long double mixed      = 4 * A * p * (a * std::cosh(k * a) - std::sinh(k * a) / k);
      return hyperbolic - mixed + p * p * L * L * L / 12;
    }
  };
} // namespace

// The closed form itself, in the two limits it must reach: the linear
// clamped beam qL⁴/(384 EI) at small load, and the membrane (string) limit
// w³ ∝ q at large load, where N ≫ EI/L² and bending is a boundary layer.
TEST(ClampedBeamStatics, IndependentSolutionHasTheLinearAndMembraneLimits)
{
  const ClampedBeamUnderUniformLoad b{0.25L, 3e6L, 0.14L};
  // Small load: the expansion of the closed form in z = kL/2,
  // w_mid = qL⁴/(384 EI) (1 − z²/10 + 17 z⁴/1680 − …).
  const long double q_small = 4; // w ≈ h/60: z ≈ 0.04
  const long double z = b.z(q_small), w_linear = q_small * std::pow(b.L, 4) / (384 * b.EI);
  ASSERT_GT(z, 0.01);
  ASSERT_LT(z, 0.1);
  EXPECT_NEAR(double(b.mid_deflection(q_small) / w_linear), double(1 - z * z / 10 + 17 * z * z * z * z / 1680), 1e-9);
  // Membrane: N w'' = −q with N = EA/(2L)∫w'² gives w_mid = (3 q L⁴ / (64 EA))^(1/3).
  const long double q_large = 3e7; // N ≈ 0.65 EA: kL ≈ 390
  const long double membrane = std::cbrt(3 * q_large * std::pow(b.L, 4) / (64 * b.EA));
  EXPECT_NEAR(double(b.mid_deflection(q_large) / membrane), 1., 0.02);
}

// The FE load path on the ideal-clamp mueller2023 strip, up to a mid-span
// deflection of 4 h (where N is ~60 times the linear buckling scale EI/L²),
// within 1e-4 of the independent solution at every load step.
TEST(ClampedBeamStatics, FELoadPathMatchesTheIndependentSolutionUpToFourThicknesses)
{
  const Scene scene = read_scene(scene_dir + "mueller2023-ideal.prm");
  const FEBeam beam(scene);
  const BeamData &d = scene.beam;
  const ClampedBeamUnderUniformLoad exact{d.bending_stiffness(), d.axial_stiffness(), d.length};

  // The load that bends the strip to 4 h by the independent solution.
  long double lo = 1, hi = 1e5;
  for (int i = 0; i < 100; ++i)
    {
      const long double mid = std::sqrt(lo * hi);
      (-exact.mid_deflection(-mid) < 4 * d.thickness ? lo : hi) = mid;
    }
  const double q_4h = double(lo);

  dealii::Vector<double> F;
  beam.assemble_line_load(-q_4h, F);
  FEStatics statics(beam);
  const unsigned int n_steps = 8;
  const auto path = statics.load_path(F, n_steps);
  ASSERT_EQ(path.size(), n_steps);
  double largest_error = 0;
  for (const auto &step : path)
    {
      const double q   = -step.load_factor * q_4h;
      const double w   = beam.deflection(step.x, 0.5 * d.length);
      const double ref = double(exact.mid_deflection(q));
      EXPECT_NEAR(w / ref, 1., 1e-4) << "q = " << q << " N/m, w_ref = " << ref / d.thickness << " h";
      largest_error = std::max(largest_error, std::abs(w / ref - 1));
    }
  std::cout << "32 elements, load to " << q_4h << " N/m: largest relative error of w_mid " << largest_error << "\n";
  EXPECT_NEAR(beam.deflection(path.back().x, 0.5 * d.length) / d.thickness, -4., 4e-4);
}

// Every mesh from 8 to 512 elements: the load path to about 2 h converges
// (Newton's residual test allows for the round-off floor that grows as
// ~Δx⁻³·⁵ against the load: fine meshes stalled at 5e-11 > 1e-11 with 56 and
// more elements) and the mid-span deflection converges with the mesh, the
// change from one mesh to the next shrinking until it reaches round-off.
TEST(ClampedBeamStatics, LoadPathConvergesOnEveryMeshAndTheDeflectionWithIt)
{
  const std::string path = scene_dir + "mueller2023-ideal.prm";
  const BeamData d       = read_scene(path).beam;
  const ClampedBeamUnderUniformLoad exact{d.bending_stiffness(), d.axial_stiffness(), d.length};
  const double q = 2000; // N/m downward: w_mid ≈ 2 h, N well above EI/L²
  const double w_exact = double(exact.mid_deflection(-q));

  std::vector<double> w;
  for (const unsigned int n : {8u, 16u, 32u, 64u, 128u, 256u, 512u})
    {
      const Scene scene = read_scene(path, {"Discretisation/Number of elements=" + std::to_string(n)});
      const FEBeam beam(scene);
      ASSERT_EQ(beam.n_elements(), n);
      dealii::Vector<double> F;
      beam.assemble_line_load(-q, F);
      FEStatics statics(beam);
      std::vector<FEStatics::LoadStep> steps;
      ASSERT_NO_THROW(steps = statics.load_path(F, 2)) << n << " elements";
      ASSERT_EQ(steps.size(), 2u);
      w.push_back(beam.deflection(steps.back().x, 0.5 * d.length));
      std::cout << n << " elements: w_mid / h = " << w.back() / d.thickness << ", relative to the closed form "
                << w.back() / w_exact - 1 << ", " << statics.n_linear_solves() << " Newton iterations\n";
      EXPECT_NEAR(w.back() / w_exact, 1., 1e-2) << n << " elements";
    }
  // Measured: the error against the closed form falls 11–16 times per
  // halving of Δx (2e-3 at 8 elements, 5e-9 at 256), then round-off.
  for (std::size_t k = 1; k < w.size(); ++k)
    {
      const double error = std::abs(w[k] / w_exact - 1), before = std::abs(w[k - 1] / w_exact - 1);
      EXPECT_LT(error, std::max(0.25 * before, 1e-8)) << "mesh " << k;
      if (k >= 2)
        {
          const double change = std::abs(w[k] - w[k - 1]), previous = std::abs(w[k - 1] - w[k - 2]);
          EXPECT_LT(change, std::max(0.5 * previous, 1e-8 * std::abs(w_exact))) << "mesh " << k;
        }
    }
}
