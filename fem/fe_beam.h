// The finite-element model of the beam (doc/physics.md §2–3): a von Kármán beam
// in 1D with axial displacement u(x) and transverse displacement w(x)
// relative to the moving base,
//
//   ε = u' + ½ w'²  (u' alone without geometric nonlinearity),   κ = w'' ,
//   Π(u, w) = ∫ ½ EA ε² + ½ EI κ² dx + Σ_ends ½ k_r w'² + ½ (2 k_t) u² ,
//   T       = ∫ ½ ρA (u̇² + ẇ²) dx + Σ_bodies ½ (m ẇ² + J ẇ'²)(x_p) ,
//   base load  -(∫ ρA δw dx + Σ_bodies m δw(x_p)) ẅ0 .
//
// EA, EI and ρA are those of each element's section: constant along a
// uniform beam, per physical tag on a beam read from a mesh (scene/beam_mesh.h).
// Point bodies (Point masses in the scene) add their mass and rotary inertia
// at their position.
//
// Discretisation. The bending energy needs C¹ continuity of w, and deal.II
// 9.4 has no Hermite element. We use deal.II's DoFHandler, quadrature and
// AffineConstraints with the element FESystem(FE_Q(p), FE_Q(1), FE_Q(1)):
// component 0 is u (Lagrange of degree p), components 1 and 2 are the nodal
// values of w and of the slope θ = w' at the vertices. On each cell these four
// vertex values are the coefficients of the cubic Hermite interpolant, whose
// shape functions we evaluate ourselves (contact/hermite_shape.h). We chose this
// over a C⁰ interior-penalty method (step-47) because the Hermite cubic is
// conforming, has no penalty parameter to tune, carries the slope as a DoF
// (which the rotational springs and the slider's rotary inertia act on
// directly), and gives the classical O(h⁴) convergence of the frequencies.
//
// Supports: w = 0 at both ends by constraints; rotational springs k_r on θ
// and axial springs 2 k_t on u at both ends (k_t is the clamping's total
// axial stiffness, as published: the two end springs in series); the ideal clamp (k_r, k_t → ∞) is
// imposed exactly by the constraints θ = 0, u = 0 instead of the springs.
//
// Units: SI. The DoF vector holds u [m], w [m] and θ [rad].
#pragma once

#include "contact/hermite_shape.h"
#include "scene/scene.h"

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <functional>
#include <vector>

namespace beamslider
{
  using dealii::types::global_dof_index;

  // The DoFs and shape-function values that give w, w' (and u) at one point x.
  // w(x) = Σ_a w_values[a] q[w_dofs[a]], and likewise for the others.
  struct FEPointShape
  {
    std::array<global_dof_index, 4> w_dofs;   // (w0, θ0, w1, θ1) of the cell containing x
    std::array<double, 4> w_values;           // Hermite N_a(x)
    std::array<double, 4> slope_values;       // N_a'(x)
    std::array<double, 4> curvature_values;   // N_a''(x)
    std::vector<global_dof_index> u_dofs;     // axial DoFs of the cell
    std::vector<double> u_values;             // their shape values at x
    std::vector<double> strain_values;        // and derivatives at x
  };

  class FEBeam
  {
  public:
    // The beam of `scene` with `n_elements` elements (0: take the scene's
    // discretisation). A uniform beam gets equal elements; a beam from a
    // mesh gets each mesh element split into n_elements / (mesh elements)
    // equal parts, which must be a whole number (else std::invalid_argument).
    explicit FEBeam(const Scene &scene, unsigned int n_elements = 0);

    unsigned int n_dofs() const { return dof_handler.n_dofs(); }
    unsigned int n_elements() const { return triangulation.n_active_cells(); }
    double length() const { return beam.length; }
    const BeamData &beam_data() const { return beam; }
    const SupportData &support_data() const { return supports; }
    bool geometric_nonlinearity() const { return nonlinear; }

    // The section of a cell of the mesh (EA, EI, ρA and h are constant on each).
    const BeamSection &section(const typename dealii::DoFHandler<1>::active_cell_iterator &cell) const
    {
      return sections[cell->material_id()];
    }
    // The section at x and its thickness [m] (at an element boundary, the
    // element to the right).
    const BeamSection &section_at(const double x) const { return section(cell_at(x)); }
    double thickness_at(const double x) const { return section_at(x).thickness; }
    // The cells from x = 0 to x = L.
    const std::vector<typename dealii::DoFHandler<1>::active_cell_iterator> &cells_in_order() const
    {
      return ordered_cells;
    }

