// The reduced model's basis on a Hermite mode table (reduced/hermite_mode_table.h):
// the FE beam's modes (fem/fe_modal_basis.h) and a solid's sampled modes
// (fem/solid_modal_basis.h) both end here.
#pragma once

#include "reduced/hermite_mode_table.h"
#include "reduced/modal_basis.h"

#include <memory>

namespace beamslider
{
  // ω, γ as given, K'_jk = ∫ φ_j' φ_k' dx (3 Gauss points per interval:
  // exact for the cubics), φ and φ' from the table, which the basis keeps.
  ModalBasis modal_basis_from_table(std::shared_ptr<const HermiteModeTable> table, const Eigen::VectorXd &omega,
                                    const Eigen::VectorXd &gamma, double membrane_stiffness);
} // namespace beamslider
