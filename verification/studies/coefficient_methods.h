// The four sources of the reduced model's cubic coefficients (doc/physics.md
// §5), run on one FE beam and its modes:
//   analytic        seed Eq. 3 with k_ax, integrals on the FE mode shapes
//   step            STEP, transverse displacements only (axial DoFs at zero)
//   step-condensed  STEP with the axial DoFs solved for at each prescribed w
//   ice             implicit condensation: full nonlinear FE statics
// Used by `beamslider coefficients` and the verification report.
#pragma once

#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "reduced/cubic_fit.h"
#include "reduced/modal_basis.h"

#include <string>
#include <vector>

namespace beamslider
{
  struct CoefficientResult
  {
    std::string method;
    CubicFit fit;                  // for "analytic": cubic terms only, n_evaluations = 0
    unsigned int n_static_solves = 0; // linear (STEP-condensed) or Newton (ICE) solves of the FE statics
    unsigned int n_linear_solves = 0; // sparse factorisations + solves
    double seconds = 0;
  };

  // `amplitude_over_h`: the STEP displacement amplitude, or for ICE the
  // linear displacement of the load level 1, as a multiple of the thickness.
  CoefficientResult compute_coefficients(const FEBeam &beam, const FEModes &modes, const ModalBasis &basis,
                                         const std::string &method, double amplitude_over_h);

  const std::vector<std::string> &coefficient_methods();

  // The b_111 the FE model itself implies: harmonic balance on the full FE
  // model (fem/fe_conservative_system, axial DoFs and their inertia kept,
  // harmonics 0…H) along the mode-1 backbone at ŵ_{L/2}/h = 0.05 … 0.3, a
  // least-squares fit of (ω/ω₁)² − 1 = c a² + d a⁴ (a = ŵ/h), and Eq. 4
  // (ω² = ω₁² + ¾ b_111 q̂², ŵ = |φ₁(L/2)| q̂) turned around:
  //   b_111 = 4 c φ₁(L/2)² ω₁² / (3 h²).
  // The a⁴ term absorbs what a single mode does not have (the other modes
  // driven by the cubic coupling, higher harmonics), so c is the single-mode
  // coefficient. No STEP or ICE fit: an independent route to the same number.
  struct FEImpliedCoefficient
  {
    double b_111 = 0;          // [1/(s² m² kg)]
    double c = 0, d = 0;       // fit coefficients of (ω/ω₁)² − 1 [-]
    double omega_1 = 0;        // FE linear frequency [rad/s]
    unsigned int n_points = 0; // backbone points fitted
    unsigned int n_harmonics = 0;
    double seconds = 0;
  };
  FEImpliedCoefficient fe_implied_b111(const FEBeam &beam, const FEModes &modes, unsigned int n_harmonics = 3);
} // namespace beamslider
