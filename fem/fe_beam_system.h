// The FE beam as a BeamSystem (contact/beam_system.h) for the shared contact
// code: the implicit Moreau–Jean θ-scheme (the scene's FE theta; 1/2, the
// implicit midpoint rule, by default) on the von Kármán forces, doc/physics.md §7–8. The scheme, its linear algebra
// and its energy bookkeeping are documented in fem/fe_transient.h.
#pragma once

#include "contact/beam_system.h"
#include "meshes/scene.h"

#include <memory>

namespace beamslider
{
  // The FE beam of `scene` (its mesh, supports, damping ratio D on the
  // scene's N lowest bending modes and none on the others, base excitation)
  // as a BeamSystem. n_elements = 0 takes the scene's mesh.
  // axial_inertia = false gives the axial DoFs no mass (the membrane in
  // static equilibrium, as in the reduced model; fem/fe_transient.h).
  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &scene, unsigned int n_elements = 0,
                                                  bool axial_inertia = true);
} // namespace beamslider
