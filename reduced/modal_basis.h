// The modal basis of the reduced-order model: the N lowest mass-normalised
// bending modes of the beam, and the integrals of doc/physics.md §5 built from
// them. It is filled from the FE model (fem/fe_modal_basis) or, in tests, from
// analytic mode shapes; the reduced model never needs the analytic formulas.
//
// Units: with mass-normalised modes (∫ ρA φ_m φ_n dx = δ_mn) φ has units of
// kg^-1/2, modal coordinates q of m·kg^1/2.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <memory>

namespace beamslider
{
  struct HermiteModeTable;

  struct ModalBasis
  {
    double length = 0;            // L [m]
    Eigen::VectorXd omega;        // ω_n, linear natural frequencies [rad/s]
    Eigen::VectorXd gamma;        // γ_n = -ρA ∫ φ_n dx [kg^1/2]
    Eigen::MatrixXd stretch;      // K'_jk = ∫ φ_j' φ_k' dx [1/(kg m)]
    double membrane_stiffness = 0; // k_ax = (L/(EA) + 1/k_t)^-1 [N/m] (SupportData::membrane_stiffness)

    // φ_n(x) and φ_n'(x) for all n at one x in [0, L].
    std::function<void(double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi)> evaluate;
    // Optional: w(x) = Σ φ_n(x) q_n and w'(x) for coordinates q without
    // forming the φ_n (a mode table sums the interval's nodal values of q
    // first: 4N products instead of 10N). Empty: evaluate and two dot products.
    std::function<void(double x, const Eigen::VectorXd &q, double &w, double &dw)> displacement;
    // Optional: the table behind evaluate and displacement when the modes
    // are cubic Hermite polynomials per interval (reduced/hermite_mode_table.h;
    // every basis built from an FE beam or a solid). The explicit reduced
    // model's contact step reads it directly (RomBeamSystem::explicit_modal_form).
    std::shared_ptr<const HermiteModeTable> table;

    unsigned int n_modes() const { return omega.size(); }
  };
} // namespace beamslider
