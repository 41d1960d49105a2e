#include "fem/fe_beam_system.h"

#include "contact/base_excitation.h"
#include "fem/fe_transient.h"

namespace beamslider
{
  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &scene, const unsigned int n_elements,
                                                  const bool axial_inertia)
  {
    FETransientSettings settings;
    settings.axial_inertia = axial_inertia;
    return std::make_unique<FETransientBeam>(scene, BaseExcitation::from_scene(scene.excitation), n_elements,
                                             settings);
  }
} // namespace beamslider
