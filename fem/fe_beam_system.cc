#include "fem/fe_beam_system.h"

#include "contact/base_excitation.h"
#include "fem/fe_transient.h"

namespace beamslider
{
  // The scene's Solvers defaults (scene/scene.h) are the FE step's own.
  static_assert(SolverData{}.newton_relative_tolerance == FETransientSettings{}.relative_tolerance &&
                  SolverData{}.newton_absolute_tolerance == FETransientSettings{}.absolute_tolerance &&
                  SolverData{}.newton_iterations == FETransientSettings{}.max_iterations,
                "the default scene's Newton settings differ from FETransientSettings' defaults");

  std::unique_ptr<BeamSystem> make_fe_beam_system(const Scene &scene, const FEBeamOptions &options)
  {
    FETransientSettings settings;
    settings.axial_inertia      = options.axial_inertia;
    settings.damped_modes       = options.damped_modes;
    settings.theta              = options.theta.value_or(scene.time_stepping.fe_theta);
    settings.impulses_through_mass = scene.time_stepping.fe_impulses == "mass";
    settings.redistributed_mass    = scene.time_stepping.fe_impulses == "redistributed";
    settings.relative_tolerance = scene.solvers.newton_relative_tolerance;
    settings.absolute_tolerance = scene.solvers.newton_absolute_tolerance;
    settings.max_iterations     = scene.solvers.newton_iterations;
    return std::make_unique<FETransientBeam>(scene, BaseExcitation::from_scene(scene.excitation), options.n_elements,
                                             settings);
  }
} // namespace beamslider
