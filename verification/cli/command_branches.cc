// `beamslider branches SCENE`: the held slider's slow manifold
// (verification/studies/slow_manifold.h, doc/physics.md §12). Writes into the
// output folder, rows as they come:
//
//   attractor.csv      x_over_L, period_count, beam_spread, slider_spread,
//                      lyapunov_per_period, lyapunov_per_s, amplitude_over_h,
//                      mean_fx_N: the rattling held slider of the scene's ROM
//                      at each probe (period_count 0: no period ≤ 8 found);
//   branches.csv       x_over_L, amplitude_over_h, mean_fx_N, stable,
//                      largest_multiplier, period_count, branch, model: the
//                      attached-slider model's periodic orbits along x_C
//                      (period_count 1: orbits of one excitation period);
//   branch_events.csv  kind, x_over_L, amplitude_over_h, mean_fx_N: turning
//                      points, period doublings and tori met on the branch;
//   summary.md, branches.png (scripts/plot_branches.py).
#include "io/console.h"
#include "io/csv_writer.h"
#include "io/output_file.h"
#include "meshes/scene.h"
#include "numerics/stop_request.h"
#include "verification/cli/commands.h"
#include "verification/report/charts.h"
#include "verification/studies/slow_manifold.h"

#include <cmath>
#include <iostream>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string describe(const SlowManifold &m, const Scene &scene)
    {
      std::ostringstream s;
      const double f = scene.excitation.frequency_hz;
      unsigned int periodic = 0, chaotic = 0;
      for (const auto &p : m.probes)
        {
          periodic += p.period_count > 0;
          chaotic += p.period_count == 0 && p.lyapunov_per_period > 0.;
        }
      s << "## The rattling held slider (" << m.model << ")\n\n"
        << m.probes.size() << " probes; a periodic orbit (period ≤ 8 excitation periods) at " << periodic
        << "; no period and a positive largest Lyapunov exponent at " << chaotic
        << ": there the held slider's motion is chaotic and has no periodic orbit to shoot for (attractor.csv).\n\n"
        << "| x_C/L | period | section spread beam / slider | Lyapunov [1/period] | [1/s] | amplitude [h] | F̄_x [N] |\n"
        << "|---|---|---|---|---|---|---|\n";
      for (const auto &p : m.probes)
        s << "| " << p.x_over_L << " | " << (p.period_count ? std::to_string(p.period_count) : "none") << " | "
          << p.beam_spread << " / " << p.slider_spread << " | " << p.lyapunov_per_period << " | "
          << p.lyapunov_per_period * f << " | " << p.amplitude_over_h << " | " << p.mean_fx << " |\n";
      if (!m.probe_stop.empty())
        s << "\nThe probes stopped " << m.probe_stop << ".\n";

      s << "\n## The attached-slider model (" << m.model << ", slider moving with the beam)\n\n";
      const Branch &b = m.attached;
      unsigned int stable = 0;
      double a_max = 0, x_at_max = 0;
      for (const auto &p : b.points)
        {
          stable += p.stable();
          if (p.observables[0] > a_max)
            {
              a_max    = p.observables[0];
              x_at_max = p.lambda;
            }
        }
      s << b.points.size() << " periodic orbits by shooting and arclength continuation (" << stable
        << " stable); largest amplitude " << a_max << " h at x_C/L = " << x_at_max << "; the continuation ended: "
        << b.end_reason << ".\n\n";
      if (b.events.empty())
        s << "No turning point, period doubling or torus on the branch: one orbit at each x_C, no bistability in "
             "this model.\n";
      for (const auto &e : b.events)
        s << "- " << to_string(e.kind) << " at x_C/L = " << e.lambda << ", amplitude " << e.observables[0] << " h\n";
      s << "\nThe attached model's F̄_x is the frictionless share of the force that carries the slider (a sticking "
           "slider can hold itself by friction); compare its amplitudes with the rattling ones, not its forces.\n";
      return s.str();
    }
  } // namespace

  int run_branches(const CommonOptions &common, const BranchesOptions &options)
  {
    const Scene scene = read_command_scene(common, options.case_name);
    SlowManifoldSettings settings = SlowManifoldSettings::for_scene(scene);
    if (options.low_over_L)
      settings.low_over_L = *options.low_over_L;
    if (options.high_over_L)
      settings.high_over_L = *options.high_over_L;
    settings.probe_step_over_L = options.probe_step_over_L;
    settings.settle_periods    = options.settle_periods;
    settings.validate(scene);
    const std::string dir = prepare_output_dir(common, scene, "branches");
    console() << "branches " << scene.name << ": x_C/L " << settings.low_over_L << " … " << settings.high_over_L
              << ", attractor probes every " << settings.probe_step_over_L << ", into " << dir << std::endl;

    CsvWriter attractor(dir + "/attractor.csv",
                        {"x_over_L", "period_count", "beam_spread", "slider_spread", "lyapunov_per_period",
                         "lyapunov_per_s", "amplitude_over_h", "mean_fx_N"});
    CsvWriter branches(dir + "/branches.csv", {"x_over_L", "amplitude_over_h", "mean_fx_N", "stable",
                                               "largest_multiplier", "period_count", "branch", "model"});
    const double f = scene.excitation.frequency_hz;
    std::string model;
    SlowManifoldObserver observer;
    observer.on_probe = [&](const HeldSliderAttractor &a) {
      attractor.row({CsvWriter::cell(a.x_over_L), std::to_string(a.period_count), CsvWriter::cell(a.beam_spread),
                     CsvWriter::cell(a.slider_spread), CsvWriter::cell(a.lyapunov_per_period),
                     CsvWriter::cell(a.lyapunov_per_period * f), CsvWriter::cell(a.amplitude_over_h),
                     CsvWriter::cell(a.mean_fx)});
      attractor.flush();
      console() << "  probe x_C/L = " << a.x_over_L << ": period " << (a.period_count ? std::to_string(a.period_count) : "none")
                << ", Lyapunov " << a.lyapunov_per_period << " per period, amplitude " << a.amplitude_over_h << " h"
                << std::endl;
    };
    unsigned long n_orbits = 0;
    observer.on_orbit = [&](const OrbitPoint &p) {
      branches.row({CsvWriter::cell(p.lambda), CsvWriter::cell(p.observables[0]), CsvWriter::cell(p.observables[1]),
                    p.stable() ? "1" : "0", CsvWriter::cell(p.largest_multiplier()), "1", "attached", "attached ROM"});
      if (++n_orbits % 200 == 0)
        {
          branches.flush();
          console() << "  attached model: " << n_orbits << " orbits, at x_C/L = " << p.lambda << std::endl;
        }
    };
    observer.on_progress = [](const std::string &line) { console() << "  " << line << std::endl; };
    const SlowManifold result = compute_slow_manifold(scene, settings, observer);
    attractor.close();
    branches.close();
    {
      CsvWriter events(dir + "/branch_events.csv", {"kind", "x_over_L", "amplitude_over_h", "mean_fx_N"});
      for (const auto &e : result.attached.events)
        events.row({to_string(e.kind), CsvWriter::cell(e.lambda), CsvWriter::cell(e.observables[0]),
                    CsvWriter::cell(e.observables[1])});
      events.close();
    }
    const bool plotted = run_plot_script("plot_branches.py", {dir, scene.name});
    std::ostringstream text;
    text << "# Slow manifold of the held slider: scene `" << scene.name << "`, " << f << " Hz, "
         << scene.excitation.acceleration_amplitude << " m/s²\n\n"
         << describe(result, scene) << "\nWall time " << result.wall_seconds << " s. Files: attractor.csv, branches.csv, "
         << "branch_events.csv" << (plotted ? ", branches.png" : "") << ".\n";
    write_text_file(dir + "/summary.md", text.str());
    console() << describe(result, scene) << "wrote " << dir << "/summary.md" << std::endl;
    stop_if_interrupted(); // an interrupted run ends as every command's does (130/143, partial)
    return result.probe_stop.empty() ? 0 : 1;
  }
} // namespace beamslider
