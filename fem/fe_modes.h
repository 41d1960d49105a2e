// Linear bending modes of the FE beam: the generalized eigenproblem
//   K φ = ω² M φ
// on the flat, undeformed beam. Small problems (up to
// max_dense_eigenproblem_size free DoFs: every mesh a scene of this system
// needs; 62 on the default mesh) are solved densely and exactly, all
// eigenpairs at once (Eigen's generalised self-adjoint solver, about a
// millisecond); larger ones with SLEPc (Krylov–Schur with shift-invert about
// σ = 0, through deal.II's wrappers). The dense route keeps MPI, PETSc and
// SLEPc out of every command that needs no large eigenproblem: starting them
// costs about 0.6 s (Open MPI's singleton start-up), more than a whole ROM
// run's set-up. Both routes agree with an 80-bit reference to 1e-11 in ω
// (tests/test_fem_beam.cc). On the flat beam the
// linear problem decouples into bending and axial motion; we constrain u = 0
// to keep the bending modes only (the first axial mode of the default scene
// lies near 18 kHz, above the 7th bending mode anyway). Optionally a rigid
// body is bonded at x_C (mass m on w, rotary inertia J on w'), the model
// behind seed Eq. 5.
//
// The modes are mass-normalised (φᵀ M φ = 1, including a bonded body) and the
// sign is fixed so that ∫ φ(x) (L - x) dx > 0, which makes them reproducible
// across meshes.
#pragma once

#include "fem/fe_beam.h"

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace beamslider
{
  struct BondedBody
  {
    double x;    // position [m]
    double mass; // [kg]
    double inertia; // about its centre of mass [kg m^2]
  };

  struct FEModes
  {
    std::vector<double> omega;                  // [rad/s], ascending
    std::vector<dealii::Vector<double>> shapes; // mass-normalised, full DoF vectors (u = 0)
    unsigned int eigensolver_iterations = 0;
  };

  enum class EigenSolverMethod
  {
    automatic, // dense up to max_dense_eigenproblem_size free DoFs, SLEPc above
    dense,     // Eigen's dense generalised solver, whatever the size
    slepc      // SLEPc shift-invert Krylov–Schur, whatever the size
  };
  constexpr unsigned int max_dense_eigenproblem_size = 600; // free DoFs; ~0.2 s dense

  // K and M on the DoFs that `constraints` leaves free, as dense matrices
  // (the dense eigensolver's problem, and the static corrections' solves);
  // dofs[a] is the global DoF of row a. The constraints must pin DoFs to zero.
  struct FreeDofProblem
  {
    std::vector<unsigned int> dofs; // row a → its global DoF
    std::vector<int> row_of_dof;    // global DoF → its row, −1 for a constrained DoF
    Eigen::MatrixXd K, M;
  };
  FreeDofProblem restrict_to_free_dofs(const dealii::SparseMatrix<double> &K, const dealii::SparseMatrix<double> &M,
                                       const dealii::AffineConstraints<double> &constraints);

  // Flips φ so that ∫ φ(x) (L − x) dx > 0 (the midpoint sum of 8 points per
  // element): a shape's sign then does not depend on the solver or the mesh.
  void fix_shape_sign(const FEBeam &beam, dealii::Vector<double> &phi);

  // The `n_modes` lowest bending modes. Throws with the solver's message if
  // the eigensolver fails.
  FEModes compute_bending_modes(const FEBeam &beam, unsigned int n_modes,
                                const std::optional<BondedBody> &body = std::nullopt,
                                EigenSolverMethod method              = EigenSolverMethod::automatic);
} // namespace beamslider
