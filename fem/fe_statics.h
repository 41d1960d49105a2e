// Nonlinear statics of the FE beam, and the three ways the reduced model's
// cubic coefficients are obtained from it (doc/physics.md §5):
//
//  - plain STEP: prescribe w = Φ q with the axial DoFs held at zero and
//    return Φᵀ f(Φ q). The membrane cannot relax, so the axial strain is
//    ½ w'² pointwise instead of its mean: the coefficients are over-predicted.
//  - condensed STEP: at the prescribed w solve the axial equilibrium for u
//    (linear in u for given w: one sparse solve), then return Φᵀ f(x).
//  - ICE: apply the load M Φ f̂, solve f(x) = M Φ f̂ by Newton's method with
//    load stepping, and return q = Φᵀ M x.
//
// Newton: tangent K_t(x) from FEBeam, sparse direct solves (UMFPACK). A
// Newton solve that does not converge is cut back in load; below a minimum
// load increment it throws a StaticSolveError that says at which load level
// and with which residual it stopped.
#pragma once

#include "fem/fe_beam.h"
#include "fem/fe_modes.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Dense>

#include <functional>
#include <stdexcept>

namespace beamslider
{
  class StaticSolveError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  struct NewtonSettings
  {
    double relative_tolerance  = 1e-11; // on ‖residual‖ / ‖load‖
    // ... or below round_off_factor × ε ‖|K||x| + |load|‖, the residual's
    // round-off floor, once the residual has stalled there (fine meshes:
    // fe_statics.cc).
    double round_off_factor    = 1;
    unsigned int max_iterations = 25;   // per load step
    double initial_load_step   = 1.0;   // fraction of the full load
    double min_load_step       = 1e-4;
  };

  class FEStatics
  {
  public:
    // The first n_modes of `modes` form Φ.
    FEStatics(const FEBeam &beam, const FEModes &modes, unsigned int n_modes, NewtonSettings settings = {});
    // Without a modal basis: for solve() and load_path() alone.
    explicit FEStatics(const FEBeam &beam, NewtonSettings settings = {});

    // STEP callbacks: q [m kg^1/2] ↦ Φᵀ f(x) [N kg^-1/2], the full restoring
    // force including its linear part diag(ω²) q.
    Eigen::VectorXd modal_force_plain(const Eigen::VectorXd &q);
    Eigen::VectorXd modal_force_condensed(const Eigen::VectorXd &q);
    // ICE callback: f̂ [N kg^-1/2] ↦ q = Φᵀ M x [m kg^1/2].
    Eigen::VectorXd modal_static_response(const Eigen::VectorXd &f_hat);
    // Its two halves: the modal load M Φ f̂ [N] (zero on the supports' DoFs),
    // and the modal coordinates Φᵀ M x [m kg^1/2] of a displacement x.
    dealii::Vector<double> modal_load(const Eigen::VectorXd &f_hat) const;
    Eigen::VectorXd modal_coordinates(const dealii::Vector<double> &x) const;

    // Solves f(x) = F for x (starting from x, which is overwritten), with
    // load stepping from F_start (x's equilibrium load; null: zero) to F.
    // Returns the number of Newton iterations.
    unsigned int solve(const dealii::Vector<double> &F, dealii::Vector<double> &x,
                       const dealii::Vector<double> *F_start = nullptr);

    // One equilibrium of a load path.
    struct LoadStep
    {
      double load_factor;              // λ: the load is λ F
      dealii::Vector<double> x;        // the displacement [m, rad]
      unsigned int newton_iterations;  // to reach it from the previous step
    };
    // The equilibria under λ_k F, λ_k = k / n_steps, k = 1 … n_steps: the
    // full-order static solution a ROM is checked against. Each step's Newton
    // solve starts from the previous equilibrium (and cuts its increment
    // back as solve() does); a step that fails throws StaticSolveError with
    // the load it stopped at. on_step, if given, sees each step as it
    // converges, so that a caller keeps the steps before a failure.
    std::vector<LoadStep> load_path(const dealii::Vector<double> &F, unsigned int n_steps,
                                    const std::function<void(const LoadStep &)> &on_step = {});

    unsigned int n_linear_solves() const { return linear_solves; }
    unsigned int n_static_solves() const { return static_solves; }
    const dealii::SparseMatrix<double> &mass_matrix() const { return M; }

  private:
    dealii::Vector<double> displacement_from_modes(const Eigen::VectorXd &q) const;
    Eigen::VectorXd project(const dealii::Vector<double> &f) const; // Φᵀ f

    const FEBeam &beam;
    NewtonSettings settings;
    std::vector<dealii::Vector<double>> Phi;
    dealii::SparseMatrix<double> M;
    dealii::AffineConstraints<double> axial_only; // supports + every w and θ DoF
    unsigned int linear_solves = 0, static_solves = 0;
    struct LoadSteppedSolve; // one solve() as numerics/newton.h's problem
  };
} // namespace beamslider