    // Homogeneous constraints of the supports (w = 0; θ = u = 0 if clamped).
    const dealii::AffineConstraints<double> &constraints() const { return support_constraints; }
    // The support constraints plus u = 0 everywhere: on the flat beam the
    // linear problem decouples, and this isolates the bending modes.
    const dealii::AffineConstraints<double> &bending_constraints() const { return bending_only_constraints; }
    const dealii::SparsityPattern &sparsity_pattern() const { return sparsity; }
    const dealii::DoFHandler<1> &get_dof_handler() const { return dof_handler; }

    // Consistent mass matrix ∫ρA(u δu + w δw) plus the point bodies of the
    // scene; constrained rows hold the diagonal entry that `constraints`
    // puts there.
    void assemble_mass_matrix(dealii::SparseMatrix<double> &M,
                              const dealii::AffineConstraints<double> &c) const;
    // Internal force f(q) = ∂Π/∂q and/or tangent K_t(q) = ∂f/∂q (either pointer
    // may be null). At q = 0, K_t is the linear stiffness.
    void assemble_internal_force(const dealii::Vector<double> &q, dealii::Vector<double> *f,
                                 dealii::SparseMatrix<double> *K_t,
                                 const dealii::AffineConstraints<double> &c) const;
    // r with the base-excitation load r ẅ0(t): r = -∫ρA N_w dx - Σ m N_w(x_p).
    void assemble_base_load(dealii::Vector<double> &r) const;
    // F with the consistent nodal forces of a uniform line load of
    // q_n_per_m [N/m] acting in +w on the whole beam: F = ∫ q N_w dx
    // (zero on constrained DoFs). A downward load has q < 0.
    void assemble_line_load(double q_n_per_m, dealii::Vector<double> &F) const;

    // Adds a rigid body bonded at x: mass m on w(x) and rotary inertia J on
    // w'(x) (the slider held fixed to the beam, seed Eq. 5's model).
    void add_point_inertia(double x, double m, double J, dealii::SparseMatrix<double> &M) const;

    // Shape-function values at x ∈ [0, L] (throws for x outside).
    FEPointShape point_shape(double x) const;
    double deflection(const dealii::Vector<double> &q, double x) const;
    double slope(const dealii::Vector<double> &q, double x) const;

    // Boolean masks: which global DoFs are axial u, transverse w, slopes θ.
    const std::vector<bool> &axial_dofs() const { return is_axial; }
    const std::vector<bool> &deflection_dofs() const { return is_deflection; }
    const std::vector<bool> &slope_dofs() const { return is_slope; }
    // DoFs at the two supports: u, w, θ at x = 0 and x = L.
    std::array<global_dof_index, 3> support_dofs(unsigned int end) const { return end_dofs[end]; }

  private:
    // r += ∫ load(section) N_w dx over the whole beam, load in N/m.
    void add_distributed_load(const std::function<double(const BeamSection &)> &load,
                              dealii::Vector<double> &r) const;
    // The cell containing x ∈ [0, L] (at a vertex, the cell to the right;
    // throws for x outside).
    typename dealii::DoFHandler<1>::active_cell_iterator cell_at(double x) const;
    void make_grid_and_dofs(unsigned int n_elements);
    void make_constraints();

    BeamData beam;
    SupportData supports;
    bool nonlinear;
    // The sections the cells' material ids point to (one for a uniform beam).
    std::vector<BeamSection> sections;

    dealii::Triangulation<1> triangulation;
    dealii::FESystem<1> fe;
    dealii::DoFHandler<1> dof_handler;
    dealii::AffineConstraints<double> support_constraints;
    dealii::AffineConstraints<double> bending_only_constraints;
    dealii::SparsityPattern sparsity;

    // Cells ordered from x = 0 to x = L, for locating a point.
    std::vector<typename dealii::DoFHandler<1>::active_cell_iterator> ordered_cells;
    // Local indices of (w0, θ0, w1, θ1) and of the axial DoFs within a cell.
    std::array<unsigned int, 4> hermite_local;
    std::vector<unsigned int> axial_local;

    std::vector<bool> is_axial, is_deflection, is_slope;
    std::array<std::array<global_dof_index, 3>, 2> end_dofs;
  };

} // namespace beamslider
