// The reduced model's basis from the solid strip's bending modes: what the
// contact code asks of a beam, the deflection φ_n(x) of the beam line and its
// slope φ_n'(x), taken from the solid as u_z on the mid-surface z = 0
// averaged over the width (3D; in plane stress its value on z = 0) and
// ∂u_z/∂x averaged likewise, at the ends of n_intervals equal intervals
// along x, joined by cubic Hermite polynomials (reduced/hermite_mode_table.h);
// 141 intervals keep the sample points off the element ends of the
// generated strips, where the C0 field has two slopes.
// The modes keep the solid's normalisation, ∫ ρ |φ|² dV = 1 (axial and
// lateral parts included), so the modal masses stay 1.
//   ω_n    the solid's,
//   γ_n  = −∫ ρ φ_z dV  (the base acceleration in z acts on the whole mass),
//   K', k_ax of the line, for the analytic membrane form; a solid's reduced
//   model takes its cubic terms from ICE on the solid instead.
// The surfaces at ±h/2 follow from the line and the scene's thickness, as for
// the beam.
#pragma once

#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "scene/scene.h"
#include "reduced/modal_basis.h"

namespace beamslider
{
  // The first n_modes bending modes of `modes`. Throws InputError on an arch
  // (the beam line is straight) and if the mesh does not fill the strip.
  template <int dim>
  ModalBasis make_solid_modal_basis(const SolidModel<dim> &model, const SolidModes &modes, unsigned int n_modes,
                                    const Scene &scene, unsigned int n_intervals = 141);
} // namespace beamslider
