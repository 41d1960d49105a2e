// The exact period of the undamped Duffing oscillator, shared by the
// backbone tests (FE against the single-mode model, the hinged beam).
#pragma once

#include <cmath>

namespace beamslider::testing
{
  // Period of q̈ + ω² q + b q³ = 0 started from rest at q0 (q = q0 sin φ):
  // T = 4 ∫₀^{π/2} dφ / √(ω² + (b/2) q0² (1 + sin²φ)), by composite Simpson
  // on n intervals (the integrand is smooth and periodic: n = 2000 is exact
  // to round-off).
  inline double duffing_period(const double omega, const double b, const double q0, const unsigned int n = 2000)
  {
    double sum = 0;
    for (unsigned int i = 0; i <= n; ++i)
      {
        const double phi = 0.5 * M_PI * i / n, s = std::sin(phi);
        const double g   = 1. / std::sqrt(omega * omega + 0.5 * b * q0 * q0 * (1 + s * s));
        sum += (i == 0 || i == n ? 1. : (i % 2 ? 4. : 2.)) * g;
      }
    return 4. * sum * (0.5 * M_PI / n) / 3.;
  }
} // namespace beamslider::testing
