// `beamslider sweep SCENE`: prescribed-slider-position sweeps (seed §4.2–4.3,
// doc/physics.md §10), both directions, with the Eq. 5 resonance curve and the
// free-slider run overlaid; files and columns in verification/report/pcs_files.h.
#include "io/output_file.h"
#include "io/input_file.h"
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/study_results.h"
#include "verification/report/pcs_files.h"
#include "verification/report/report.h"
#include "io/console.h"
#include "verification/studies/pcs_comparison.h"
#include "verification/studies/pcs_sweep.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <thread>

namespace beamslider
{
  int run_sweep(const CommonOptions &common, const SweepOptions &options, StudyHandover *handover)
  {
    const Scene scene = read_command_scene(common, options.case_name);
    PcsStudySettings settings;
    settings.model = options.model;
    settings.sweep = PcsSweepSettings::for_scene(scene);
    if (options.low_over_L)
      settings.sweep.low_over_L = *options.low_over_L;
    if (options.high_over_L)
      settings.sweep.high_over_L = *options.high_over_L;
    settings.sweep.step_over_L  = options.step_over_L;
    settings.sweep.settle_time  = options.settle_time;
    settings.sweep.average_time = options.average_time;
    settings.free_time          = options.free_time.value_or(scene.time_stepping.end_time);
    settings.sweep.validate(scene);

    // The sweep to compare with is read before this one runs: a wrong
    // folder is an input error now, not after minutes of simulation.
    std::vector<PcsPoint> other;
    std::string other_label;
    if (!options.against.empty())
      {
        other = read_pcs_csv(options.against + "/pcs.csv");
        std::vector<PcsPoint> planned;
        for (const SweepDirection d : {SweepDirection::up, SweepDirection::down})
          for (const double x : settings.sweep.positions(d))
            {
              PcsPoint p;
              p.x_over_L  = x;
              p.direction = d;
              planned.push_back(p);
            }
        require_same_positions(planned, other);
        // The other sweep's model, from its summary's title line.
        std::istringstream summary(read_text_file_if_present(options.against + "/summary.md", InputLimits::text));
        std::string title;
        std::getline(summary, title);
        const auto at = title.rfind(", model ");
        other_label   = (at == std::string::npos ? std::string() : title.substr(at + 8) + " ") + "'" + options.against + "'";
      }

    const bool write_kept = handover && handover->mode == StudyHandover::Mode::write;
    if (write_kept)
      require_same_scene(std::any_cast<const SweepRun &>(handover->result).scene, scene, "sweep");
    const std::string dir = handover && !write_kept ? std::string() : prepare_output_dir(common, scene, "sweep");
    const std::size_t n_positions = settings.sweep.positions(SweepDirection::up).size();
    const double simulated =
      2 * n_positions * (settings.sweep.settle_time + settings.sweep.average_time) + settings.free_time;
    // The three runs go on the cores at once: the longest chain of them sets the wall time.
    const double longest = pcs_sweep_chain_time(settings, std::max(1u, std::thread::hardware_concurrency()));
    if (!write_kept)
      console() << "sweep " << scene.name << " --model " << settings.model << ": x_C/L " << settings.sweep.low_over_L
                << " … " << settings.sweep.high_over_L << " step " << settings.sweep.step_over_L << " ("
                << n_positions << " positions per direction), " << simulated
                << " s simulated in all, in three runs at once on the cores (ROM: ~" << std::ceil(longest / 5.)
                << " s wall; FE at its step of " << scene.time_stepping.fe_time_step << " s: about "
                << std::ceil(longest * 15e-6 / scene.time_stepping.fe_time_step) // ~15 µs per FE step
                << " s wall), " << (dir.empty() ? std::string("in memory") : "into " + dir) << std::endl;

    PcsStudy study;
    if (write_kept)
      {
        // The sweep computed before, from the same options (python/study_bindings.cc).
        study = std::any_cast<const SweepRun &>(handover->result).study;
        write_pcs_files(study, dir);
      }
    else if (handover)
      {
        handover->result = SweepRun{scene, settings, run_pcs_sweep_in_memory(scene, settings)};
        return 0;
      }
    else
      study = run_pcs_sweep_into(scene, settings, dir);
    const bool plotted   = run_plot_script("plot_pcs.py", {dir, scene.name});
    std::string text     = describe(study, scene);
    if (!options.against.empty())
      {
        std::vector<PcsPoint> points = study.up.points;
        points.insert(points.end(), study.down.points.begin(), study.down.points.end());
        const PcsComparison comparison = compare_sweeps(points, other);
        write_pcs_comparison(comparison, dir);
        const std::string label = "this sweep (" + settings.model + ")";
        text += "\n## Against " + other_label + "\n\n" + describe(comparison, label, other_label) +
                "\nFiles: comparison.csv, crossings.csv, pcs_compare.png.\n";
        run_plot_script("plot_pcs_compare.py", {dir, options.against, settings.model, other_label});
      }
    write_text_file(dir + "/summary.md",
                    "# PCS sweep: scene `" + scene.name + "`, model " + settings.model + "\n\n" + text);
    console() << text << "wrote " << dir << "/pcs.csv" << (plotted ? " and pcs.png" : "") << std::endl;
    const bool complete = study.up.last_run.status == RunStatus::completed &&
                          study.down.last_run.status == RunStatus::completed;
    for (const auto *branch : {&study.up, &study.down})
      if (branch->last_run.status != RunStatus::completed)
        std::cerr << "sweep: a branch stopped early (" << to_string(branch->last_run.status)
                  << "): " << branch->last_run.message << std::endl;
    return complete ? 0 : 1;
  }
} // namespace beamslider
