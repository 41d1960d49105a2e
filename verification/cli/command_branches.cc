// `beamslider branches SCENE`: the held slider's slow manifold
// (verification/studies/slow_manifold.h, doc/physics.md §12): attractor.csv,
// branches.csv and branch_events.csv (their columns in
// verification/report/slow_manifold_files.h), summary.md and branches.png
// (scripts/plot_branches.py).
#include "io/console.h"
#include "io/output_file.h"
#include "scene/scene.h"
#include "numerics/stop_request.h"
#include "verification/cli/commands.h"
#include "verification/report/charts.h"
#include "verification/report/slow_manifold_files.h"

#include <cmath>
#include <iostream>
#include <sstream>

namespace beamslider
{
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

    const SlowManifold result = run_slow_manifold_into(scene, settings, dir);
    const bool plotted = run_plot_script("plot_branches.py", {dir, scene.name});
    const double f = scene.excitation.frequency_hz;
    std::ostringstream text;
    text << "# Slow manifold of the held slider: scene `" << scene.name << "`, " << f << " Hz, "
         << scene.excitation.acceleration_amplitude << " m/s²\n\n"
         << describe_slow_manifold(result, scene) << "\nWall time " << result.wall_seconds << " s. Files: attractor.csv, branches.csv, "
         << "branch_events.csv" << (plotted ? ", branches.png" : "") << ".\n";
    write_text_file(dir + "/summary.md", text.str());
    console() << describe_slow_manifold(result, scene) << "wrote " << dir << "/summary.md" << std::endl;
    stop_if_interrupted(); // an interrupted run ends as every command's does (130/143, partial)
    return result.probe_stop.empty() ? 0 : 1;
  }
} // namespace beamslider
