// The prescribed-position sweep in words (verification/studies/pcs_sweep.h
// computes it): its description and the report's subsection of section 4.
#include "verification/report/charts.h"
#include "verification/report/pcs_files.h"
#include "verification/report/report.h"
#include "verification/report/slow_manifold_files.h"
#include "io/console.h"
#include "verification/studies/pcs_sweep.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string list(const std::vector<ForceZeroCrossing> &crossings)
    {
      std::string s;
      unsigned int n_noise = 0;
      for (const ForceZeroCrossing &c : crossings)
        if (c.resolved)
          s += (s.empty() ? "" : ", ") + fixed(c.x_over_L, 3) + (c.stable ? " (stable)" : " (unstable)");
        else
          ++n_noise;
      if (s.empty())
        s = "none resolved";
      if (n_noise > 0)
        s += " (and " + std::to_string(n_noise) + " within the noise: |F̄_x| inside its 95 % batch-means interval next to them)";
      return s;
    }

    std::string jump_text(const std::optional<AmplitudeJump> &jump)
    {
      if (!jump)
        return "no jump (no neighbouring positions differ by more than a factor 1.5 in amplitude)";
      return "jump between x_C/L = " + fixed(jump->x_before_over_L, 3) + " and " + fixed(jump->x_after_over_L, 3) +
             ": amplitude " + fixed(jump->amplitude_before_over_h, 3) + " h → " + fixed(jump->amplitude_after_over_h, 3) +
             " h";
    }
  } // namespace

  std::string describe(const PcsStudy &study, const Scene &scene)
  {
    std::ostringstream s;
    s << "- Branch up (x_C/L increasing, " << study.up.points.size() << " positions): " << jump_text(study.jump_up)
      << "; zero crossings of F̄_x: " << list(study.crossings_up) << ".\n";
    s << "- Branch down (x_C/L decreasing, " << study.down.points.size()
      << " positions): " << jump_text(study.jump_down) << "; zero crossings of F̄_x: " << list(study.crossings_down)
      << ".\n";
    for (const PcsBranch *b : {&study.up, &study.down})
      if (b->last_run.status != RunStatus::completed)
        s << "- Branch " << to_string(b->direction) << " stopped early (" << to_string(b->last_run.status) << ") after "
          << b->points.size() << " positions: " << b->last_run.message << "\n";
    if (study.free_run.n_steps == 0 && study.free_run.status != RunStatus::completed)
      s << "- The free slider's run stopped before its first step (" << to_string(study.free_run.status)
        << "): " << study.free_run.message << "\n";
    if (study.free_run.n_steps > 0)
      {
        s << "- Free slider from x_C/L = " << fixed(scene.initial.slider_position_over_L, 3) << " over "
          << fixed(study.free_run.t_end, 1) << " s: ended at x_C/L = " << fixed(study.free_final_x_over_L, 3);
        if (study.free_run.status != RunStatus::completed)
          s << " (stopped early, " << to_string(study.free_run.status) << ": " << study.free_run.message << ")";
        s << ".";
        if (study.free_jump)
          {
            s << " It jumped at t = " << fixed(study.free_jump->t, 2) << " s, x_C/L = " << fixed(study.free_jump->x_over_L, 3)
              << " (envelope " << fixed(study.free_jump->amplitude_before_over_h, 3) << " h → "
              << fixed(study.free_jump->amplitude_after_over_h, 3) << " h one second later)";
            for (const auto *jump : {&study.jump_up, &study.jump_down})
              if (*jump && (*jump)->amplitude_after_over_h > (*jump)->amplitude_before_over_h)
                s << "; the prescribed-position branch jumps up between x_C/L = " << fixed((*jump)->x_before_over_L, 3)
                  << " and " << fixed((*jump)->x_after_over_L, 3) << ": "
                  << (std::abs(study.free_jump->x_over_L - 0.5 * ((*jump)->x_before_over_L + (*jump)->x_after_over_L)) <
                          0.02
                        ? "the free slider jumps where the slow manifold of fixed-slider states turns (seed §4.2)"
                        : "more than 0.02 L from the free slider's jump");
            s << ".";
          }
        s << "\n";
      }
    s << "- Wall time " << fixed(study.wall_seconds, 1) << " s (branches " << fixed(study.up.wall_seconds, 1) << " s + "
      << fixed(study.down.wall_seconds, 1) << " s, free run " << fixed(study.free_run.wall_seconds, 1) << " s).\n";
    return s.str();
  }

  void add_pcs_sweep_subsection(Report &report, const Scene &scene, const bool full)
  {
    PcsStudySettings settings;
    settings.sweep = PcsSweepSettings::for_scene(scene);
    if (full)
      {
        settings.free_time = scene.time_stepping.end_time;
      }
    else
      {
        // Same settling and averaging as full, half the positions, a third
        // of the free run (the jump of mueller2023 comes near 5–8 s).
        settings.sweep.step_over_L = 0.005;
        settings.free_time         = std::min(20., scene.time_stepping.end_time);
      }
    settings.verbose = true;
    console() << "Prescribed slider position sweeps (ROM, N = " << scene.discretisation.n_modes << ", x_C/L "
              << settings.sweep.low_over_L << " … " << settings.sweep.high_over_L << " in steps of "
              << settings.sweep.step_over_L << ")" << std::endl;
    const PcsStudy study = run_pcs_sweep_into(scene, settings, report.dir);
    const bool plotted   = run_plot_script("plot_pcs.py", {report.dir, scene.name});

    report.text << "### Prescribed slider position (seed §4.2–4.3)\n\n"
                << "The slider's horizontal position is held (height and tilt free, contacts active) and stepped by Δx_C/L = "
                << settings.sweep.step_over_L << " between x_C/L = " << settings.sweep.low_over_L << " and "
                << settings.sweep.high_over_L << ", up and down, each step from the previous state; at each position "
                << settings.sweep.settle_time << " s settle, then the amplitude and the horizontal contact force F̄_x are "
                << "averaged over the periods of the next " << settings.sweep.average_time
                << " s (" << (full ? "the seed's step" : "quick mode: coarser than the seed's 0.003, shorter free run")
                << "). F̄_x > 0 pushes a free slider toward x = L; its zero crossings are equilibria of the free slider, "
                << "stable where F̄_x decreases with x. The dashed curve is seed Eq. 5's resonance curve; the black line "
                << "the free slider of the same scene (one point per period).\n\n"
                << describe(study, scene) << "\n";
    if (plotted)
      report.text << "![PCS sweep](pcs.png)\n\n";
    report.text << "Data: `pcs.csv`, `resonance.csv`, `free_periods.csv`, `runs.csv`.\n\n";
  }

  void add_slow_manifold_subsection(Report &report, const Scene &scene)
  {
    const SlowManifoldSettings settings = SlowManifoldSettings::for_scene(scene);
    console() << "Periodic orbits of the held slider (ROM, x_C/L " << settings.low_over_L << " … "
              << settings.high_over_L << ")" << std::endl;
    const SlowManifold m = run_slow_manifold_into(scene, settings, report.dir);
    const bool plotted   = run_plot_script("plot_branches.py", {report.dir, scene.name});
    report.text << "### Periodic orbits of the held slider\n\n"
                << "The slider held as in the sweeps, the periodic orbits looked for by shooting on the period map "
                   "(doc/physics.md §12): the rattling held slider probed every "
                << settings.probe_step_over_L << " L (each settled " << settings.settle_periods
                << " periods from the state the probe before left), and the attached-slider model (the slider moving "
                   "with the beam) continued in x_C by pseudo-arclength with its Floquet multipliers.\n\n"
                << describe_slow_manifold(m, scene, "####") << "\n";
    if (plotted)
      report.text << "![Slow manifold of the held slider](branches.png)\n\n";
    report.text << "Data: `attractor.csv`, `branches.csv`, `branch_events.csv` (" << fixed(m.wall_seconds, 1)
                << " s).\n\n";
  }
} // namespace beamslider
