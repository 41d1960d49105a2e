// The four sources of the reduced model's cubic coefficients (DESIGN.md
// §1.2), run on one FE beam and its modes:
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
} // namespace beamslider
