// The strip as a continuum: a total-Lagrangian St. Venant–Kirchhoff solid
// (doc/physics.md §8), the model that checks what the von Kármán beam
// idealises (Poisson and plate effects of a wide strip, shear and rotary
// inertia, the exact Green–Lagrange strain).
//
// With the displacement u(X) of the reference configuration X,
//
//   F = I + ∇u,   E = ½ (Fᵀ F − I)                  (Green–Lagrange strain),
//   S = λ tr(E) I + 2 μ E                           (SVK: 2nd Piola–Kirchhoff),
//   Π(u) = ∫ ½ E : S dV,   T = ∫ ½ ρ |u̇|² dV,
//
// so the internal force f(u) = ∂Π/∂u, ⟨f, v⟩ = ∫ S : sym(Fᵀ∇v) dV, is exactly
// cubic in u, and its tangent is
//
//   ⟨K_t(u) w, v⟩ = ∫ sym(Fᵀ∇v) : C : sym(Fᵀ∇w) + S : (∇vᵀ ∇w) dV.
//
// dim = 2 is the plane-stress strip in the x–z plane: the width b is the
// out-of-plane thickness (every integral carries the factor b) and
// λ = E ν / (1 − ν²) (the plane-stress modulus, σ_yy = 0); dim = 3 is the
// strip itself with λ = E ν / ((1 + ν)(1 − 2ν)). In both μ = E / (2 (1 + ν)).
// z, the last coordinate, is the beam's w direction.
//
// The generated strip: x ∈ [0, L], (y ∈ [−b/2, b/2],) z ∈ [−h/2, h/2], of
// the scene's element counts, clamped (u = 0) on the faces x = 0 and x = L:
// the ideal clamp of the beam scenes. Discretisation: vector FE_Q(p) on a
// parallel::distributed triangulation (p4est), PETSc MPI matrices and
// vectors: the same code on 1 rank and under mpirun -n K.
//
// Units: SI; vectors hold the displacement components [m].
#pragma once

#include "meshes/scene.h"

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <mpi.h>

namespace beamslider
{
  template <int dim>
  class SolidModel
  {
  public:
    // The scene's strip (Solid/Continuum must match dim); MPI must be running.
    SolidModel(const Scene &scene, MPI_Comm communicator);

    MPI_Comm communicator() const { return mpi_communicator; }
    const dealii::DoFHandler<dim> &get_dof_handler() const { return dof_handler; }
    const dealii::AffineConstraints<double> &constraints() const { return clamp_constraints; }
    const dealii::IndexSet &locally_owned_dofs() const { return owned_dofs; }
    const dealii::IndexSet &locally_relevant_dofs() const { return relevant_dofs; }
    dealii::types::global_dof_index n_dofs() const { return dof_handler.n_dofs(); }
    unsigned int n_cells() const { return triangulation.n_global_active_cells(); }
    double length() const { return beam.length; }
    double width() const { return beam.width; }
    double thickness() const { return beam.thickness; }
    double density() const { return beam.density; }
    // λ and μ of the law above [Pa] (λ the plane-stress one in 2D).
    double lame_lambda() const { return lambda; }
    double lame_mu() const { return mu; }
    // The factor every volume integral carries: b in 2D, 1 in 3D [m or -].
    double out_of_plane_thickness() const { return dim == 2 ? beam.width : 1.; }

    // A matrix with this model's sparsity, a vector of its owned DoFs, and
    // one with ghost entries (to read a displacement on the owned cells).
    void reinit_matrix(dealii::PETScWrappers::MPI::SparseMatrix &A) const;
    void reinit_vector(dealii::PETScWrappers::MPI::Vector &v) const;
    void reinit_ghosted_vector(dealii::PETScWrappers::MPI::Vector &v) const;

    // Consistent mass matrix ∫ ρ v·w dV; constrained rows carry a diagonal entry.
    void assemble_mass_matrix(dealii::PETScWrappers::MPI::SparseMatrix &M) const;
    // f(u) and/or K_t(u) (either may be null), u ghosted. Constrained rows
    // of f are zero; those of K_t carry a diagonal entry. At u = 0, K_t is
    // the linear stiffness.
    void assemble_internal_force(const dealii::PETScWrappers::MPI::Vector &u_ghosted,
                                 dealii::PETScWrappers::MPI::Vector *f,
                                 dealii::PETScWrappers::MPI::SparseMatrix *K_t) const;

  private:
    MPI_Comm mpi_communicator;
    BeamData beam;
    double lambda, mu;

    dealii::parallel::distributed::Triangulation<dim> triangulation;
    dealii::FESystem<dim> fe;
    dealii::DoFHandler<dim> dof_handler;
    dealii::IndexSet owned_dofs, relevant_dofs;
    dealii::AffineConstraints<double> clamp_constraints;
    dealii::DynamicSparsityPattern sparsity;
  };
} // namespace beamslider
