// Linear bending modes of the FE beam: the generalized eigenproblem
//   K φ = ω² M φ
// on the flat, undeformed beam, solved with SLEPc (Krylov–Schur with
// shift-invert about σ = 0, through deal.II's wrappers). On the flat beam the
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

#include <deal.II/lac/vector.h>

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

  // The `n_modes` lowest bending modes. Throws with the SLEPc message if the
  // eigensolver does not converge.
  FEModes compute_bending_modes(const FEBeam &beam, unsigned int n_modes,
                                const std::optional<BondedBody> &body = std::nullopt);
} // namespace beamslider
