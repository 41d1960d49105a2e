// Analytic natural frequencies of a uniform Euler–Bernoulli beam with w = 0 at
// both ends and equal rotational springs k_r there (the ideal clamp is
// k_r → ∞, the pinned beam k_r = 0). Independent of the FE code: the tests
// and the verification report compare the FE frequencies against these.
//
// With ξ = x - L/2 the modes are symmetric, W = A cos βξ + C cosh βξ, or
// antisymmetric, W = B sin βξ + D sinh βξ. The conditions at ξ = L/2,
// W = 0 and EI W'' + k_r W' = 0, give with a = βL/2 (divided by cosh a to keep
// them bounded):
//   symmetric:      2 EI β² cos a + k_r β (cos a tanh a + sin a) = 0
//   antisymmetric:  2 EI β² sin a tanh a + k_r β (sin a - tanh a cos a) = 0
// For k_r → ∞ these are the two factors of cos βL cosh βL = 1.
#pragma once

#include <limits>
#include <vector>

namespace beamslider::analytic
{
  // The n lowest roots β_k L of cos βL cosh βL = 1 (clamped–clamped).
  std::vector<double> clamped_clamped_beta_L(unsigned int n);

  // The n lowest β_k L for rotational springs k_r [N m/rad] at both ends of a
  // beam with bending stiffness EI [N m²] and length L [m]
  // (k_r = infinity: the ideal clamp).
  std::vector<double> spring_supported_beta_L(unsigned int n, double EI, double L, double k_r);

  // ω = (βL)² / L² · sqrt(EI/ρA) [rad/s].
  double frequency_from_beta_L(double beta_L, double EI, double rhoA, double L);
} // namespace beamslider::analytic
