// Nonlinear statics of the solid strip: f(u) = F by a modified Newton method
// with load stepping and a parallel direct solve (MUMPS); the strip's dead
// loads and its mid-span deflection.
//
// Modified Newton: the tangent's MUMPS factorisation (fem/kept_factorisation)
// is kept across iterations and across static solves, and refreshed at the
// current state when successive corrections shrink by less than 4x, after 10
// iterations on it, or when a load increment is cut back. An ICE solve (a
// small modal load from u = 0) takes two corrections on the kept tangent (the
// second as large as the first: the linear stiffness has no coupling of
// bending and stretching), one factorisation at the bent state and ~2 more
// back-substitutions, instead of ~4 factorisations: on the 3D strip's ICE
// with N = 5, 1.2 factorisations per solve instead of 4, 577 s -> 166 s
// (doc/performance.md). Large loads (`statics` to 4 h) refresh often.
//
// Line search: each large correction (above 1e-3 of u) is scaled by α where
// the total potential energy along it is lowest, found as the root of its
// slope g(α) = du·(F − f(u + α du)) (full step if |g(1)| ≤ ½ g(0), else up
// to three secant steps inside the bracket). A flat strip's tangent has no
// membrane stiffness, so the full first correction of a load that bends it
// to h bends it by many h and the increment diverged: on the 3D strip of
// `verify` section 8 the loads to h, 2 h, 4 h took 60–76 iterations and ~20
// factorisations each, half of them in increments cut back; with the line
// search one increment each, 12–14 iterations and 2–4 factorisations
// (section 8: 23 → 7 s). An increment is cut back when its residual exceeds
// 1e8 times the load (diverging), after 6 factorisations or 30 iterations.
//
// Convergence: the relative residual ‖F − f(u)‖/‖F‖ below 1e-10, or Newton's
// correction below 1e-10 of the displacement. The second is needed on a thin
// strip: its membrane forces are ~1e7 times its bending forces, so the
// residual of a bending state stalls at round-off (~1e-4 of the load at
// L/h = 140) while the displacement has converged. A Newton solve that does
// not converge is cut back in load; below 1e-4 of the load it throws
// SolidStaticSolveError saying at which load fraction and residual it stopped.
#pragma once

#include "numerics/newton.h"

#include "fem/kept_factorisation.h"
#include "fem/solid_model.h"

#include <functional>
#include <stdexcept>
#include <vector>

namespace beamslider
{
  class SolidStaticSolveError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  template <int dim>
  class SolidStatics
  {
  public:
    explicit SolidStatics(const SolidModel<dim> &model);

    // Solves f(u) = F for u (overwritten, starting from it), stepping the
    // load from F_start (u's equilibrium load; null: zero) to F. Returns the
    // number of Newton iterations (back-substitutions).
    unsigned int solve(const dealii::PETScWrappers::MPI::Vector &F, dealii::PETScWrappers::MPI::Vector &u,
                       const dealii::PETScWrappers::MPI::Vector *F_start = nullptr);

    // The load path of F from rest in n_steps equal steps, λ = k/n_steps:
    // each converged step k (1-based) to `on_step(k, λ, u, iterations)`, u
    // ghosted (every rank calls it; collective evaluations are allowed). A
    // step that fails throws SolidStaticSolveError beginning "load step k of
    // n: "; an interruption throws Interrupted.
    void load_path(const dealii::PETScWrappers::MPI::Vector &F, unsigned int n_steps,
                   const std::function<void(unsigned int k, double lambda,
                                            const dealii::PETScWrappers::MPI::Vector &u, unsigned int iterations)>
                     &on_step);

    // A uniform dead line load of q_n_per_m [N/m] along the strip in +z,
    // applied as the pressure q/b on the top face (z = h/2 of the generated
    // strip, Solid/Loaded boundary of a mesh; in 2D, q per length of the
    // top edge), per unit of the face projected on the x–y plane. Throws
    // InputError if the mesh has no loaded face.
    dealii::PETScWrappers::MPI::Vector line_load(double q_n_per_m) const;
    // The deflection of the section x [m], 0 <= x < L: u_z averaged over the
    // cross-section (exactly on the generated strip, by 8 Gauss points per
    // direction of the Beam's b × h section on a mesh file).
    double section_deflection(const dealii::PETScWrappers::MPI::Vector &u_ghosted, double x) const;
    // The mid-span deflection [m]: that of the section x = L/2.
    double mid_span_deflection(const dealii::PETScWrappers::MPI::Vector &u_ghosted) const
    {
      return section_deflection(u_ghosted, 0.5 * model.length());
    }

    unsigned int n_static_solves() const { return static_solves; }
    unsigned int n_linear_solves() const { return linear_solves; }
    unsigned int n_factorisations() const { return tangent.n_factorisations(); }

  private:
    double section_average_on_strip(const dealii::PETScWrappers::MPI::Vector &u_ghosted, double x) const;
    double section_average_by_points(const dealii::PETScWrappers::MPI::Vector &u_ghosted, double x) const;

    const SolidModel<dim> &model;
    unsigned int static_solves = 0, linear_solves = 0;
    KeptFactorisation tangent;  // kept across solve() calls
    NewtonMatrixAge tangent_age; // back-substitutions on it so far
    struct LoadSteppedSolve;     // one solve() as numerics/newton.h's problem
  };
} // namespace beamslider
