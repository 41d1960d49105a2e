// The FE beam as a BeamSystem (contact/beam_system.h) for the shared contact
// code: the implicit Moreau–Jean θ-scheme (the scene's FE theta; 1/2, the
// implicit midpoint rule, by default) on the von Kármán forces, doc/physics.md §7–8. The scheme, its linear algebra
// and its energy bookkeeping are documented in fem/fe_transient.h.
#pragma once

#include "contact/beam_system.h"
#include "scene/scene.h"

#include <memory>
#include <optional>

namespace beamslider
{
  // What a run of the FE beam sets apart from the scene: a model's resolved
  // setting (verification/studies/fe_rom_study.h's ModelSetting). Each
  // entry left at its default takes the scene's value; the scene itself is
  // never changed.
  struct FEBeamOptions
  {
    unsigned int n_elements = 0;   // 0: the scene's mesh (`Discretisation/Number of elements`)
    unsigned int damped_modes = 0; // modes damped with D; 0: the scene's N
    std::optional<double> theta;   // the Moreau–Jean θ; unset: the scene's `FE theta`
    // false gives the axial DoFs no mass (the membrane in static equilibrium,
    // as in the reduced model; fem/fe_transient.h).
    bool axial_inertia = true;
  };

  // The FE beam of `scene` (its mesh, supports, damping ratio D on the
  // lowest bending modes and none on the others, base excitation) as a
  // BeamSystem.
  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &scene, const FEBeamOptions &options = {});
} // namespace beamslider
