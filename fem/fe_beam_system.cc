#include "fem/fe_beam_system.h"

#include "contact/base_excitation.h"
#include "fem/fe_transient.h"

namespace beamslider
{
  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &scene, const unsigned int n_elements,
                                                  const bool axial_inertia)
  {
    FETransientSettings settings;
    settings.axial_inertia      = axial_inertia;
    settings.relative_tolerance = scene.solvers.newton_relative_tolerance;
    settings.absolute_tolerance = scene.solvers.newton_absolute_tolerance;
    settings.max_iterations     = scene.solvers.newton_iterations;
    return std::make_unique<FETransientBeam>(scene, BaseExcitation::from_scene(scene.excitation), n_elements,
                                             settings);
  }
} // namespace beamslider
