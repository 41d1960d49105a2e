// Modal coefficients of the solid strip (doc/physics.md §11): the reduced
// internal force of the SVK solid on N of its modes Φ = [φ_1 … φ_N],
//
//   Φᵀ f(Φ q) = K q + Σ_{j≤k} a^(n)_jk q_j q_k + Σ_{j≤k≤l} c^(n)_jkl q_j q_k q_l ,
//
// two ways:
//
//  - exactly, from the element integrals of the cubic law (the reduced SVK
//    polynomial): with G_j = ∇φ_j, e_j = sym G_j, H_jk = sym(G_jᵀ G_k) and
//    C:X = λ tr(X) I + 2μ X, the Green–Lagrange strain of u = Φq is
//    E = Σ q_j e_j + ½ Σ q_j q_k H_jk and its variation along φ_n is
//    e_n + Σ q_l H_ln, so
//      K_nj        = ∫ e_n : C : e_j dV,
//      q_j q_k:      ∫ ½ H_jk : C : e_n + (C : e_j) : H_kn dV,
//      q_j q_k q_l:  ∫ ½ (C : H_jk) : H_ln dV,
//    summed over the permutations of each sorted index set;
//  - by the black-box procedures of reduced/cubic_fit.h on the solid: plain
//    STEP (u = Φ q prescribed, every other DoF held: Φᵀ f(Φ q)) and ICE (the
//    modal load M Φ f̂, the full nonlinear statics solved by Newton with load
//    stepping and a direct parallel solve (MUMPS), q = Φᵀ M u).
//
// STEP on an exactly cubic model is exact, so STEP against the polynomial is
// a check of both. The coefficients are in the units of cubic_fit.h
// (mass-normalised modes).
#pragma once

#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "fem/solid_statics.h"
#include "reduced/cubic_fit.h"

#include <Eigen/Dense>


namespace beamslider
{
  template <int dim>
  class SolidModalCoefficients
  {
  public:
    // Φ: the bending modes of `modes` (modes.bending), the first n_modes.
    SolidModalCoefficients(const SolidModel<dim> &model, const SolidModes &modes, unsigned int n_modes);
    // Φ: the modes modes.all[i] for i in `indices` (0-based, any shapes, in
    // that order): torsion or lateral modes beside the bending ones.
    SolidModalCoefficients(const SolidModel<dim> &model, const SolidModes &modes,
                           const std::vector<unsigned int> &indices);

    // The reduced SVK polynomial (fit.linear = K, fit.quadratic, fit.cubic).
    CubicFit exact_polynomial() const;
    // q ↦ Φᵀ f(Φ q) [N kg^-1/2] (plain STEP's callback; includes K q).
    Eigen::VectorXd modal_force(const Eigen::VectorXd &q) const;
    // Relaxed STEP's callback (the solid's condensed STEP): q ↦ λ = Φᵀ f(u)
    // with u = Φ q + v, every DoF outside the kept modes relaxed: Φᵀ M v = 0
    // and f(u) = M Φ λ, by Newton on the bordered system
    //   [K_t  −MΦ] [dv]   [M Φ λ − f(u)]
    //   [(MΦ)ᵀ  0] [dλ] = [     0      ]
    // through its N × N Schur complement on a MUMPS factorisation of K_t.
    // Throws SolidStaticSolveError if Newton does not converge.
    Eigen::VectorXd modal_force_relaxed(const Eigen::VectorXd &q);
    // f̂ ↦ q = Φᵀ M u with f(u) = M Φ f̂ (ICE's callback).
    Eigen::VectorXd modal_static_response(const Eigen::VectorXd &f_hat);
    // Its two halves: the modal load M Φ f̂ [N] (zero on constrained DoFs),
    // and the modal coordinates Φᵀ M u [m kg^1/2] of a displacement u
    // (owned entries; its constrained entries carry no mass).
    dealii::PETScWrappers::MPI::Vector modal_load(const Eigen::VectorXd &f_hat) const;
    Eigen::VectorXd modal_coordinates(const dealii::PETScWrappers::MPI::Vector &u) const;

    // a_j = length / max |φ_j|: the amplitude of a peak displacement `length`.
    Eigen::VectorXd amplitudes(double length) const;
    Eigen::VectorXd omega() const;
    unsigned int n_static_solves() const { return statics.n_static_solves(); }
    unsigned int n_linear_solves() const { return statics.n_linear_solves(); }
    unsigned int n_factorisations() const { return statics.n_factorisations(); }

  private:
    const SolidModel<dim> &model;
    std::vector<dealii::PETScWrappers::MPI::Vector> Phi; // owned entries
    std::vector<const dealii::PETScWrappers::MPI::Vector *> Phi_ghosted;
    std::vector<double> omegas;
    dealii::PETScWrappers::MPI::SparseMatrix M;
    SolidStatics<dim> statics;
    KeptFactorisation relaxed_tangent{model.communicator()};
    struct RelaxedStep; // modal_force_relaxed() as numerics/newton.h's problem
  };

  // The coefficients of `coefficients`' modes by a method, at the load or
  // amplitude the beam uses too (doc/physics.md §11):
  //   exact  the reduced SVK polynomial;
  //   step   plain STEP with amplitudes of one thickness (exact for the cubic
  //          law at any size);
  //   step-relaxed  STEP with the other DoFs relaxed, amplitudes of 0.03 h
  //          (not exactly cubic: the other bending modes respond too);
  //   ice    ICE at load level 1 = a linear response of 0.03 h.
  // Throws std::invalid_argument for another method.
  template <int dim>
  CubicFit solid_cubic_fit(SolidModalCoefficients<dim> &coefficients, const std::string &method, double thickness);
} // namespace beamslider
