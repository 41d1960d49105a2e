// Identification of the cubic (and quadratic) modal stiffness coefficients of
// a geometrically nonlinear structure from a black-box model (doc/physics.md §5):
//
//   f_n(q) = Σ_{j≤k} a^(n)_jk q_j q_k + Σ_{j≤k≤l} c^(n)_jkl q_j q_k q_l ,
//
// the nonlinear part of the modal restoring force in mass-normalised modal
// coordinates q [m kg^1/2]; f has units of N kg^-1/2 (= m kg^1/2 / s²). The
// coefficients are stored once per sorted index set (CubicTerm of
// rom_operator.h; c^(n)_jkl is the sum over the permutations of b^(n)_jkl of
// seed Eq. 3). For a flat beam the quadratic coefficients vanish by symmetry
// (w → −w); they are identified anyway so that a report can show they do.
//
// Two procedures, both written against callbacks so the FE code (deal.II) can
// supply the model without this library knowing about it:
//
// - STEP, stiffness evaluation procedure (Muravyov & Rizzi, Comput. Struct. 81,
//   2003; Mignolet et al., J. Sound Vib. 332, 2013): prescribe q in the
//   combinations ±a_j e_j, ±a_j e_j ± a_k e_k, ±(a_j e_j + a_k e_k + a_l e_l),
//   evaluate the modal force, and separate the coefficients exactly by the
//   even/odd parts of these evaluations. "Plain" STEP prescribes transverse
//   displacements only (the membrane cannot relax: over-predicts, doc/physics.md §5);
//   "condensed" STEP solves for the in-plane DOFs at given w in the callback.
//   The algorithm is the same; the callback decides which one it is.
// - ICE, implicit condensation (Hollkamp & Gordon, J. Sound Vib. 318, 2008):
//   apply modal load patterns f̂ (the physical load M Φ f̂), solve the full
//   nonlinear statics, project back q = Φᵀ M x, and fit the polynomial
//   f̂ = K_lin q + quadratic + cubic by least squares.
#pragma once

#include "reduced/rom_operator.h"

#include <Eigen/Dense>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace beamslider
{
  // q [m kg^1/2] ↦ modal restoring force Φᵀ f_int(Φ q) [N kg^-1/2]. Plain STEP:
  // the FE internal force at the prescribed transverse displacement Φ q with
  // the in-plane DOFs held at zero; condensed STEP: the same after a static
  // solve for the in-plane DOFs. It may include the linear part K_lin q if the
  // caller sets StepSettings::linear_stiffness (which is then subtracted).
  using ModalForceFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd &q)>;

  // Modal load f̂ [N kg^-1/2] ↦ static modal response q [m kg^1/2]: the caller
  // applies the physical load M Φ f̂, solves the full nonlinear FE statics for
  // x and returns q = Φᵀ M x. It should throw if its Newton solve fails.
  using ModalStaticSolveFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd &f_hat)>;

  // Quadratic coefficient a^(n)_jk of q_j q_k, stored for j ≤ k, 0-based.
  struct QuadraticTerm
  {
    unsigned int n, j, k;
    double value;
  };

  // What STEP and ICE return. The coefficient lists are complete (every n and
  // every sorted index set, in the order of ReducedOrderModel::analytic_cubic_terms).
  struct CubicFit
  {
    std::vector<CubicTerm> cubic;         // c^(n)_jkl [N kg^-2 m^-2 = 1/(s² m² kg)]
    std::vector<QuadraticTerm> quadratic; // a^(n)_jk  [1/(s² m kg^1/2)]
    // ICE with fit_linear: the fitted linear stiffness (should be ≈ diag ω²);
    // otherwise the linear stiffness that was subtracted (may be empty) [1/s²].
    Eigen::MatrixXd linear;
    Eigen::VectorXd amplitudes;      // a_j used [m kg^1/2]
    unsigned int n_evaluations = 0;  // force evaluations (STEP) or static solves (ICE)
    // ICE: rms of the fit residual over rms of f̂ (0 for an exact model);
    // STEP: 0 (the procedure interpolates, it does not fit).
    double relative_fit_residual = 0;
    // ICE: the largest |q_j| / a_j reached over all load cases (how far into
    // the nonlinear range the fit reached); STEP: 1.
    double max_relative_response = 0;

    unsigned int n_modes() const { return amplitudes.size(); }
    // Look-ups with indices in any order (sorted internally), 0-based.
    double cubic_coefficient(unsigned int n, unsigned int j, unsigned int k, unsigned int l) const;
    double quadratic_coefficient(unsigned int n, unsigned int j, unsigned int k) const;
    double max_abs_quadratic() const;
  };

  // a_j = length_scale / max_x |φ_j(x)|: the modal amplitude that gives a
  // transverse displacement of length_scale (e.g. the thickness h) [m kg^1/2].
  Eigen::VectorXd step_amplitudes(const Eigen::VectorXd &max_abs_phi, double length_scale);

  struct StepSettings
  {
    Eigen::VectorXd amplitudes; // a_j > 0 [m kg^1/2], one per mode (see step_amplitudes)
    // If non-empty (N×N, e.g. diag ω²), K_lin q is subtracted from every force
    // evaluation: the callback then returns the full restoring force.
    Eigen::MatrixXd linear_stiffness;
  };

  // STEP: 2N + 4·N(N−1)/2 + 2·N(N−1)(N−2)/6 evaluations of modal_force.
  // Exact (to round-off) when the model is a cubic polynomial; otherwise the
  // higher-order terms alias into the coefficients by O(a²).
  CubicFit identify_cubic_step(const ModalForceFunction &modal_force, const StepSettings &settings);

  struct IceSettings
  {
    Eigen::VectorXd omega;      // ω_n [rad/s], the linear frequencies of the basis
    Eigen::VectorXd amplitudes; // a_j [m kg^1/2]: load level 1 on mode j is f̂_j = ω_j² a_j,
                                // the load whose *linear* response is a_j
    // Load levels (multiples of ω_j² a_j), each applied with both signs.
    std::vector<double> load_levels = {0.5, 1.0};
    bool pairs   = true; // load cases ±f̂_j ± f̂_k
    bool triples = true; // load cases ±f̂_j ± f̂_k ± f̂_l (all 8 sign patterns)
    bool fit_linear    = true; // false: the linear part is fixed to diag ω²
    bool fit_quadratic = true;
  };

  // ICE: single modes, pairs and triples at every load level and sign, then a
  // least-squares fit per modal equation (columns scaled by a_j). The number of
  // static solves is 2N·L + 4·N(N−1)/2·L + 8·N(N−1)(N−2)/6·L for L levels.
  CubicFit identify_cubic_ice(const ModalStaticSolveFunction &static_solve, const IceSettings &settings);
} // namespace beamslider
