// The reduced-order model (seed Eqs. 1–3, doc/physics.md §5): the second
// implementation of the beam's second-order system, the FE model being the
// first. In modal coordinates q (mass-normalised modes)
//
//   q'' + 2 D ω_n q_n' + ω_n² q_n + f_n(q) = γ_n ẅ0 ,
//   f(q) = (k_ax/2) (qᵀ K' q) K' q                      (O(N²) per evaluation)
//
// which equals Σ b^(n)_jkl q_j q_k q_l with b^(n)_jkl = (k_ax/2) K'_jk K'_ln.
// A full cubic tensor (from STEP or ICE) can replace the analytic form.
#pragma once

#include "reduced/modal_basis.h"

#include <Eigen/Dense>

#include <optional>
#include <vector>

namespace beamslider
{
  // A symmetric cubic polynomial f_n(q) = Σ_{j≤k≤l} c^(n)_jkl q_j q_k q_l,
  // each coefficient stored once for sorted j ≤ k ≤ l (the sum over the
  // permutations of (j,k,l) of b^(n)_jkl). Indices are 0-based here; files and
  // reports use 1-based mode numbers.
  struct CubicTerm
  {
    unsigned int n, j, k, l;
    double value;
  };

  class ReducedOrderModel
  {
  public:
    ReducedOrderModel(ModalBasis basis, double damping_ratio, bool geometric_nonlinearity = true);

    // Replace the analytic restoring force by an explicit list of cubic terms.
    void set_cubic_terms(std::vector<CubicTerm> terms);

    unsigned int n_modes() const { return basis_.n_modes(); }
    const ModalBasis &basis() const { return basis_; }
    double damping_ratio() const { return damping_ratio_; }

    // Modal damping acts on the first n_damped modes only; the others ring
    // undamped. The FE's modal damping acts on the scene's N modes of a mesh
    // with many more, so a ROM with every mode of that mesh damps the same
    // set only with this (the error ladder's "damped set" rung). Default and
    // n_damped ≥ N: every kept mode is damped.
    void set_damped_modes(unsigned int n_damped);
    unsigned int n_damped_modes() const { return n_damped_; }
    // c_n = 2 D ω_n for a damped mode, 0 otherwise [1/s].
    const Eigen::VectorXd &damping_coefficients() const { return damping_; }

    // Whether f is the analytic membrane form (qᵀK'q) K'q (true unless cubic
    // terms replaced it); the implicit step exploits its structure.
    bool has_membrane_form() const { return !terms_.has_value(); }
    bool is_nonlinear() const { return nonlinear_; }

    // Nonlinear part f(q) of the modal restoring force [N kg^-1/2 = m kg^1/2/s²].
    Eigen::VectorXd nonlinear_force(const Eigen::VectorXd &q) const;
    // The membrane form's axial force N = ½ k_ax qᵀK'q [N], with K'q written
    // into stretch_q (a vector of N entries): f(q) = N K'q.
    double membrane_axial_force(const Eigen::VectorXd &q, Eigen::VectorXd &stretch_q) const;
    // f += scale · f(q) without allocating (scratch: a vector of N entries).
    void add_nonlinear_force(const Eigen::VectorXd &q, double scale, Eigen::VectorXd &f,
                             Eigen::VectorXd &scratch) const;
    // ∂f/∂q.
    Eigen::MatrixXd nonlinear_tangent(const Eigen::VectorXd &q) const;
    // Linear part: ω_n² q_n + c_n v_n.
    Eigen::VectorXd linear_force(const Eigen::VectorXd &q, const Eigen::VectorXd &v) const;

    // The analytic tensor in the sorted storage above (for reports and
    // comparisons with STEP/ICE).
    std::vector<CubicTerm> analytic_cubic_terms() const;
    // The tensor f uses: the one set by set_cubic_terms, else the analytic one.
    std::vector<CubicTerm> cubic_terms() const { return terms_ ? *terms_ : analytic_cubic_terms(); }

  private:
    ModalBasis basis_;
    double damping_ratio_;
    unsigned int n_damped_;
    Eigen::VectorXd damping_; // c_n [1/s]
    bool nonlinear_;
    std::optional<std::vector<CubicTerm>> terms_;
  };
} // namespace beamslider
