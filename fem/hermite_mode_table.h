// Modes along a beam line as cubic Hermite polynomials per interval, from
// the values and slopes (w, θ = w') at the interval ends: φ_n(x) and
// φ_n'(x) anywhere in [0, L]. The FE beam's modes are exactly of this form
// (its elements are Hermite cubics); a solid's modes are sampled into it
// (fem/solid_modal_basis.h). The reduced model's basis is built on it.
#pragma once

#include "reduced/modal_basis.h"

#include <Eigen/Dense>

#include <memory>
#include <vector>

namespace beamslider
{
  struct HermiteModeTable
  {
    double length           = 0;
    unsigned int n_intervals = 0, n_modes = 0;
    std::vector<double> vertices;     // x of the interval ends, increasing, from 0 to L [m]
    std::vector<double> coefficients; // [interval][mode][w0, θ0, w1, θ1]

    // φ_n(x), φ_n'(x) of every mode; throws std::out_of_range outside [0, L].
    void evaluate(double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) const;
    // w(x) = Σ φ_n(x) q_n and w'(x): the interval's nodal values of w and θ
    // for these coordinates, then the Hermite shape functions once.
    void displacement(double x, const Eigen::VectorXd &q, double &w, double &dw) const;

  private:
    // The interval holding x; throws std::out_of_range outside [0, L].
    unsigned int interval(double x) const;
  };

  // The reduced model's basis on the table: ω, γ as given, K'_jk = ∫ φ_j' φ_k' dx
  // (3 Gauss points per interval: exact for the cubics), φ and φ' from the table.
  ModalBasis modal_basis_from_table(std::shared_ptr<const HermiteModeTable> table, const Eigen::VectorXd &omega,
                                    const Eigen::VectorXd &gamma, double membrane_stiffness);
} // namespace beamslider
