// Modal damping for the FE model (doc/physics.md §2–3): the damping matrix
//   C = Σ_{n ≤ N} 2 D ω_n (M φ_n)(M φ_n)ᵀ
// gives every one of the N kept (mass-normalised) modes exactly the ratio D,
// as in the reduced model, and leaves every other mode, bending or axial,
// undamped (φ_mᵀ C φ_m = 0 for m > N since the modes are M-orthogonal). It
// is a rank-N matrix, applied without forming it.
#pragma once

#include "fem/fe_modes.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace beamslider
{
  class ModalDamping
  {
  public:
    ModalDamping(const dealii::SparseMatrix<double> &M, const FEModes &modes, unsigned int n_kept,
                 double damping_ratio);

    // dst = C src.
    void vmult(dealii::Vector<double> &dst, const dealii::Vector<double> &src) const;

    unsigned int rank() const { return coefficients.size(); }
    const std::vector<dealii::Vector<double>> &mass_weighted_modes() const { return M_phi; }
    const std::vector<double> &modal_coefficients() const { return coefficients; } // 2 D ω_n [1/s]

  private:
    std::vector<dealii::Vector<double>> M_phi;
    std::vector<double> coefficients;
  };
} // namespace beamslider
