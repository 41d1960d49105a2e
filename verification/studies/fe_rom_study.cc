#include "numerics/elapsed.h"
#include "verification/studies/fe_rom_study.h"

#include "contact/beam_system.h"
#include "numerics/stop_request.h"
#include "fem/fe_beam.h"
#include "fem/static_corrections.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/solid_reduced_model.h"
#include "reduced/rom_beam_system.h"
#include "reduced/rom_implicit_beam_system.h"
#include "verification/studies/coefficient_methods.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <utility>

namespace beamslider
{
  std::string ModelSetting::label() const
  {
    std::ostringstream s;
    if (family == "fe")
      s << "FE " << n_elements << " el." << (axial_inertia ? "" : " no axial inertia");
    else
      s << "ROM N=" << n_modes << (n_static_corrections ? "+" + std::to_string(n_static_corrections) + "sc" : "")
        << (n_static_corrections && ritz_blocks > 1
              ? "+" + std::to_string(n_static_corrections * (ritz_blocks - 1)) + "ldr"
              : "")
        << " " << coefficients << (integrator == "implicit" ? " implicit" : "");
    if (damped_modes)
      s << " damped " << damped_modes;
    if (theta != 0.5)
      s << " theta=" << theta;
    s << " dt=" << time_step; // no comma: labels go into CSV cells
    if (slider_offset_over_L != 0)
      s << " x0+" << slider_offset_over_L;
    return s.str();
  }

  namespace
  {
    // Where the solid's model build reports (set_model_build_progress).
    std::function<void(const std::string &)> &model_build_progress()
    {
      static std::function<void(const std::string &)> progress;
      return progress;
    }

    // Everything a solid's modes and coefficients depend on, in full
    // precision; not the slider, excitation or start position, where an
    // ensemble's members differ and still share the model.
    std::string solid_key(const Scene &s, const unsigned int N, const std::string &method)
    {
      std::ostringstream k;
      k << std::setprecision(17) << s.beam.length << ' ' << s.beam.width << ' ' << s.beam.thickness << ' '
        << s.beam.youngs_modulus << ' ' << s.beam.density << ' ' << s.supports.type() << ' '
        << s.supports.rotational_stiffness << ' ' << s.supports.axial_stiffness << ' ' << s.solid.continuum << ' '
        << s.solid.poissons_ratio << ' ' << s.solid.degree << ' ' << s.solid.elements_along_length << ' '
        << s.solid.elements_across_width << ' ' << s.solid.elements_through_thickness << ' ' << s.solid.arch_rise
        << ' ' << s.solid.mesh_file << ' ' << s.solid.loaded_boundary << ' ' << s.solid.materials << ' ' << N
        << ' ' << method;
      for (const std::string &group : s.solid.clamped_boundaries)
        k << ' ' << group;
      return k.str();
    }

    // The solid's reduced model, built once per process and key: the
    // members of an ensemble (threads, or ranks each with its own copy)
    // share it. The lock also keeps two builds (PETSc) from running at once.
    std::shared_ptr<const SolidReducedModel> shared_solid_rom(const Scene &scene, const unsigned int N,
                                                              const std::string &method)
    {
      static std::mutex mutex;
      static std::map<std::string, std::shared_ptr<const SolidReducedModel>> built;
      const std::lock_guard<std::mutex> lock(mutex);
      const std::string key = solid_key(scene, N, method);
      if (const auto found = built.find(key); found != built.end())
        return found->second;
      const auto &progress = model_build_progress();
      auto rom = std::make_shared<const SolidReducedModel>(
        build_solid_reduced_model(scene, N, method, [&progress](const std::string &line) {
          if (progress)
            progress("Building the " + line);
        }));
      if (progress)
        {
          std::ostringstream seconds;
          seconds << std::fixed << std::setprecision(1) << rom->build_seconds;
          progress("Built the solid's reduced model in " + seconds.str() + " s");
        }
      built.emplace(key, rom);
      return rom;
    }
  } // namespace

  void set_model_build_progress(std::function<void(const std::string &)> progress)
  {
    model_build_progress() = std::move(progress);
  }

  ModelSetting scene_model(const Scene &scene, const std::string &family)
  {
    if (family != "rom" && family != "fe")
      throw InputError("--model '" + family + "' is not one of rom, fe");
    ModelSetting s;
    s.family     = family;
    s.n_modes    = scene.discretisation.n_modes;
    s.n_elements = scene.discretisation.n_elements;
    if (family == "rom")
      {
        s.n_static_corrections = scene.discretisation.n_static_corrections;
        s.ritz_blocks          = scene.discretisation.ritz_blocks;
      }
    // A solid scene's ROM takes its coefficients from the solid by ICE
    // (fem/solid_reduced_model.h): what a user who brings a solid wants.
    if (scene.solid.enabled())
      s.coefficients = "ice";
    // Each model family at its own step: the ROM at the scene's Time step,
    // the FE at its FE time step (scene.h says why they differ).
    s.time_step = family == "fe" ? scene.time_stepping.fe_time_step : scene.time_stepping.time_step;
    if (family == "fe")
      s.theta = scene.time_stepping.fe_theta;
    return s;
  }

