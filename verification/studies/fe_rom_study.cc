#include "verification/studies/fe_rom_study.h"

#include "contact/beam_system.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "reduced/rom_beam_system.h"
#include "reduced/rom_implicit_beam_system.h"
#include "verification/studies/coefficient_methods.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace beamslider
{
  std::string ModelSetting::label() const
  {
    std::ostringstream s;
    if (family == "fe")
      s << "FE " << n_elements << " el." << (axial_inertia ? "" : " no axial inertia");
    else
      s << "ROM N=" << n_modes << " " << coefficients << (integrator == "implicit" ? " implicit" : "");
    if (damped_modes)
      s << " damped " << damped_modes;
    s << " dt=" << time_step; // no comma: labels go into CSV cells
    if (slider_offset_over_L != 0)
      s << " x0+" << slider_offset_over_L;
    return s.str();
  }

  ModelSetting scene_model(const Scene &scene, const std::string &family)
  {
    if (family != "rom" && family != "fe")
      throw InputError("--model '" + family + "' is not one of rom, fe");
    ModelSetting s;
    s.family     = family;
    s.n_modes    = scene.discretisation.n_modes;
    s.n_elements = scene.discretisation.n_elements;
    // Each model family at its own step: the ROM at the scene's Time step,
    // the FE at its FE time step (scene.h says why they differ).
    s.time_step = family == "fe" ? scene.time_stepping.fe_time_step : scene.time_stepping.time_step;
    return s;
  }

  std::unique_ptr<BeamSystem> make_beam_model(const Scene &scene_in, const ModelSetting &setting)
  {
    Scene scene                     = scene_in;
    scene.time_stepping.time_step   = setting.time_step;
    if (setting.family == "fe")
      {
        if (setting.n_elements)
          scene.discretisation.n_elements = setting.n_elements;
        if (setting.damped_modes) // the FE damps the scene's N modes
          scene.discretisation.n_modes = setting.damped_modes;
        return make_fe_beam_system(scene, 0, setting.axial_inertia);
      }
    if (setting.family != "rom")
      throw InputError("model family '" + setting.family + "' is not one of fe, rom");

    const FEBeam beam(scene);
    const FEModes modes = compute_bending_modes(beam, setting.n_modes);
    ModalBasis basis    = make_modal_basis(beam, modes, setting.n_modes);
    ReducedOrderModel rom(basis, scene.damping_ratio, scene.discretisation.geometric_nonlinearity);
    if (setting.damped_modes)
      rom.set_damped_modes(setting.damped_modes);
    if (setting.coefficients != "analytic")
      {
        // STEP amplitude one thickness; ICE at 0.03 h (report section 2.4).
        const double level = setting.coefficients == "ice" ? 0.03 : 1.0;
        rom.set_cubic_terms(compute_coefficients(beam, modes, basis, setting.coefficients, level).fit.cubic);
      }
    if (setting.integrator == "implicit")
      return std::make_unique<RomImplicitBeamSystem>(std::move(rom), scene.beam.thickness_profile(),
                                                     BaseExcitation::from_scene(scene.excitation));
    if (setting.integrator != "explicit")
      throw InputError("ROM integrator '" + setting.integrator + "' is not one of explicit, implicit");
    return std::make_unique<RomBeamSystem>(std::move(rom), scene.beam.thickness_profile(),
                                           BaseExcitation::from_scene(scene.excitation));
  }

  ModelRun run_setting(const Scene &scene_in, const ModelSetting &setting, const double window,
                       const std::function<void(const PeriodRecord &)> &on_period)
  {
    ModelRun run;
    run.setting      = setting;
    const auto start = std::chrono::steady_clock::now();
    try
      {
        Scene scene                   = scene_in;
        scene.time_stepping.time_step = setting.time_step;
        scene.initial.slider_position_over_L += setting.slider_offset_over_L;
        if (setting.family == "fe" && setting.n_elements)
          scene.discretisation.n_elements = setting.n_elements;
        auto beam          = make_beam_model(scene, setting);
        RunOptions options = RunOptions::from_scene(scene);
        options.end_time   = window;
        options.progress_interval = 1e9;
        AdaptationRun adaptation(scene, *beam, options);
        adaptation.on_period = [&run, &on_period](const PeriodRecord &p) {
          run.periods.push_back(p);
          if (on_period)
            on_period(p);
        };
        run.result = adaptation.run();
        run.ok     = run.result.status == RunStatus::completed;
        run.message = run.result.message;
      }
    catch (const std::exception &e)
      {
        run.ok      = false;
        run.message = e.what();
      }
    run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
  }

  double cost_per_simulated_second(const ModelSetting &setting, const Scene &scene)
  {
    const double per_step =
      setting.family == "fe"
        ? 40. * (setting.n_elements ? setting.n_elements : scene.discretisation.n_elements) / 32.
        : 0.97 + 0.03 * (setting.n_modes / 5.) * (setting.n_modes / 5.);
    return per_step / setting.time_step;
  }
} // namespace beamslider
