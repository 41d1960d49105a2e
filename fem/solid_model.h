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
// The mesh (fem/solid_mesh.h): the generated strip x ∈ [0, L],
// (y ∈ [−b/2, b/2],) z ∈ [−h/2, h/2] of the scene's element counts (or that
// strip lifted into a shallow arch), clamped (u = 0) on the faces x = 0 and
// x = L, the ideal clamp of the beam scenes; or a mesh file with its
// clamped groups and material regions. Discretisation: vector FE_Q(p) on
// quadrilaterals/hexahedra, FE_SimplexP(p) on triangles/tetrahedra; the
// generated strip on a parallel::distributed triangulation (p4est), a mesh
// file on a parallel::fullydistributed one (which takes simplices),
// partitioned by METIS; PETSc MPI matrices and vectors: the same code on 1
// rank and under mpirun -n K.
//
// Units: SI; vectors hold the displacement components [m].
#pragma once

#include "fem/solid_mesh.h"
#include "scene/scene.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/petsc_sparse_matrix.h>
#include <deal.II/lac/petsc_vector.h>

#include <mpi.h>

#include <memory>
#include <optional>

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
    unsigned int n_cells() const { return triangulation->n_global_active_cells(); }
    double length() const { return beam.length; }
    double width() const { return beam.width; }
    double thickness() const { return beam.thickness; }
    // The factor every volume integral carries: b in 2D, 1 in 3D [m or -].
    double out_of_plane_thickness() const { return dim == 2 ? beam.width : 1.; }

    // Every integral over cells and faces uses these: the mapping (Q1 or
    // its simplex counterpart) and Gauss rules exact for the mass matrix.
    const dealii::Mapping<dim> &mapping() const { return *cell_mapping; }
    const dealii::Quadrature<dim> &quadrature() const { return cell_quadrature; }
    const dealii::Quadrature<dim - 1> &face_quadrature() const { return face_rule; }
    // The law in a cell's region (its material id).
    const SolidMaterial &material(dealii::types::material_id region) const { return groups.materials.at(region); }
    bool simplex() const { return is_simplex; }
    // The generated strip (or arch): axis-aligned sections x = const.
    bool generated() const { return !from_mesh; }
    // The top face the line load presses on, if the mesh names one.
    std::optional<dealii::types::boundary_id> loaded_boundary() const { return groups.loaded; }
    // "FE_Q(2)", "FE_SimplexP(2)": for messages.
    std::string element_name() const;

    // The published elastic supports (Supports/Type = elastic; on a mesh
    // file, its two clamped groups must be the end faces x = 0 and x = L):
    // each end face moves as a rigid plate,
    //   u_x = U − θ z,  u_y = u_z = 0,
    // its axial translation U on the spring 2 k_t (k_t is both ends'
    // total, as in the beam) and its rotation θ on k_r. The plate's two
    // degrees of freedom are u_x of two nodes of the face, at z = −h/2 and
    // z = h/2 nearest y = 0 (U = (u_b + u_t)/2, θ = (u_b − u_t)/h); every
    // other u_x of the face is constrained to them. So the springs'
    // resultants are exactly the beam's k_t and k_r, and the face stays
    // plane as the beam's section does.
    bool elastic_supports() const { return !plates.empty(); }
    // aᵀ K_s b: the springs' bilinear form over both ends (ghosted vectors).
    double support_spring_product(const dealii::PETScWrappers::MPI::Vector &a,
                                  const dealii::PETScWrappers::MPI::Vector &b) const;
    // Sets the constrained entries of v (owned, not ghosted) from the ones
    // they follow: zero on a clamp, the plate's motion on an elastic end.
    void distribute(dealii::PETScWrappers::MPI::Vector &v) const { clamp_constraints.distribute(v); }

    // A matrix with this model's sparsity, a vector of its owned DoFs, and
    // one with ghost entries (to read a displacement on the owned cells).
    void reinit_matrix(dealii::PETScWrappers::MPI::SparseMatrix &A) const;
    void reinit_vector(dealii::PETScWrappers::MPI::Vector &v) const;
    void reinit_ghosted_vector(dealii::PETScWrappers::MPI::Vector &v) const;

    // Consistent mass matrix ∫ ρ v·w dV; constrained rows carry a diagonal entry.
    void assemble_mass_matrix(dealii::PETScWrappers::MPI::SparseMatrix &M) const;
    // f(u) and/or K_t(u) (either may be null), u ghosted. Constrained rows
    // of f are zero; those of K_t carry a diagonal entry. At u = 0, K_t is
    // the linear stiffness. A K_t that already has this model's size must
    // come from this model's reinit_matrix: its entries are zeroed and its
    // PETSc structure kept (a Newton loop reuses one matrix).
    void assemble_internal_force(const dealii::PETScWrappers::MPI::Vector &u_ghosted,
                                 dealii::PETScWrappers::MPI::Vector *f,
                                 dealii::PETScWrappers::MPI::SparseMatrix *K_t) const;

  private:
    MPI_Comm mpi_communicator;
    BeamData beam;
    bool from_mesh, is_simplex;

    std::unique_ptr<dealii::parallel::TriangulationBase<dim>> triangulation;
    SolidMeshGroups groups;
    std::unique_ptr<dealii::FESystem<dim>> fe;
    std::unique_ptr<dealii::Mapping<dim>> cell_mapping;
    dealii::Quadrature<dim> cell_quadrature;
    dealii::Quadrature<dim - 1> face_rule;
    dealii::DoFHandler<dim> dof_handler;
    dealii::IndexSet owned_dofs, relevant_dofs;
    dealii::AffineConstraints<double> clamp_constraints;
    dealii::DynamicSparsityPattern sparsity;

    struct EndPlate
    {
      dealii::types::global_dof_index bottom, top; // u_x at z = −h/2 and h/2
    };
    std::vector<EndPlate> plates; // none: clamped
    double plate_axial_stiffness = 0, plate_rotational_stiffness = 0; // 2 k_t [N/m], k_r [N m/rad]
    void make_end_plates(const std::vector<std::string> &group_names);
    void add_support_springs(const dealii::PETScWrappers::MPI::Vector &u_ghosted,
                             dealii::PETScWrappers::MPI::Vector *f,
                             dealii::PETScWrappers::MPI::SparseMatrix *K_t) const;
  };
} // namespace beamslider
