// `beamslider simulate SCENE --model rom|fe|auto [--case NAME]`: the free
// slider on the ROM (N modes of the FE basis, analytic coefficients; on a
// scene with a Solid, N modes of the solid with its ICE coefficients) or on
// the FE beam, through the shared contact code (runs/adaptation_run.h).
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
// Its checkpoints (checkpoint.bin, --resume) are in simulate_checkpoint.cc.
#include "runs/adaptation_run.h"
#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/output_file.h"
#include "output/vtk_animation.h"
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/ladder_cache.h"
#include "verification/cli/simulate_run.h"
#include "numerics/elapsed.h"
#include "io/console.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/simulation.h"
#include "verification/studies/simulation_cases.h"

#include <chrono>
#include <filesystem>
#include <optional>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace beamslider
{
  namespace
  {
    using internal::check_checkpoint_is_folders_run;
    using internal::load_checkpoint_to_resume;
    using internal::restore_checkpointed_run;
    using internal::RunCsvFiles;
    using internal::run_identity;
    using internal::SimulationRun;
    using internal::write_checkpoint;

    // The animation window of --animate: the end of the run, where the
    // adaptation has happened, at a frame rate that resolves the excitation.
    constexpr double animation_window = 0.1;   // [s]
    constexpr double animation_rate   = 2000.; // frames per simulated second

    void check_simulate_options(const SimulateOptions &options)
    {
      if (options.checkpoint_every && options.animate)
        throw InputError("--checkpoint-every cannot be combined with --animate");

      if (options.model != "rom" && options.model != "fe" && options.model != "auto")
        throw InputError("--model '" + options.model + "' is not one of rom, fe, auto");
      if (options.end_time && !(*options.end_time > 0.))
        throw InputError("--end-time " + std::to_string(*options.end_time) + " s must be > 0");
    }

    // The scene (and case) as the run uses it, with --end-time; refused if
    // its trace would be too large.
    void read_simulation_scene(SimulationRun &r)
    {
      const SimulateOptions &options = r.options;
      r.scene_file = std::filesystem::absolute(resolve_scene_path(r.common.scene_file)).string();
      r.the_case   = options.case_name.empty() ? nullptr : &find_case(options.case_name);
      Scene &scene = r.outcome.scene;
      scene        = read_command_scene(r.common, options.case_name, &r.modified);
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
    }

    // The run goes in pieces of --checkpoint-every, each ending in a
    // checkpoint: pieces shorter than a time step hold no step, and the run
    // writes checkpoints without getting on (it never ended). The bound is
    // the step of the model the run uses; --model auto has not chosen yet,
    // so it takes the larger of the ROM's and the FE's.
    void check_checkpoint_interval(const SimulationRun &r)
    {
      const SimulateOptions &options = r.options;
      const Scene &scene             = r.outcome.scene;
      const double rom_step = scene_model(scene, "rom").time_step, fe_step = scene_model(scene, "fe").time_step;
      const double step = r.resuming                 ? r.saved.setting.time_step
                          : options.model == "rom"   ? rom_step
                          : options.model == "fe"    ? fe_step
                                                     : std::max(rom_step, fe_step);
      const std::string which =
        r.resuming ? "the resumed run's time step"
        : options.model == "rom" ? "the ROM's 'Time stepping/Time step'"
        : options.model == "fe"  ? "the FE's 'Time stepping/FE time step'"
                                 : "the larger of the ROM's and the FE's time steps (--model auto may run either)";
      if (!(*options.checkpoint_every >= step))
        {
          std::ostringstream m;
          m << "--checkpoint-every " << *options.checkpoint_every << " s is outside the allowed range [" << step
            << ", inf): at least " << which << ", " << step << " s";
          throw InputError(m.str());
        }
    }

    // What defines this run (its command, scene and scene without end time)
    // and, on --resume, that it is the checkpoint's run.
    void describe_run(SimulationRun &r)
    {
      const Scene &scene = r.outcome.scene;
      r.command_label    = r.the_case ? "simulate/" + r.the_case->name : std::string("simulate");
      r.scene_text       = scene_file_text(scene);
      {
        Scene timeless                  = scene;
        timeless.time_stepping.end_time = 0.;
        r.timeless_scene_text           = scene_file_text(timeless);
      }
      if (!r.resuming)
        return;
      const std::string identity = run_identity(r.command_label, r.saved.setting, r.timeless_scene_text);
      if (fnv1a(identity) != r.saved.identity_digest)
        {
          // The scene file reads differently now (another build's defaults):
          // the first line in which the two runs differ.
          const auto lines = first_differing_lines(identity, r.saved.identity);
          throw InputError("--resume: the checkpoint in '" + r.options.resume_dir +
                           "' is of another run: this run has '" + (lines ? lines->first : identity) +
                           "' where the checkpoint's has '" + (lines ? lines->second : r.saved.identity) +
                           "'; not resumed");
        }
    }

    // The model: as asked, or the cheapest whose ensemble end state the
    // scene's error ladder puts within the tolerance of the FE reference's.
    void choose_model(SimulationRun &r)
    {
      const Scene &scene    = r.outcome.scene;
      ModelSetting &setting = r.outcome.setting;
      setting = scene_model(scene, r.options.model == "fe" ? "fe" : "rom"); // the FE at the scene's FE time step
      if (r.resuming)
        {
          setting      = r.saved.setting;
          r.outcome.why = r.saved.why;
        }
      else if (r.options.model == "auto")
        {
          // The ladder is cached beside the scene's reports, keyed by its content.
          setting = choose_model(scene, r.options.tolerance, choice_cache_dir(scene), r.outcome.why);
          console() << r.outcome.why << std::endl;
        }
    }

    // trace.csv and periods.csv, streams that a stopped run keeps; a resumed
    // run appends to the files it continues. The trace (1000 rows per
    // simulated second) is flushed every 1000 rows, periods.csv every row.
    CsvOptions run_csv_options(const bool append, const unsigned int flush_every)
    {
      CsvOptions options;
      options.append      = append;
      options.in_place    = true;
      options.flush_every = flush_every;
      return options;
    }
  } // namespace

  namespace internal
  {
    RunCsvFiles::RunCsvFiles(const std::string &dir, const bool append)
      : trace(dir + "/trace.csv", trace_csv_columns(), run_csv_options(append, 1000))
      , periods(dir + "/periods.csv", period_csv_columns(), run_csv_options(append, 1))
    {}
  } // namespace internal

  namespace
  {
    // The run's rows into the files (and its period records into the
    // outcome); with `verbose`, its progress on the console.
    void connect_outputs(AdaptationRun &run, RunCsvFiles &files, std::vector<PeriodRecord> &periods,
                         const bool verbose)
    {
      run.on_trace_row = [&files](const TraceRow &row) { write_trace_row(files.trace, row); };
      run.on_period    = [&files, &periods](const PeriodRecord &r) {
        write_period_row(files.periods, r);
        periods.push_back(r);
      };
      if (verbose)
        run.on_progress = [](const RunProgress &p) {
          console() << "  t = " << std::fixed << std::setprecision(1) << p.t << " / " << p.end_time
                    << " s, x_C/L = " << std::setprecision(3) << p.slider_x_over_L << ", amplitude "
                    << p.amplitude_over_h << " h, " << std::setprecision(0) << p.steps_per_second << " steps/s"
                    << std::endl
                    << std::defaultfloat;
        };
    }

    // --animate: the run up to the animation window, then frame by frame
    // to the end, each frame into animation.pvd.
    RunResult run_with_animation(AdaptationRun &run, const std::string &dir, const double end_time)
    {
      const double t_first = std::max(0., end_time - animation_window);
      RunResult result     = run.run_until(t_first);
      VtkAnimationWriter animation(dir, 1.);
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
          animation.write(make_animation_frame(run.stepper()));
        }
      animation.finish();
      return result;
    }

    // The run in pieces of --checkpoint-every, each followed by a
    // checkpoint; one piece without it. The trace is the same either way.
    RunResult run_in_pieces(SimulationRun &r, AdaptationRun &run, RunCsvFiles &files)
    {
      const double end_time = r.outcome.scene.time_stepping.end_time;
      const double every    = r.options.checkpoint_every.value_or(0.);
      const double eps      = 1e-9 * r.outcome.setting.time_step;
      double t_stop         = every > 0. ? (std::floor(run.state().t / every + 1e-9) + 1.) * every : end_time;
      RunResult result;
      while (true)
        {
          t_stop                = std::min(t_stop, end_time);
          const RunResult piece = run.run_until(t_stop);
          result.status         = piece.status;
          result.message        = piece.message;
          result.n_steps += piece.n_steps;
          result.t_end           = piece.t_end;
          result.slider_x_over_L = piece.slider_x_over_L;
          result.max_solver_iterations = std::max(result.max_solver_iterations, piece.max_solver_iterations);
          if (piece.status != RunStatus::completed)
            break;
          if (every > 0.)
            write_checkpoint(r, run, files, result.n_steps);
          if (t_stop >= end_time - eps)
            break;
          t_stop += every;
        }
      run.finish_trace();
      return result;
    }

    // summary.md: settings, cost, status and the verdict, against the
    // case's published behaviour where the run keeps the case as it is.
    std::string summary_text(const SimulationRun &r)
    {
      const Scene &scene          = r.outcome.scene;
      const SimulationCase *the_case = r.the_case;
      const RunResult &result     = r.outcome.result;
      const double wall           = r.outcome.wall_seconds;
      std::ostringstream summary;
      summary << "# simulate: scene `" << scene.name << "`" << (the_case ? ", case `" + the_case->name + "`" : "") << "\n\n";
      if (the_case && !r.modified.empty())
        {
          summary << "- Case: " << the_case->name << ", modified: ";
          for (std::size_t i = 0; i < r.modified.size(); ++i)
            summary << (i ? "; " : "") << r.modified[i];
          summary << ".\n- Not compared with the published behaviour (" << the_case->published
                  << "): the run changes parameters the case fixes.\n";
        }
      else if (the_case)
        {
          summary << "- Case: " << the_case->description << ".\n- Published: " << the_case->published << ".\n";
          const std::string differs = disagreements(r.outcome.verdict, the_case->expected);
          summary << "- Against the published behaviour: " << (differs.empty() ? "agrees on every stated feature" : "differs: " + differs) << ".\n";
        }
      const std::string &why = r.outcome.why;
      summary << "- Model: " << r.outcome.setting.label() << ".\n"
              << (why.empty() ? "" : "- Chosen by --model auto:\n\n```\n" + why + "\n```\n\n")
              << (r.resuming ? "- Resumed from the checkpoint in this folder (" + std::to_string(r.saved.n_steps) +
                                 " steps done before).\n"
                             : std::string())
              << (r.options.checkpoint_every ? "- Checkpoint every " + std::to_string(*r.options.checkpoint_every) +
                                                 " s simulated: checkpoint.bin (resume with `beamslider simulate --resume " +
                                                 r.outcome.dir + "`).\n"
                                             : std::string())
              << "- Simulated " << result.t_end << " s of " << scene.time_stepping.end_time << " s in " << wall << " s wall ("
              << (wall > 0 ? result.n_steps / wall : 0.) << " steps/s).\n"
              << "- Status: " << to_string(result.status) << (result.message.empty() ? "" : ": " + result.message) << ".\n"
              << "- Verdict: " << r.outcome.verdict.line << ".\n"
              << "\nFiles: trace.csv, periods.csv" << (r.options.animate ? ", animation.pvd" : "") << ", trace.png.\n";
      return summary.str();
    }

    // trace.png; none of an interrupted run: the user asked it to stop.
    void draw_trace_chart(EarlyPlot &chart, const SimulationRun &r)
    {
      if (r.outcome.result.status == RunStatus::interrupted)
        return;
      std::ostringstream title;
      title << r.outcome.scene.name << (r.the_case ? " / " + r.the_case->name : std::string()) << " ("
            << r.outcome.setting.label() << ")";
      chart.draw({r.outcome.dir, title.str(), std::to_string(r.outcome.scene.beam.thickness)});
    }
  } // namespace

  SimulationOutcome run_simulation(const CommonOptions &given_common, const SimulateOptions &given_options,
                                   const bool verbose)
  {
    // --resume DIR: the scene, overrides, case and model come from DIR's
    // checkpoint; the run continues from its state into the same files.
    SimulationRun r;
    r.common   = given_common;
    r.options  = given_options;
    r.resuming = !r.options.resume_dir.empty();
    if (r.resuming)
      {
        load_checkpoint_to_resume(r);
        check_checkpoint_is_folders_run(r);
      }
    check_simulate_options(r.options);
    read_simulation_scene(r);
    if (r.options.checkpoint_every)
      check_checkpoint_interval(r);
    describe_run(r);
    const Scene &scene     = r.outcome.scene;
    const std::string &dir = r.outcome.dir =
      prepare_output_dir(r.common, scene, r.command_label, r.resuming ? RunRecord::append : RunRecord::replace);
    // The chart's Python starts now and loads matplotlib while the run
    // computes; it draws once the CSV files are complete.
    EarlyPlot chart("plot_trace.py");

    choose_model(r);
    const ModelSetting &setting = r.outcome.setting;
    std::unique_ptr<BeamSystem> beam = make_beam_model(scene, setting);
    const double end_time = scene.time_stepping.end_time;
    console() << "simulate " << scene.name << (r.the_case ? " --case " + r.the_case->name : std::string()) << ": "
              << setting.label() << ", " << end_time << " s (" << std::llround(end_time / setting.time_step)
              << " steps), output in " << dir << std::endl;
    RunOptions run_options        = RunOptions::from_scene(scene, setting.time_step);
    run_options.progress_interval = std::max(1., end_time / 20.);
    require_stable_time_step(setting, *beam);
    AdaptationRun run(scene, *beam, run_options);
    if (r.resuming)
      restore_checkpointed_run(r, run);

    RunCsvFiles files(dir, r.resuming);
    connect_outputs(run, files, r.outcome.periods, verbose);
    r.start          = std::chrono::steady_clock::now();
    RunResult &result = r.outcome.result;
    result = r.options.animate ? run_with_animation(run, dir, end_time) : run_in_pieces(r, run, files);
    r.outcome.wall_seconds = elapsed_seconds(r.start);
    files.trace.close();
    files.periods.close();

    r.outcome.verdict = case_verdict(r.outcome.periods, result, trace_thresholds(scene));
    const std::string summary = summary_text(r);
    write_text_file(dir + "/summary.md", summary);
    if (!ends_in_a_result(result.status))
      std::cerr << "simulate: " << to_string(result.status) << ": " << result.message << std::endl;
    draw_trace_chart(chart, r);
    if (verbose)
      console() << summary;
    return std::move(r.outcome);
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
    return ends_in_a_result(result.status) ? 0 : 1;
  }
} // namespace beamslider

