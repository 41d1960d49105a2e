// `beamslider animate SCENE --model fe|rom`: runs a short window of the
// scene (default 0.2 s) with the shared contact code (runs/adaptation_run)
// on the FE beam (fem/fe_transient) or on the ROM (N modes, analytic
// coefficients from the FE modes) and writes a ParaView time series
// (output/vtk_animation.h): animation.pvd with beam, slider and contact forces at
// `--frame-rate` frames per simulated second from `--start-time`, plus
// trace.csv (the ROM's columns), frames.csv and frames.png (a strip of stills
// drawn by scripts/plot_frames.py).
// On a scene with a Solid, `--model rom` runs the reduced model built from
// the solid, and the run is also drawn on the solid itself
// (output/solid_rom_animation.h): solid.pvd, one .pvtu per frame with the
// displacement w0 e_z + Σ q_n φ_n of the whole strip.
#include "runs/adaptation_run.h"
#include "io/interruption.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "output/solid_rom_animation.h"
#include "output/vtk_animation.h"
#include "scene/scene.h"
#include "reduced/rom_beam_system.h"
#include "numerics/elapsed.h"
#include "verification/cli/commands.h"
#include "io/console.h"
#include "verification/studies/fe_rom_study.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>

namespace beamslider
{
  int run_animate(const CommonOptions &common, const AnimateOptions &options)
  {
    if (options.model != "fe" && options.model != "rom")
      throw InputError("--model '" + options.model + "' is not one of fe, rom");
    Scene scene = read_command_scene(common, options.case_name);
    const ModelSetting setting = scene_model(scene, options.model); // the FE at the scene's FE time step
    const double end_time = options.end_time.value_or(0.2);
    if (!(options.start_time < end_time))
      throw InputError("--start-time " + std::to_string(options.start_time) + " s must lie before the end time " +
                       std::to_string(end_time) + " s");
    const double frame_interval = 1. / options.frame_rate;
    const double dt             = setting.time_step;
    const double n_frames       = std::floor((end_time - options.start_time) / frame_interval + 1e-9) + 1;
    if (n_frames > 20000)
      throw InputError("animate would write " + std::to_string(static_cast<long>(n_frames)) +
                       " frames; lower --frame-rate or shorten the window (--start-time, --end-time)");
    const std::string dir = prepare_output_dir(common, scene, "animate");

    std::unique_ptr<BeamSystem> beam = make_beam_model(scene, setting);

    console() << "animate " << scene.name << " --model " << options.model << ": " << end_time << " s at dt = " << dt
              << " s, " << static_cast<long>(n_frames) << " frames from t = " << options.start_time << " s into "
              << dir << std::endl;

    RunOptions run_options        = RunOptions::from_scene(scene, dt);
    run_options.end_time          = end_time;
    run_options.progress_interval = 1e9;
    AdaptationRun run(scene, *beam, run_options);
    CsvOptions trace_options;
    trace_options.flush_every = 1000; // 1000 rows per simulated second
    trace_options.in_place    = true;
    CsvWriter trace(dir + "/trace.csv", trace_csv_columns(), trace_options);
    run.on_trace_row = [&trace](const TraceRow &row) { write_trace_row(trace, row); };

    VtkAnimationWriter writer(dir, options.magnification);
    // The reduced model of a solid scene moves the solid's own modes.
    std::unique_ptr<SolidRomAnimation> solid;
    if (scene.solid.enabled() && options.model == "rom")
      solid = std::make_unique<SolidRomAnimation>(scene, setting.n_modes, dir);
    const auto start = std::chrono::steady_clock::now();
    RunResult last;
    for (long k = 0; k < static_cast<long>(n_frames); ++k)
      {
        // Frames on the time-step grid nearest to start + k / frame rate.
        const double t_frame = options.start_time + k * frame_interval;
        last                 = run.run_until(t_frame);
        if (last.status != RunStatus::completed)
          break;
        const AnimationFrame frame = make_animation_frame(run.stepper());
        writer.write(frame);
        if (solid)
          solid->write(frame.t, frame.beam.base_displacement, run.state().q);
      }
    run.finish_trace();
    trace.close();
    writer.finish();
    if (solid)
      solid->finish();
    const double wall = elapsed_seconds(start);
    if (last.status != RunStatus::completed)
      std::cerr << "animate: the run stopped early (" << to_string(last.status) << "): " << last.message << "\n";
    console() << "wrote " << writer.n_frames() << " frames to " << writer.pvd_file()
              << (solid ? " and, on the solid, " + solid->pvd_file() : std::string()) << " (" << wall
              << " s wall, final x_C/L = " << run.state().s[0] / scene.beam.length << ")" << std::endl;

    if (last.status == RunStatus::interrupted)
      return interruption_exit_code();
    run_plot_script("plot_frames.py", {dir + "/frames.csv", dir + "/frames.png"});
    return ends_in_a_result(last.status) ? 0 : 1;
  }
} // namespace beamslider
