// Nonlinear statics of the solid strip: f(u) = F by Newton's method with
// load stepping and a parallel direct solve (MUMPS) of each tangent system;
// the strip's dead loads and its mid-span deflection.
//
// Convergence: the relative residual ‖F − f(u)‖/‖F‖ below 1e-10, or Newton's
// correction below 1e-10 of the displacement. The second is needed on a thin
// strip: its membrane forces are ~1e7 times its bending forces, so the
// residual of a bending state stalls at round-off (~1e-4 of the load at
// L/h = 140) while the displacement has converged. A Newton solve that does
// not converge is cut back in load; below 1e-4 of the load it throws
// SolidStaticSolveError saying at which load fraction and residual it stopped.
#pragma once

#include "fem/solid_model.h"

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
    // number of Newton iterations.
    unsigned int solve(const dealii::PETScWrappers::MPI::Vector &F, dealii::PETScWrappers::MPI::Vector &u,
                       const dealii::PETScWrappers::MPI::Vector *F_start = nullptr);

    // A uniform dead line load of q_n_per_m [N/m] along the strip in +z,
    // applied as the pressure q/b on the top face (z = h/2 of the generated
    // strip, Solid/Loaded boundary of a mesh; in 2D, q per length of the
    // top edge), per unit of the face projected on the x–y plane. Throws
    // InputError if the mesh has no loaded face.
    dealii::PETScWrappers::MPI::Vector line_load(double q_n_per_m) const;
    // The mid-span deflection [m]: u_z averaged over the cross-section x = L/2
    // (exactly on the generated strip, by 8 Gauss points per direction of
    // the Beam's b × h section on a mesh file).
    double mid_span_deflection(const dealii::PETScWrappers::MPI::Vector &u_ghosted) const;

    unsigned int n_static_solves() const { return static_solves; }
    unsigned int n_linear_solves() const { return linear_solves; }

  private:
    double section_average_on_strip(const dealii::PETScWrappers::MPI::Vector &u_ghosted) const;
    double section_average_by_points(const dealii::PETScWrappers::MPI::Vector &u_ghosted) const;

    const SolidModel<dim> &model;
    unsigned int static_solves = 0, linear_solves = 0;
  };
} // namespace beamslider
