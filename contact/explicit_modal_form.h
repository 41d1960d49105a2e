// The explicit reduced model as the Moreau step sees it when it takes the
// model's whole step itself (MoreauStepper, "the explicit modal step"):
//
//   u_free = u_B + Δt (−c ∘ u_B − ω² ∘ q_M − N K'q_M + γ ẅ0(t_M)),
//   N = ½ k_ax q_Mᵀ K' q_M,   S = I,
//   w(x) = Σ_n φ_n(x) q_n with φ_n cubic Hermite on each interval of a table.
//
// The general step asks a BeamSystem for each of these through virtual
// calls, std::function and dynamic Eigen products, which cost more than
// their arithmetic at N = 5–10 modes; with the data in hand the step does
// the same physics in a few tight passes (doc/performance.md). Plain data,
// owned by the model that hands it out (RomBeamSystem).
#pragma once

#include "contact/base_excitation.h"
#include "scene/scene.h"

namespace beamslider
{
  struct ExplicitModalForm
  {
    unsigned int n_modes = 0;
    const double *omega_squared = nullptr; // ω_n² [1/s²]
    const double *damping       = nullptr; // c_n = 2 D ω_n, or 0 for an undamped mode [1/s]
    const double *gamma         = nullptr; // γ_n [kg^1/2]
    const double *stretch       = nullptr; // K' (n × n, column-major) [1/(kg m)]
    double membrane_stiffness   = 0;       // k_ax [N/m]; 0 for a linear model
    BaseExcitation excitation;             // the base acceleration of the load γ ẅ0
    const ThicknessProfile *thickness = nullptr; // h(x) [m]
    // The modes on the table: interval ends [m] (n_intervals + 1, increasing
    // from 0 to L) and, per interval and mode, the nodal values (w0, θ0, w1, θ1).
    unsigned int n_intervals   = 0;
    const double *vertices     = nullptr;
    const double *coefficients = nullptr;
  };
} // namespace beamslider
