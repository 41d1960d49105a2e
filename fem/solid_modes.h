// Linear modes of the solid strip: K φ = ω² M φ at u = 0, by SLEPc
// (Krylov–Schur, shift-invert about 0, the shifted system factorised by
// MUMPS, parallel), mass-normalised (φᵀ M φ = 1), the sign such that
// ∫ ρ φ_z (L − x) dV > 0 (the beam's convention, fem/fe_modes.h).
//
// Each mode is classified by where its kinetic energy lies: the share of
// ∫ ρ |φ|² dV in each displacement component, and, for the z (thickness)
// component in 3D, its correlation with y across the width,
//   c = (∫ ρ φ_z y)² / (∫ ρ φ_z² · ∫ ρ y²),
// which is 1 for a twist φ_z = θ(x) y and 0 for bending, whose φ_z is even
// in y on the symmetric strip, but misses a twist whose angle changes sign
// along x (the second torsion mode); and the order of φ_z across the width,
//   k = ∫ ρ φ_z y ∂φ_z/∂y dV / ∫ ρ φ_z² dV,
// which is 0 for a φ_z uniform across the width (bending, but for the slight
// anticlastic curvature), 1 for φ_z ∝ y (a twist, whatever its shape along
// x) and 2 for φ_z ∝ y² − b²/12 (the strip bent across its width). The
// shape is
//   axial    most energy in x,
//   lateral  most in y (3D: in-plane bending across the width),
//   plate    most in z with k > 1.5: bent across the width, a plate mode no
//            beam has,
//   torsion  most in z with c > ½ or k > ½,
//   bending  most in z otherwise (the beam's w modes).
#pragma once

#include "fem/solid_model.h"

#include <array>
#include <string>
#include <vector>

namespace beamslider
{
  struct SolidMode
  {
    double omega;                      // [rad/s]
    std::string shape;                 // bending | torsion | lateral | axial
    std::array<double, 3> energy_share; // of x, y, z (2D: x, z, 0) [-]
    double twist_correlation = 0;      // c above (3D), 0 in 2D
    double width_order       = 0;      // k above (3D), 0 in 2D
    dealii::PETScWrappers::MPI::Vector vector; // mass-normalised, ghosted
  };

  struct SolidModes
  {
    std::vector<SolidMode> all;          // every mode computed, ascending
    std::vector<unsigned int> bending;   // indices into `all` of the bending modes, ascending
    unsigned int eigensolver_iterations = 0;
  };

  // The lowest modes, as many as it takes to find n_bending bending modes
  // and at least n_lowest modes of any shape (computed in rounds of growing
  // size). Throws std::runtime_error with SLEPc's message if the eigensolver
  // fails.
  template <int dim>
  SolidModes compute_solid_modes(const SolidModel<dim> &model, unsigned int n_bending, unsigned int n_lowest = 0);
} // namespace beamslider
