// Beam models from a scene, and one run of a model: the model factory that
// `simulate`, `ensemble`, the error ladder (error_ladder.h) and report
// section 5 use, and the stated cost model by which `--model auto` ranks
// models.
//
// A setting is one model and its numerical parameters:
//   fe   the deal.II beam (fem/fe_beam_system) with n_elements and Δt,
//   rom  the reduced model on the FE modal basis with N modes, cubic
//        coefficients from `analytic | step-condensed | ice`, an integrator
//        (explicit | implicit) and Δt. On a scene with a Solid, the ROM's
//        basis and coefficients (`ice | step | exact | analytic`) come from
//        the solid instead (fem/solid_reduced_model.h); the FE family stays
//        the 1D beam, the transient reference (the solid is not integrated
//        in time).
// Single runs of this system are chaotic (two runs that differ in the last
// digit part after a few dozen periods): compare models as ensembles
// (ensemble.h), not run against run.
#pragma once

#include "numerics/state_bytes.h"
#include "reduced/rom_operator.h"
#include "runs/adaptation_run.h"
#include "runs/trace_analysis.h"
#include "scene/scene.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace beamslider
{
  class BeamSystem;

  struct ModelSetting
  {
    std::string family = "rom"; // fe | rom
    unsigned int n_elements = 0; // fe: 0 = the scene's
    unsigned int n_modes = 5;    // rom
    // rom on a beam scene: static corrections added to the N modes
    // (fem/static_corrections.h), 0 for none.
    unsigned int n_static_corrections = 0;
    // rom with static corrections: their blocks (1: the corrections alone;
    // b > 1 adds b − 1 blocks of load-dependent Ritz vectors).
    unsigned int ritz_blocks = 1;
    // rom: analytic | step-condensed | ice on a beam scene;
    //      ice | step | exact | analytic on a solid scene (from the solid)
    std::string coefficients = "analytic";
    // rom: explicit (the published midpoint step) | implicit (the FE's
    // implicit midpoint rule, reduced/rom_implicit_beam_system.h): the
    // ladder rung that changes only the integrator.
    std::string integrator = "explicit";
    // fe: false gives the axial DoFs no mass (membrane in static equilibrium,
    // the ROM's assumption): the ladder rung "FE without axial inertia".
    bool axial_inertia = true;
    // The modes the modal damping acts on (0: the model's own set: the
    // scene's N for the FE, every kept mode for the ROM). The ladder sets it
    // so that a ROM and the FE beside it damp the same modes.
    unsigned int damped_modes = 0;
    double time_step = 2e-5;     // [s]
    // fe, and rom implicit: θ of the Moreau–Jean scheme (fem/fe_transient.h,
    // reduced/rom_implicit_beam_system.h), 0.5 the midpoint rule; the
    // scene's FE theta for the scene's own FE model.
    double theta = 0.5;
    // Added to the scene's start position x_C/L: a "round-off twin" of a run
    // (e.g. 1e-9) measures how far the rattling alone spreads two runs.
    double slider_offset_over_L = 0;

    std::string label() const;
  };

  // The scene's own model of a family ("rom" | "fe", else InputError): its N
  // modes or elements, analytic coefficients (ICE from the solid on a solid
  // scene), the explicit ROM step; Δt is the scene's Time step for the ROM
  // and its FE time step for the FE.
  ModelSetting scene_model(const Scene &scene, const std::string &family);

  // The beam model of a setting for `scene` (the scene's mesh, damping and
  // excitation; the setting's own parameters). Throws if it cannot be built.
  // On a solid scene the solid's reduced model is built once per process
  // (minutes), and its progress reported to set_model_build_progress's
  // callback.
  std::unique_ptr<BeamSystem> make_beam_model(const Scene &scene, const ModelSetting &setting);

  // The reduced-order model of a "rom" setting for `scene` (its modes,
  // coefficients and damped set; no integrator): what make_beam_model
  // steps, for callers that evaluate it (the Python module's ReducedModel).
  ReducedOrderModel make_reduced_model(const Scene &scene, const ModelSetting &setting);

  // Refuses (InputError, naming the parameter, its value and the bound) a
  // setting whose time step is above the model's stability limit.
  void require_stable_time_step(const ModelSetting &setting, const BeamSystem &beam);

  // A setting in a checkpoint (numerics/state_bytes.h), every field, so
  // that a resumed run rebuilds exactly its model.
  void save_setting(CheckpointWriter &out, const ModelSetting &setting);
  ModelSetting load_setting(CheckpointReader &in);

  // Where the build of a solid's reduced model reports its progress, a line
  // each (without '\n'): the command line sends it to the console
  // (verification/cli/command_line.cc); unset, nothing is reported. Set it
  // before any model is built (the builds of several threads read it).
  void set_model_build_progress(std::function<void(const std::string &)> progress);

  struct ModelRun
  {
    ModelSetting setting;
    std::vector<PeriodRecord> periods;
    RunResult result;
    bool ok = false;        // ran to the end of the window
    std::string message;    // why not
    double wall_seconds = 0; // model set-up + run
  };

  // Runs `setting` on `scene` from t = 0 to `window` seconds. Never throws
  // for a failing model: the failure is recorded in the result. `on_period`
  // (optional) sees every period as it closes, e.g. to stream it to a CSV.
  ModelRun run_setting(const Scene &scene, const ModelSetting &setting, double window,
                       const std::function<void(const PeriodRecord &)> &on_period = {});

  // The cost of simulating one second with a setting, in units of the
  // published ROM's step (N = 5): a stated model, not a clock reading, so
  // that a loaded machine cannot change a choice. Per step, a ROM costs
  // 0.97 + 0.03 (N/5)² units, N its coordinates (modes and static
  // corrections) (the contact part dominates; the cubic force
  // grows like N² but stays small: measured 0.72, 0.80 and 1.1 µs per step
  // for N = 5, 10, 20 in the error ladder's ensembles) and the FE
  // 40 × elements/32 units (~28 µs per step on the default mesh); times the
  // steps per second, 1/Δt. An implicit ROM step costs implicit_rom_step_factor
  // explicit ones of the same basis (its Newton solve).
  double cost_per_simulated_second(const ModelSetting &setting, const Scene &scene);

  // The implicit ROM's step over the explicit one's on the same basis and
  // step: 21 s against 6 s per member (3.4×) for N = 20 at Δt/4 in the error
  // ladder, 3.2× in the published full report's front.
  constexpr double implicit_rom_step_factor = 3.3;

} // namespace beamslider
