// The reduced model's modal basis taken from the FE model (doc/physics.md §5):
// the N lowest mass-normalised bending modes of the FE beam with
//   γ_n = -∫ ρA φ_n dx - Σ m φ_n(x_p) = rᵀ φ_n  (r the FE base-load vector),
//   K'_jk = ∫ φ_j' φ_k' dx        (Gauss quadrature, exact for the Hermite cubics),
//   k_ax  = (∫dx/EA + 1/k_t)^-1 (k_t the clamping's total axial stiffness; see SupportData),
// and φ_n(x), φ_n'(x) evaluable at any x from per-element Hermite
// coefficients, so the reduced model never needs deal.II or the analytic mode
// formulas at run time.
#pragma once

#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "reduced/modal_basis.h"

#include <Eigen/Dense>

namespace beamslider
{
  // Uses the first n_modes of `modes` (all if 0).
  ModalBasis make_modal_basis(const FEBeam &beam, const FEModes &modes, unsigned int n_modes = 0);

  // The modes as columns of a dense matrix Φ (n_dofs × N).
  Eigen::MatrixXd mode_matrix(const FEModes &modes, unsigned int n_modes);

  // max_x |φ_n(x)| for each mode, sampled at 8 points per element.
  Eigen::VectorXd max_abs_deflection(const FEBeam &beam, const FEModes &modes, unsigned int n_modes);

  // ∫ EA(x) φ'⁴ dx for a mode (Gauss, exact): plain STEP's b_111 is half of
  // it, against (k_ax/2)(∫φ'²)² when the membrane may relax, so plain STEP
  // over-predicts by ∫EAφ'⁴ / (k_ax (∫φ'²)²) (doc/physics.md §5).
  double axial_weighted_slope_fourth_power(const FEBeam &beam, const dealii::Vector<double> &phi);
} // namespace beamslider
