// The `beamslider` command line as a library function: the CLI11 parser of
// every sub-command, the dispatch to the run_* functions (commands.h) and the
// mapping of errors to exit statuses and one-line messages. The executable's
// main() (beamslider.cc) and the Python module (python/) both call it, so that
// a study run from Python is the same run, with the same checks and the same
// messages, as from the shell.
#include "verification/cli/command_line.h"

#include "io/interruption.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "fem/petsc_session.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "verification/cli/cli_validators.h"
#include "verification/cli/commands.h"
#include "runtime/mpi_cells.h"
#include "io/console.h"
#include "verification/studies/fe_rom_study.h"

#include <deal.II/base/exceptions.h>

#include <mpi.h>

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstring>
#include <functional>
#include <iostream>
#include <sstream>

namespace beamslider
{
namespace
{
// The parsed sub-command's options with their effective values (given, or
// the default), recorded for the output folder's command.prm.
void record_effective_options(const CLI::App &command)
{
  std::vector<beamslider::CommandSetting> settings;
  for (const CLI::Option *option : command.get_options())
    {
      const std::string name = option->get_single_name(); // "end-time" for --end-time
      if (name == "help" || name.empty() || option->get_group().empty()) // hidden: internal
        continue;
      std::string value;
      if (option->count() > 0)
        for (const std::string &r : option->results())
          value += (value.empty() ? "" : ", ") + r;
      else if (option->get_default_str() != "[]") // an empty list: nothing
        value = option->get_default_str();
      settings.push_back({name, value, option->get_description()});
    }
  beamslider::record_command_settings(command.get_name(), settings);
}

// The exit status of the exception in flight, its one-line message on
// `errors`: 2 bad input, 1 a failure or a result not written, 128 + the
// signal when interrupted (run_beamslider says so).
int exit_status_of_failure(std::ostream &errors)
{
  try
    {
      throw;
    }
    catch (const InputError &e)
      {
        // Values the user gave may hold a line break or an escape sequence.
        errors << "error: " << one_line(e.what()) << std::endl;
        return 2;
      }
    catch (const std::invalid_argument &e)
      {
        // The library's checks of values that came from the scene or the
        // options (a time step above the model's stability limit, ...).
        errors << "error: " << one_line(e.what()) << std::endl;
        return 2;
      }
    catch (const FileReadError &e)
      {
        // A file the run was given or had to read back (io/input_file.h).
        errors << "error: " << one_line(e.what()) << std::endl;
        return 2;
      }
    catch (const Interrupted &)
      {
        // A solver, Newton loop or continuation stopped for Ctrl-C or kill;
        // run_beamslider says so and gives 128 + the signal.
        return interruption_exit_code();
      }
    catch (const FolderInUseError &e)
      {
        errors << "error: " << e.what() << std::endl; // nothing was written: not a failed write
        return 1;
      }
    catch (const OutputError &e)
      {
        errors << "error: results not written: " << one_line(e.what()) << std::endl;
        return 1;
      }
    catch (const dealii::ExceptionBase &e)
      {
        // deal.II's what() carries a stack trace and source lines that mean
        // nothing to a user; its name and additional information do.
        std::ostringstream info;
        e.print_info(info);
        errors << "beamslider failed: " << e.get_exc_name() << ": " << info.str() << std::endl;
        return 1;
      }
    catch (const std::exception &e)
      {
        const std::string what = e.what();
        errors << "beamslider failed: " << (what.empty() ? "unknown error" : what) << std::endl;
        return 1;
      }
  return 1;
}

// `simulate --resume DIR` continues the run of DIR's checkpoint: what
// defines that run cannot be given beside it.
void refuse_what_resume_takes_from_the_checkpoint(const CLI::App &simulate_cmd, const SimulateOptions &simulate)
{
  if (simulate.resume_dir.empty())
    return;
  for (const char *given : {"scene", "--set", "--case", "--model", "--output"})
    if (simulate_cmd.get_option(given)->count() > 0)
      throw InputError(std::string("simulate --resume takes the scene, case, model, parameters and folder from the "
                                   "checkpoint; ") +
                       given + " cannot be given with it (only --end-time, --checkpoint-every)");
}

// Adds the options every sub-command has (scene, --set, --output, --quiet).
using AddCommon = std::function<void(CLI::App *)>;

// The same options mean the same on every sub-command: the scene (a path or
// a name in meshes/, default mueller2023), --set, --output, --quiet.
AddCommon common_options(CommonOptions &common, bool &quiet)
{
  return [&common, &quiet](CLI::App *sub) {
    sub->add_option("scene", common.scene_file, "scene file (.prm) or name in meshes/ (default: mueller2023)");
    sub->add_option("--set", common.overrides, "override a parameter: \"Section/Name=value\" (repeatable)");
    sub->add_option("--output,-o", common.output_dir, "output folder (default reports/<scene>/<command>)");
    sub->add_flag("--quiet,-q", quiet,
                  "nothing on standard output (no progress, timing or summary); the results are in the output "
                  "folder, errors and warnings still on standard error");
  };
}

// One function a sub-command: it declares the sub-command and its options,
// which parse into the struct it is given, and returns the sub-command.
CLI::App *declare_modes(CLI::App &app, const AddCommon &add_common, ModesOptions &modes)
{
  auto *modes_cmd = app.add_subcommand("modes", "linear bending modes of the bare beam or with a bonded slider");
  add_common(modes_cmd);
  modes_cmd->add_option("--slider-at", modes.slider_at, "bond the slider at x_C/L = S (seed Eq. 5 comparison)")
    ->check(finite_in(0., 1.));
  modes_cmd->add_option("--modes", modes.n_modes, "number of modes")->check(integer_in(1, 50));
  modes_cmd->add_option("--elements", modes.n_elements, "FE elements (default: the scene's)")->check(integer_in(1, 4096));
  return modes_cmd;
}

CLI::App *declare_coefficients(CLI::App &app, const AddCommon &add_common, CoefficientsOptions &coefficients)
{
  auto *coefficients_cmd = app.add_subcommand("coefficients", "modal cubic stiffness coefficients (coefficients.csv)");
  add_common(coefficients_cmd);
  coefficients_cmd->add_option("--method", coefficients.method,
                               "analytic | step | step-condensed | ice (a solid scene: exact | step | step-condensed | ice; "
                               "analytic means exact there)")
    ->check(CLI::IsMember({"analytic", "exact", "step", "step-condensed", "ice"}));
  auto *coefficient_modes =
    coefficients_cmd->add_option("--modes", coefficients.n_modes, "N (default: the scene's)")->check(integer_in(1, 10));
  coefficients_cmd
    ->add_option("--mode-indices", coefficients.mode_indices,
                 "a solid scene: the modes by their index in modes.csv (any shape), e.g. 1,2,4")
    ->delimiter(',')
    ->check(integer_in(1, 50))
    ->excludes(coefficient_modes);
  return coefficients_cmd;
}

CLI::App *declare_statics(CLI::App &app, const AddCommon &add_common, StaticsOptions &statics)
{
  auto *statics_cmd =
    app.add_subcommand("statics", "nonlinear statics under a uniform line load or a modal load (statics.csv)");
  add_common(statics_cmd);
  auto *line_load_opt =
    statics_cmd->add_option("--line-load", statics.line_load_n_per_m, "uniform dead load Q [N/m], positive downward")
      ->check(finite_nonzero());
  auto *modal_load_opt =
    statics_cmd
      ->add_option("--modal-load", statics.modal_load,
                   "modal load f [N kg^-1/2]: the dead load M phi_n f on bending mode n (--mode), along +phi_n")
      ->check(finite_nonzero())
      ->excludes(line_load_opt);
  statics_cmd->add_option("--mode", statics.mode, "n of --modal-load: the n-th bending mode")
    ->check(integer_in(1, 10))
    ->needs(modal_load_opt);
  statics_cmd->add_option("--steps", statics.n_steps, "equal load steps to the full load")
    ->check(integer_in(1, 10000));
  return statics_cmd;
}

CLI::App *declare_backbone(CLI::App &app, const AddCommon &add_common, BackboneOptions &backbone)
{
  auto *backbone_cmd = app.add_subcommand("backbone", "backbone curve by harmonic balance (backbone.csv)");
  add_common(backbone_cmd);
  backbone_cmd->add_option("--model", backbone.model, "rom | fe")->check(CLI::IsMember({"rom", "fe"}));
  backbone_cmd->add_option("--modes", backbone.n_modes, "ROM modes N (default: the scene's; at most the scene's limit, 40)")->check(integer_in(1, 40));
  backbone_cmd->add_option("--harmonics", backbone.n_harmonics, "harmonics H")->check(integer_in(1, 40));
  backbone_cmd->add_option("--max-amplitude", backbone.max_amplitude_over_h, "largest w(L/2)/h, in (0.01, 10]")->check(finite_in(0.01, 10., Bound::open, Bound::closed));
  return backbone_cmd;
}

CLI::App *declare_simulate(CLI::App &app, const AddCommon &add_common, SimulateOptions &simulate)
{
  auto *simulate_cmd = app.add_subcommand("simulate", "free-slider simulation (trace.csv, trace.png)");
  add_common(simulate_cmd);
  simulate_cmd->add_option("--model", simulate.model, "rom | fe | auto")->check(CLI::IsMember({"rom", "fe", "auto"}));
  simulate_cmd->add_option("--case", simulate.case_name, "a published case or ablation (see doc/scenes.md)");
  simulate_cmd->add_option("--end-time", simulate.end_time, "simulated time [s]")->check(finite_positive());
  simulate_cmd->add_flag("--animate", simulate.animate, "also write a ParaView animation");
  simulate_cmd->add_option("--tolerance", simulate.tolerance, "--model auto: the largest distance of the end position x_C/L to the FE reference (W1, upper end of its 90 % interval; default: the reference's own interval to its refinement, at least 0.005)")->check(finite_positive());
  simulate_cmd->add_option("--checkpoint-every", simulate.checkpoint_every,
                           "write checkpoint.bin every S simulated seconds (resume with --resume DIR)")
    ->check(finite_positive());
  simulate_cmd->add_option("--resume", simulate.resume_dir,
                           "continue the run whose checkpoint.bin is in DIR (scene, case, model and parameters from "
                           "it; --end-time may extend it)");
  simulate_cmd->add_flag("--allow-large-output", simulate.allow_large_output,
                         "allow a trace of more than " + std::to_string(static_cast<long>(SimulateOptions::max_trace_rows)) +
                           " rows (End time x Output rate)");
  return simulate_cmd;
}

CLI::App *declare_branches(CLI::App &app, const AddCommon &add_common, BranchesOptions &branches)
{
  auto *cmd = app.add_subcommand("branches", "the held slider's slow manifold: periodic orbits by shooting and "
                                             "continuation, attractor probes (branches.csv, attractor.csv)");
  add_common(cmd);
  cmd->add_option("--case", branches.case_name, "a published case or ablation (its excitation and slider; see doc/scenes.md)");
  cmd->add_option("--from", branches.low_over_L, "smallest x_C/L (default: the half of the beam holding the start)")
    ->check(finite_in(0., 1.));
  cmd->add_option("--to", branches.high_over_L, "largest x_C/L")->check(finite_in(0., 1.));
  cmd->add_option("--probe-step", branches.probe_step_over_L, "x_C/L between attractor probes")->check(finite_in(1e-3, 0.5));
  cmd->add_option("--settle-periods", branches.settle_periods, "excitation periods each probe settles before its section")
    ->check(CLI::Range(0u, 100000u));
  return cmd;
}

CLI::App *declare_sweep(CLI::App &app, const AddCommon &add_common, SweepOptions &sweep)
{
  auto *sweep_cmd = app.add_subcommand("sweep", "prescribed slider position sweeps (pcs.csv)");
  add_common(sweep_cmd);
  sweep_cmd->add_option("--model", sweep.model, "rom | fe")->check(CLI::IsMember({"rom", "fe"}));
  sweep_cmd->add_option("--case", sweep.case_name, "a published case or ablation (its excitation and slider; see doc/scenes.md)");
  sweep_cmd->add_option("--step", sweep.step_over_L, "position step dx_C/L")->check(finite_in(1e-4, 0.1));
  sweep_cmd->add_option("--settle-time", sweep.settle_time, "simulated time per position before averaging [s]")
    ->check(finite_non_negative());
  sweep_cmd->add_option("--average-time", sweep.average_time, "simulated time averaged per position [s]")
    ->check(finite_positive());
  sweep_cmd->add_option("--from", sweep.low_over_L, "smallest x_C/L (default: the half of the beam holding the start)")
    ->check(finite_in(0., 1.));
  sweep_cmd->add_option("--to", sweep.high_over_L, "largest x_C/L")->check(finite_in(0., 1.));
  sweep_cmd->add_option("--free-time", sweep.free_time, "free-slider run overlaid [s] (default: the scene's end time; 0: none)")
    ->check(finite_non_negative());
  sweep_cmd->add_option("--against", sweep.against,
                        "another sweep's folder (same positions, e.g. the other model) to compare with: "
                        "comparison.csv, crossings.csv, pcs_compare.png");
  return sweep_cmd;
}

CLI::App *declare_animate(CLI::App &app, const AddCommon &add_common, AnimateOptions &animate)
{
  auto *animate_cmd = app.add_subcommand("animate", "ParaView time series (.pvd of .vtu/.vtp) of a run");
  add_common(animate_cmd);
  animate_cmd->add_option("--model", animate.model, "fe | rom")->check(CLI::IsMember({"rom", "fe"}));
  animate_cmd->add_option("--case", animate.case_name, "a published case or ablation (see doc/scenes.md)");
  animate_cmd->add_option("--end-time", animate.end_time, "simulated time [s]")->check(finite_positive());
  animate_cmd->add_option("--start-time", animate.start_time, "first frame time [s]")->check(finite_non_negative());
  animate_cmd->add_option("--frame-rate", animate.frame_rate, "frames per simulated second")->check(finite_positive());
  animate_cmd->add_option("--magnification", animate.magnification, "deformation scale")->check(finite_positive());
  return animate_cmd;
}

CLI::App *declare_ensemble(CLI::App &app, const AddCommon &add_common, EnsembleOptions &ensemble)
{
  auto *ensemble_cmd = app.add_subcommand("ensemble", "K runs differing by a tiny start shift: outcome statistics");
  add_common(ensemble_cmd);
  ensemble_cmd->add_option("--model", ensemble.model, "rom | fe | auto (the cheapest model the scene's error ladder puts within --tolerance of the FE reference, cached per scene)")->check(CLI::IsMember({"rom", "fe", "auto"}));
  ensemble_cmd->add_option("--tolerance", ensemble.tolerance, "--model auto: the largest distance of the end position x_C/L to the FE reference (W1, upper end of its 90 % interval; default: the reference's own interval to its refinement, at least 0.005)")->check(finite_positive());
  ensemble_cmd->add_option("--integrator", ensemble.integrator,
                           "ROM time integrator: explicit (published) | implicit (the FE's implicit midpoint rule)")
    ->check(CLI::IsMember({"explicit", "implicit"}));
  ensemble_cmd->add_option("--theta", ensemble.theta,
                           "theta of the implicit ROM's Moreau-Jean scheme, 0.5 (midpoint rule, default) to 1: above "
                           "0.5 it damps the modes the step cannot resolve, as the FE reference does")
    ->check(finite_in(0.5, 1.));
  ensemble_cmd->add_option("--coefficients", ensemble.coefficients,
                           "ROM cubic coefficients: analytic | step-condensed | ice on a beam scene (default "
                           "analytic); ice | step | exact | analytic from the solid on a solid scene (default ice)");
  ensemble_cmd->add_option("--case", ensemble.case_name, "a published case or ablation (see doc/scenes.md)");
  ensemble_cmd->add_option("--members", ensemble.members, "K members")->check(integer_in(1, 1000));
  ensemble_cmd->add_option("--perturbation", ensemble.perturbation, "start shift of x_C/L per member index")
    ->check(finite_in(0., 1e-3));
  ensemble_cmd->add_option("--end-time", ensemble.end_time, "simulated time per member [s]")->check(finite_positive());
  ensemble_cmd->add_option("--against", ensemble.against, "compare with the ensemble in this folder (its members.csv)");
  ensemble_cmd->add_flag("--unchecked", ensemble.unchecked,
                         "fe: skip the convergence check (the same ensemble at Δt/2, Δt/4, … until it ends where Δt "
                         "ends); the result says it is unchecked");
  return ensemble_cmd;
}

CLI::App *declare_map(CLI::App &app, const AddCommon &add_common, MapOptions &map)
{
  auto *map_cmd = app.add_subcommand("map", "the adaptation over a grid of parameters, one run or ensemble per cell "
                                            "(under mpirun: cells spread over the ranks); restartable");
  add_common(map_cmd);
  map_cmd->add_option("--frequency", map.frequency, "excitation frequency axis [Hz]: A:B:STEP or one value");
  map_cmd->add_option("--acceleration", map.acceleration, "base acceleration amplitude axis [m/s^2]: A:B:STEP or one value");
  map_cmd->add_option("--start", map.start, "start position axis x_C/L: A:B:STEP or one value");
  map_cmd->add_option("--axis", map.axes, "any scene parameter as an axis: \"Section/Name=A:B:STEP\" (repeatable)");
  map_cmd->add_option("--model", map.model, "rom | fe | auto (one model for every cell: the one --model auto picks on the scene without the axes)")->check(CLI::IsMember({"rom", "fe", "auto"}));
  map_cmd->add_option("--tolerance", map.tolerance, "--model auto: the largest distance of the end position x_C/L to the FE reference (W1, upper end of its 90 % interval; default: the reference's own interval to its refinement, at least 0.005)")->check(finite_positive());
  map_cmd->add_option("--members", map.members, "K members per cell (start x_C/L + m x perturbation)")
    ->check(integer_in(1, 1000));
  map_cmd->add_option("--perturbation", map.perturbation, "start shift of x_C/L per member index")
    ->check(finite_in(0., 1e-3));
  map_cmd->add_option("--end-time", map.end_time, "simulated time per member [s]")->check(finite_positive());
  return map_cmd;
}

CLI::App *declare_identify(CLI::App &app, const AddCommon &add_common, IdentifyOptions &identify)
{
  auto *identify_cmd = app.add_subcommand("identify", "the seed's System 1 facts over a grid of unknown parameters "
                                                      "(one map per fact); scores each candidate");
  add_common(identify_cmd);
  identify_cmd->add_option("--axis", identify.axes, "an unknown scene parameter: \"Section/Name=A:B:STEP\" (repeatable)");
  identify_cmd->add_option("--fact", identify.facts, "only this fact, by id (repeatable; default: every fact)");
  identify_cmd->add_option("--members", identify.members, "K members per run (start x_C/L + m x perturbation)")
    ->check(integer_in(1, 1000));
  identify_cmd->add_option("--perturbation", identify.perturbation, "start shift of x_C/L per member index")
    ->check(finite_in(0., 1e-3));
  return identify_cmd;
}

CLI::App *declare_verify(CLI::App &app, const AddCommon &add_common, VerifyOptions &verify)
{
  auto *verify_cmd = app.add_subcommand("verify", "write the verification report (reports/<scene>/report.md)");
  add_common(verify_cmd);
  auto *verify_full = verify_cmd->add_flag("--full", verify.full, "run the long studies too");
  verify_cmd
    ->add_flag("--diagnostics", verify.diagnostics,
               "with --full: the error ladder's diagnostic rungs too (the midpoint-rule FE in dt, the ROM with all "
               "modes; about 26 min more on 2 cores)")
    ->needs(verify_full);
  verify_cmd->add_option("--section", verify.sections, "write only this section (1-8; repeatable)")
    ->check(integer_in(1, 8));
  // Not for users (hidden): how verify starts its section 8 in a second process.
  verify_cmd->add_option("--part-file", verify.part_file, "")->group("");
  return verify_cmd;
}

CLI::App *declare_ladder(CLI::App &app, const AddCommon &add_common, LadderOptions &ladder)
{
  auto *ladder_cmd = app.add_subcommand("ladder", "the error ladder alone (report section 5.1-5.2): model settings "
                                                  "as ensembles against the FE reference");
  add_common(ladder_cmd);
  ladder_cmd->add_flag("--full", ladder.full, "the rungs of verify --full, the speed-accuracy front's candidates among them, each explicit ROM also at dt/2; writes front.csv (8 members over 40 s)");
  ladder_cmd->add_flag("--diagnostics", ladder.diagnostics,
                       "the rungs of --full and the diagnostic rungs (the midpoint-rule FE in dt, the ROM with all "
                       "modes; 4 members each)");
  ladder_cmd->add_option("--rung", ladder.rungs,
                         "run only this rung, by name, of the ladder with diagnostics and front candidates (repeatable; the reference, the scene's FE model, always runs)");
  ladder_cmd->add_option("--members", ladder.members, "members per rung (default 4, or 8 with --full)")
    ->check(integer_in(2, 1000));
  ladder_cmd->add_option("--end-time", ladder.end_time, "simulated time per member [s] (default 25, or 40 with --full)")
    ->check(finite_positive());
  return ladder_cmd;
}

int parse_and_run(int argc, char **argv, std::ostream &errors, StudyHandover *handover)
{
  CLI::App app{"beamslider: FE and reduced-order models of a beam with a sliding mass (cross-verification suite)"};
  app.require_subcommand(1);
  // Every option keeps its default as text, for command.prm.
  app.option_defaults()->always_capture_default();

  CommonOptions common;
  bool quiet = false;
  common.scene_file           = "mueller2023";
  const AddCommon add_common = common_options(common, quiet);

  ModesOptions modes;
  auto *modes_cmd = declare_modes(app, add_common, modes);
  CoefficientsOptions coefficients;
  auto *coefficients_cmd = declare_coefficients(app, add_common, coefficients);
  StaticsOptions statics;
  auto *statics_cmd = declare_statics(app, add_common, statics);
  BackboneOptions backbone;
  auto *backbone_cmd = declare_backbone(app, add_common, backbone);
  SimulateOptions simulate;
  auto *simulate_cmd = declare_simulate(app, add_common, simulate);
  SweepOptions sweep;
  auto *sweep_cmd = declare_sweep(app, add_common, sweep);
  BranchesOptions branches;
  auto *branches_cmd = declare_branches(app, add_common, branches);
  AnimateOptions animate;
  auto *animate_cmd = declare_animate(app, add_common, animate);
  EnsembleOptions ensemble;
  auto *ensemble_cmd = declare_ensemble(app, add_common, ensemble);
  MapOptions map;
  auto *map_cmd = declare_map(app, add_common, map);
  IdentifyOptions identify;
  auto *identify_cmd = declare_identify(app, add_common, identify);
  VerifyOptions verify;
  auto *verify_cmd = declare_verify(app, add_common, verify);
  LadderOptions ladder;
  auto *ladder_cmd = declare_ladder(app, add_common, ladder);

  auto *template_cmd = app.add_subcommand("scene-template", "print a scene file with every parameter, its unit and range");

  try
    {
      app.parse(argc, argv);
    }
  catch (const CLI::CallForHelp &e)
    {
      return app.exit(e);
    }
  catch (const CLI::CallForAllHelp &e)
    {
      return app.exit(e);
    }
  catch (const CLI::ParseError &e)
    {
      // One readable line and status 2, like every other input error.
      errors << "error: " << describe_parse_error(app, e, argc, argv) << "\n(see 'beamslider --help' or 'beamslider COMMAND --help')"
                << std::endl;
      return 2;
    }

  set_quiet(quiet);
  record_effective_options(*app.get_subcommands().front());
  try
    {
      if (handover && !*sweep_cmd && !*ensemble_cmd && !*map_cmd && !*ladder_cmd)
        StudyHandover::refuse(handover, app.get_subcommands().front()->get_name());
      if (*modes_cmd)
        return run_modes(common, modes);
      if (*coefficients_cmd)
        return run_coefficients(common, coefficients);
      if (*statics_cmd)
        return run_statics(common, statics);
      for (const CLI::App *one : {backbone_cmd, simulate_cmd, sweep_cmd, branches_cmd, animate_cmd, identify_cmd})
        if (*one)
          require_one_process(one->get_name());
      if (*backbone_cmd)
        return run_backbone(common, backbone);
      if (*simulate_cmd)
        {
          refuse_what_resume_takes_from_the_checkpoint(*simulate_cmd, simulate);
          return run_simulate(common, simulate);
        }
      if (*sweep_cmd)
        return run_sweep(common, sweep, handover);
      if (*branches_cmd)
        return run_branches(common, branches);
      if (*animate_cmd)
        return run_animate(common, animate);
      if (*ensemble_cmd)
        return run_ensemble_command(common, ensemble, handover);
      if (*map_cmd)
        return run_map(common, map, handover);
      if (*identify_cmd)
        return run_identify(common, identify);
      if (*verify_cmd)
        return run_verify(common, verify);
      if (*ladder_cmd)
        return run_ladder_command(common, ladder, handover);
      if (*template_cmd)
        {
          // A full disk or a closed pipe must not pass for a written template.
          errno = 0;
          std::cout << scene_template() << std::flush;
          if (!std::cout)
            throw OutputError(std::string("the scene template could not be written to standard output: ") +
                              (errno != 0 ? std::strerror(errno) : "write error"));
          return 0;
        }
    }
  catch (...)
    {
      return exit_status_of_failure(errors);
    }
  return 0;
}
} // namespace

int run_beamslider(int argc, char **argv, std::ostream &errors, StudyHandover *handover)
{
  // Under mpirun every rank runs the command; rank 0 says what went wrong,
  // once. Another rank keeps its message where rank 0 meets the same error:
  // bad input (every rank reads the same), an interruption (mpirun passes
  // the signal to all), or any error of a command that runs on MPI (an
  // error that arises on some ranks only is shared, output/collective_failure.h).
  // A command without MPI runs on each rank alone, so that rank's own error
  // (its folder in use by the other rank) is said, with its rank.
  const unsigned int rank = launch_rank();
  clear_output_failures();
  // A solid's reduced model (built on first use by any command) says what it builds.
  set_model_build_progress([](const std::string &line) { console() << line << std::endl; });
  std::ostringstream messages; // also the first line of run.txt's `ended:` record
  int status = parse_and_run(argc, argv, messages, handover);
  if (status == 0 && !output_failures().empty())
    status = 1; // a chart or another result file was not written
  if (interruption_requested())
    {
      messages << "interrupted by signal " << interruption_signal() << std::endl;
      status = interruption_exit_code();
    }
  if (rank == 0)
    errors << messages.str() << std::flush;
  else if (status != 2 && status < 128 && (!mpi_started() || a_rank_was_lost()) && !messages.str().empty())
    errors << "rank " << rank << ": " << messages.str() << std::flush;
  if (!record_run_end(status, messages.str(), errors) && status == 0)
    status = 1;
  // Under mpirun no rank may exit before rank 0 has recorded the end: a
  // non-zero exit (130/143 after a Ctrl-C) makes mpirun kill the others.
  // A rank that does not come within a minute has died or hangs: the job
  // is ended, with a message, instead of waiting for it.
  constexpr double meet_seconds = 60;
  if (a_rank_was_lost())
    {
      // Nobody to wait for: the error above named the rank that died.
      MPI_Abort(MPI_COMM_WORLD, status ? status : 1);
    }
  if (!all_ranks_meet(meet_seconds))
    {
      errors << "rank " << rank << ": the other ranks did not end within " << meet_seconds
             << " s (one died or hangs); ending the job" << std::endl;
      MPI_Abort(MPI_COMM_WORLD, status ? status : 1);
    }
  release_output_folders(); // the command's folders are free again (the Python module lives on)
  return status;
}
} // namespace beamslider
