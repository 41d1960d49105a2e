// The averaged description of the held slider (doc/physics.md §12): the
// reduced model with the slider moving with the beam at x_C, its mass m and
// rotary inertia J carried by the beam there, instead of rattling in its
// clearance. The rattling held slider has no periodic orbit to continue (its
// stroboscopic map is chaotic: runs/held_slider_map.h, the evidence in the
// report), but the beam's amplitude it leaves is nearly steady; this smooth
// model is the one whose periodic orbits, unstable ones included, can be
// followed through their turning points in x_C.
//
// Equations, in the N modal coordinates q (unit modal masses, the ROM's
// frequencies ω_n, damping c_n and cubic restoring force f(q)):
//   (I + m φφᵀ + J φ'φ'ᵀ) q̈ + C q̇ + Ω_n² q + f(q) = γ ẅ₀(t) − m φ (ẅ₀(t) + g),
// φ = φ(x_C), φ' = φ'(x_C), γ_n = −ρA∫φ_n dx, ẅ₀ the base acceleration. The
// slider's centre-of-mass offset and the clearance are left out.
//
// The mean horizontal force on the held slider is not defined by this model
// (a slider that sticks can hold itself by friction); the observable given is
// the frictionless one, the slope's share of the force that carries the
// slider, F_x = −m (ẅ₀ + ẅ(x_C) + g) w'(x_C), averaged over the period
// [N, + toward x = L]. Its sign says toward which end the vibration pushes a
// slider that slides without friction.
#pragma once

#include "contact/base_excitation.h"
#include "numerics/periodic_orbits.h"
#include "reduced/rom_operator.h"

#include <string>
#include <vector>

namespace beamslider
{
  class AttachedSliderModel
  {
  public:
    // The ROM must outlive the model. `thickness` h [m] scales the amplitude.
    AttachedSliderModel(const ReducedOrderModel &rom, double slider_mass, double slider_inertia, double gravity,
                        const BaseExcitation &base, double thickness);

    unsigned int n_unknowns() const { return 2 * rom_.n_modes(); }
    // RK4 steps per excitation period: at least 400 and ω_N Δt ≤ 0.5.
    unsigned int steps_per_period() const { return steps_; }

    // Φ(y; x_C/L) over one excitation period from phase zero, y = (q, q̇);
    // observables in the order of observable_names().
    PeriodMapValue operator()(const Eigen::VectorXd &y, double x_over_L) const;
    static std::vector<std::string> observable_names(); // amplitude_over_h, mean_fx_N

    // Typical sizes of y around a state: each block its largest entry.
    Eigen::VectorXd scale(const Eigen::VectorXd &y) const;

    // The state of the linear steady response at x_C/L (the nonlinearity
    // and gravity left out), a start for shooting on the low branch.
    Eigen::VectorXd linear_response(double x_over_L) const;

  private:
    const ReducedOrderModel &rom_;
    double mass_, inertia_, gravity_, thickness_;
    BaseExcitation base_;
    unsigned int steps_;
  };
} // namespace beamslider