  ReducedOrderModel make_reduced_model(const Scene &scene, const ModelSetting &setting)
  {
    std::optional<ReducedOrderModel> rom;
    if (scene.solid.enabled())
      {
        // The solid's beam line and its coefficients: the FE beam is not used.
        if (setting.n_static_corrections)
          throw InputError("Parameter 'Discretisation/Static corrections' = " +
                           std::to_string(setting.n_static_corrections) +
                           " is not allowed on a solid scene: only 0 (static corrections are built on the FE beam)");
        const auto solid = shared_solid_rom(scene, setting.n_modes, setting.coefficients);
        rom.emplace(solid->basis, scene.damping_ratio, scene.discretisation.geometric_nonlinearity);
        if (!solid->cubic.empty())
          rom->set_cubic_terms(solid->cubic);
      }
    else
      {
        const FEBeam beam(scene);
        const FEModes modes =
          reduced_basis_vectors(beam, setting.n_modes, setting.n_static_corrections, setting.ritz_blocks);
        ModalBasis basis = make_modal_basis(beam, modes);
        rom.emplace(basis, scene.damping_ratio, scene.discretisation.geometric_nonlinearity);
        if (setting.coefficients != "analytic")
          {
            // STEP amplitude one thickness; ICE at 0.03 h (report section 2.4).
            const double level = setting.coefficients == "ice" ? 0.03 : 1.0;
            rom->set_cubic_terms(compute_coefficients(beam, modes, basis, setting.coefficients, level).fit.cubic);
          }
      }
    if (setting.damped_modes)
      rom->set_damped_modes(setting.damped_modes);
    return std::move(*rom);
  }

  std::unique_ptr<BeamSystem> make_beam_model(const Scene &scene, const ModelSetting &setting)
  {
    if (setting.family == "fe")
      {
        FEBeamOptions options;
        options.n_elements    = setting.n_elements;
        options.damped_modes  = setting.damped_modes;
        options.theta         = setting.theta;
        options.axial_inertia = setting.axial_inertia;
        return make_fe_beam_system(scene, options);
      }
    if (setting.family != "rom")
      throw InputError("model family '" + setting.family + "' is not one of fe, rom");
    ReducedOrderModel rom = make_reduced_model(scene, setting);
    if (!(setting.theta >= 0.5 && setting.theta <= 1.))
      throw InputError("theta = " + std::to_string(setting.theta) + " is outside [0.5, 1]");
    if (setting.integrator == "implicit")
      return std::make_unique<RomImplicitBeamSystem>(std::move(rom), scene.beam.thickness_profile(),
                                                     BaseExcitation::from_scene(scene.excitation), setting.theta);
    if (setting.integrator != "explicit")
      throw InputError("ROM integrator '" + setting.integrator + "' is not one of explicit, implicit");
    if (setting.theta != 0.5)
      throw InputError("theta = " + std::to_string(setting.theta) +
                       " applies to the implicit ROM only (the explicit ROM is the midpoint rule, theta = 0.5)");
    return std::make_unique<RomBeamSystem>(std::move(rom), scene.beam.thickness_profile(),
                                           BaseExcitation::from_scene(scene.excitation));
  }

  void require_stable_time_step(const ModelSetting &setting, const BeamSystem &beam)
  {
    if (!(setting.time_step <= beam.max_stable_time_step()))
      {
        std::ostringstream m;
        m << "Parameter 'Time stepping/" << (setting.family == "fe" ? "FE time step" : "Time step")
          << "' = " << setting.time_step << " s is not allowed: the " << setting.label()
          << " is stable only for time steps up to " << beam.max_stable_time_step()
          << " s (explicit scheme: 2/omega_max)";
        throw InputError(m.str());
      }
  }

  void save_setting(CheckpointWriter &out, const ModelSetting &setting)
  {
    out.put(setting.family);
    out.put(std::uint64_t(setting.n_modes));
    out.put(std::uint64_t(setting.n_static_corrections));
    out.put(std::uint64_t(setting.ritz_blocks));
    out.put(std::uint64_t(setting.n_elements));
    out.put(setting.time_step);
    out.put(setting.coefficients);
    out.put(setting.integrator);
    out.put(setting.axial_inertia);
    out.put(std::uint64_t(setting.damped_modes));
    out.put(setting.theta);
  }

  ModelSetting load_setting(CheckpointReader &in)
  {
    ModelSetting s;
    s.family        = in.get_string();
    s.n_modes       = in.get_uint();
    s.n_static_corrections = in.get_uint();
    s.ritz_blocks          = in.get_uint();
    s.n_elements    = in.get_uint();
    s.time_step     = in.get_double();
    s.coefficients  = in.get_string();
    s.integrator    = in.get_string();
    s.axial_inertia = in.get_bool();
    s.damped_modes  = in.get_uint();
    s.theta         = in.get_double();
    return s;
  }

  ModelRun run_setting(const Scene &scene_in, const ModelSetting &setting, const double window,
                       const std::function<void(const PeriodRecord &)> &on_period)
  {
    ModelRun run;
    run.setting      = setting;
    const auto start = std::chrono::steady_clock::now();
    try
      {
        Scene scene = scene_in;
        scene.initial.slider_position_over_L += setting.slider_offset_over_L; // the member's start
        auto beam          = make_beam_model(scene, setting);
        RunOptions options = RunOptions::from_scene(scene, setting.time_step);
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
    catch (const Interrupted &)
      {
        throw;
      }
    catch (const std::exception &e)
      {
        run.ok      = false;
        run.message = e.what();
      }
    run.wall_seconds = elapsed_seconds(start);
    return run;
  }

  double cost_per_simulated_second(const ModelSetting &setting, const Scene &scene)
  {
    // A ROM's step costs by its coordinates: modes, static corrections and
    // their Ritz blocks.
    const double n_coordinates = setting.n_modes + setting.n_static_corrections * setting.ritz_blocks;
    if (setting.family == "fe")
      return 40. * (setting.n_elements ? setting.n_elements : scene.discretisation.n_elements) / 32. /
             setting.time_step;
    const double explicit_step = 0.97 + 0.03 * (n_coordinates / 5.) * (n_coordinates / 5.);
    return (setting.integrator == "implicit" ? implicit_rom_step_factor : 1.) * explicit_step / setting.time_step;
  }
} // namespace beamslider
