// The FE beam as a BeamSystem (contact/beam_system.h) for the shared contact
// code: implicit Moreau–Jean θ-scheme on the von Kármán forces (DESIGN.md §1.4).
// PLACEHOLDER: to be implemented.
#pragma once

#include "contact/beam_system.h"
#include "meshes/scene.h"

#include <memory>

namespace beamslider
{
  // The FE beam of `scene` (its mesh, supports, damping on the scene's N
  // modes, base excitation) as a BeamSystem.
  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &scene);
} // namespace beamslider
