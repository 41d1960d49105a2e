// `beamslider simulate SCENE --model rom|fe|auto [--case NAME]`: the free
// slider on the ROM (N modes of the FE basis, analytic coefficients) or on the
// FE beam, through the shared contact code (contact/adaptation_run.h).
//
// Writes into the output folder:
//   trace.csv    t_s,slider_x_over_L,slider_z_m,slider_beta_rad,w_center_m,
//                w_probe_m,amplitude_over_h at the scene's output rate (w
//                relative to the base; probe at 4L/7; amplitude = (max − min)/2
//                of w(L/2) over the last excitation period, / h)
//   periods.csv  one row per excitation period, with the energy bookkeeping
//   trace.png    beam deflection at L/2 and slider position against time
//                (like seed Figs. 5–8)
//   summary.md   settings, cost, status and a one-line verdict
//   animation.pvd (+ files) with --animate: the last 0.1 s at 2000 frames/s
// Both CSV files are flushed as the run goes: a stopped run keeps them.
#include "contact/adaptation_run.h"
#include "contact/interruption.h"
#include "contact/output_file.h"
#include "fem/vtk_animation.h"
#include "meshes/scene.h"
#include "verification/commands.h"
#include "verification/fe_rom_study.h"
#include "verification/simulation_cases.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // The animation window of --animate: the end of the run, where the
    // adaptation has happened, at a frame rate that resolves the excitation.
    constexpr double animation_window = 0.1;   // [s]
    constexpr double animation_rate   = 2000.; // frames per simulated second
  } // namespace

  SimulationOutcome run_simulation(const CommonOptions &common, const SimulateOptions &options, const bool verbose)
  {
    if (options.model != "rom" && options.model != "fe" && options.model != "auto")
      throw InputError("--model '" + options.model + "' is not one of rom, fe, auto");
    if (options.model == "auto" && !options.tolerance)
      throw InputError("--model auto needs --tolerance (the largest acceptable slider-drift error, e.g. 0.2)");
    if (options.end_time && !(*options.end_time > 0.))
      throw InputError("--end-time " + std::to_string(*options.end_time) + " s must be > 0");

    const std::string scene_file = resolve_scene_path(common.scene_file);
    const SimulationCase *the_case = options.case_name.empty() ? nullptr : &find_case(options.case_name);
    SimulationOutcome outcome;
    Scene &scene = outcome.scene;
    std::vector<std::string> modified; // the case's own parameters the user changed
    scene = the_case ? read_case_scene(scene_file, *the_case, common.overrides, &modified)
                     : read_scene(scene_file, common.overrides);
    if (options.end_time)
      {
        scene.time_stepping.end_time = *options.end_time;
        validate_scene(scene); // the step count limit
      }
    const double n_rows = scene.time_stepping.end_time * scene.time_stepping.output_rate;
    if (n_rows > SimulateOptions::max_trace_rows && !options.allow_large_output)
      {
        std::ostringstream m;
        m << "End time " << scene.time_stepping.end_time << " s at Output rate " << scene.time_stepping.output_rate
          << " 1/s would write " << n_rows << " rows to trace.csv, more than " << SimulateOptions::max_trace_rows
          << " (about 1 GB); lower 'Time stepping/Output rate' or pass --allow-large-output";
        throw InputError(m.str());
      }
    const std::string dir = outcome.dir =
      prepare_output_dir(common, scene.name, the_case ? "simulate/" + the_case->name : std::string("simulate"));

    // The model: as asked, or the cheapest that the speed–accuracy study says
    // meets the tolerance on this scene.
    ModelSetting &setting = outcome.setting;
    setting.family    = options.model == "fe" ? "fe" : "rom";
    setting.n_modes   = scene.discretisation.n_modes;
    setting.n_elements = scene.discretisation.n_elements;
    setting.time_step = scene.time_stepping.time_step;
    std::string &why = outcome.why;
    if (options.model == "auto")
      {
        std::cout << "simulate --model auto: running the candidate models over 0.5 s against the FE reference ..."
                  << std::endl;
        setting = choose_model(scene, *options.tolerance, why);
        std::cout << why << std::endl;
        scene.time_stepping.time_step = setting.time_step;
      }
    std::unique_ptr<BeamSystem> beam = make_beam_model(scene, setting);
    const double k_ax = scene.discretisation.geometric_nonlinearity ? scene.supports.membrane_stiffness(scene.beam) : 0.;

    const double end_time = scene.time_stepping.end_time;
    std::cout << "simulate " << scene.name << (the_case ? " --case " + the_case->name : std::string()) << ": "
              << setting.label() << ", " << end_time << " s (" << std::llround(end_time / scene.time_stepping.time_step)
              << " steps), output in " << dir << std::endl;

    RunOptions run_options        = RunOptions::from_scene(scene);
    run_options.progress_interval = std::max(1., end_time / 20.);
    if (!(scene.time_stepping.time_step <= beam->max_stable_time_step()))
      {
        std::ostringstream m;
        m << "Parameter 'Time stepping/Time step' = " << scene.time_stepping.time_step
          << " s is not allowed: the " << setting.label() << " is stable only for time steps up to "
          << beam->max_stable_time_step() << " s (explicit scheme: 2/omega_max)";
        throw InputError(m.str());
      }
    AdaptationRun run(scene, *beam, run_options);
    OutputFile trace_file(dir + "/trace.csv"), period_file(dir + "/periods.csv");
    TraceCsvWriter trace(trace_file.stream(), 1000, trace_file.path());
    PeriodCsvWriter period_writer(period_file.stream(), period_file.path());
    std::vector<PeriodRecord> periods;
    run.on_trace_row = [&trace](const TraceRow &row) { trace.write(row); };
    run.on_period    = [&](const PeriodRecord &r) {
      period_writer.write(r);
      periods.push_back(r);
    };
    if (verbose)
      run.on_progress = [](const RunProgress &p) {
        std::cout << "  t = " << std::fixed << std::setprecision(1) << p.t << " / " << p.end_time
                  << " s, x_C/L = " << std::setprecision(3) << p.slider_x_over_L << ", amplitude "
                  << p.amplitude_over_h << " h, " << std::setprecision(0) << p.steps_per_second << " steps/s"
                  << std::endl
                  << std::defaultfloat;
      };

    const auto start = std::chrono::steady_clock::now();
    RunResult result;
    std::unique_ptr<VtkAnimationWriter> animation;
    if (options.animate)
      {
        const double t_first = std::max(0., end_time - animation_window);
        result               = run.run_until(t_first);
        animation            = std::make_unique<VtkAnimationWriter>(dir, 1.);
        for (long k = 0; result.status == RunStatus::completed; ++k)
          {
            const double t_frame = t_first + k / animation_rate;
            if (t_frame > end_time + 1e-12)
              break;
            const RunResult part = run.run_until(t_frame);
            result.status        = part.status;
            result.message       = part.message;
            result.n_steps += part.n_steps;
            result.t_end = part.t_end;
            if (part.status != RunStatus::completed)
              break;
            animation->write(make_animation_frame(run.stepper(), sample_beam(*beam, run.state().q, k_ax)));
          }
        animation->finish();
      }
    else
      result = run.run();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    trace.flush();
    trace_file.close();
    period_file.close();

    outcome.result       = result;
    outcome.wall_seconds = wall;
    outcome.verdict      = case_verdict(periods, result);
    const CaseVerdict &verdict = outcome.verdict;
    std::ostringstream summary;
    summary << "# simulate: scene `" << scene.name << "`" << (the_case ? ", case `" + the_case->name + "`" : "") << "\n\n";
    if (the_case && !modified.empty())
      {
        summary << "- Case: " << the_case->name << ", modified: ";
        for (std::size_t i = 0; i < modified.size(); ++i)
          summary << (i ? "; " : "") << modified[i];
        summary << ".\n- Not compared with the published behaviour (" << the_case->published
                << "): the run changes parameters the case fixes.\n";
      }
    else if (the_case)
      {
        summary << "- Case: " << the_case->description << ".\n- Published: " << the_case->published << ".\n";
        const std::string differs = disagreements(outcome.verdict, the_case->expected);
        summary << "- Against the published behaviour: " << (differs.empty() ? "agrees on every stated feature" : "differs: " + differs) << ".\n";
      }
    summary << "- Model: " << setting.label() << ".\n"
            << (why.empty() ? "" : "- Chosen by --model auto:\n\n```\n" + why + "\n```\n\n")
            << "- Simulated " << result.t_end << " s of " << end_time << " s in " << wall << " s wall ("
            << (wall > 0 ? result.n_steps / wall : 0.) << " steps/s).\n"
            << "- Status: " << to_string(result.status) << (result.message.empty() ? "" : ": " + result.message) << ".\n"
            << "- Verdict: " << verdict.line << ".\n"
            << "\nFiles: trace.csv, periods.csv" << (animation ? ", animation.pvd" : "") << ", trace.png.\n";
    write_text_file(dir + "/summary.md", summary.str());
    if (result.status != RunStatus::completed && result.status != RunStatus::slider_at_support)
      std::cerr << "simulate: " << to_string(result.status) << ": " << result.message << std::endl;

    // No chart of an interrupted run: the user asked it to stop.
    if (result.status != RunStatus::interrupted)
      {
        std::ostringstream title;
        title << scene.name << (the_case ? " / " + the_case->name : std::string()) << " (" << setting.label() << ")";
        run_plot_script("plot_trace.py", {dir, title.str(), std::to_string(scene.beam.thickness)});
      }

    if (verbose)
      std::cout << summary.str();
    return outcome;
  }

  int run_simulate(const CommonOptions &common, const SimulateOptions &options)
  {
    const SimulationOutcome outcome = run_simulation(common, options);
    const RunResult &result         = outcome.result;
    // Reaching a support is a physical outcome of the scene (the run stops
    // there by design); a failing solver, a non-finite or unphysical state is
    // not; an interrupted run exits as the signal says (130, 143).
    if (result.status == RunStatus::interrupted)
      return interruption_exit_code();
    return result.status == RunStatus::completed || result.status == RunStatus::slider_at_support ? 0 : 1;
  }
} // namespace beamslider
