// The resonance curve of seed §4.2 (dashed grey in seed Figs. 10b–13b): the
// amplitude ŵ_{L/2} at which the single-mode natural frequency with the
// slider, seed Eq. 5,
//
//   ω̃₁²(ŵ, x_C) = (ω₁² + ¾ b₁₁₁ q̂²) / (1 + m φ₁(x_C)² + J φ₁'(x_C)²),
//   ŵ = |φ₁(L/2)| q̂,
//
// equals the excitation frequency Ω = 2π f_ex. Solved for q̂:
//
//   q̂² = (Ω² (1 + m φ₁² + J φ₁'²) − ω₁²) / (¾ b₁₁₁),
//
// which has no real root (no resonance at any amplitude) where the slider's
// added inertia already puts ω̃₁(0, x_C) above Ω (stiffening only raises it).
// m is the slider mass, J its rotary inertia (doc/physics.md §5; the window's
// offset d is not part of Eq. 5).
#pragma once

#include "reduced/rom_operator.h"

namespace beamslider
{
  struct ResonanceCurveData
  {
    double omega_1  = 0; // ω₁ of the bare beam [rad/s]
    double b_111    = 0; // cubic coefficient of mode 1 [1/(s² m² kg)]
    double phi_1_centre = 0; // φ₁(L/2) [kg^-1/2]
    double slider_mass = 0, slider_inertia = 0; // [kg], [kg m²]
    double thickness = 0; // h [m]

    // From a ROM (mode 1 of its basis, b₁₁₁ of its analytic tensor).
    static ResonanceCurveData from_model(const ReducedOrderModel &rom, double slider_mass, double slider_inertia,
                                         double thickness);
  };

  // ŵ_{L/2}/h on the resonance curve at x_C for excitation frequency f_ex
  // [Hz], or NaN where Eq. 5 has no resonance at that position.
  double resonance_amplitude_over_h(const ReducedOrderModel &rom, const ResonanceCurveData &data, double x_C,
                                    double excitation_hz);
} // namespace beamslider
