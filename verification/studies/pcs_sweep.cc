// The prescribed-slider-position study, see pcs_sweep.h.
#include "verification/studies/pcs_sweep.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/simulation_cases.h"

#include "contact/trace_analysis.h"

#include "contact/adaptation_run.h"
#include "contact/csv_writer.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "reduced/resonance_curve.h"
#include "reduced/rom_beam_system.h"
#include "verification/cli/commands.h"
#include "verification/studies/console.h"
#include "verification/studies/parallel_for.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>

namespace beamslider
{
  namespace
  {
    ModalBasis modal_basis_of(const Scene &scene)
    {
      const FEBeam fe(scene);
      const unsigned int N = scene.discretisation.n_modes;
      return make_modal_basis(fe, compute_bending_modes(fe, N), N);
    }

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

  double pcs_sweep_chain_time(const PcsStudySettings &settings, const unsigned int cores)
  {
    const double branch =
      settings.sweep.positions(SweepDirection::up).size() * (settings.sweep.settle_time + settings.sweep.average_time);
    const double free_run = settings.free_time;
    // With two cores the second branch goes to whichever of the free run and
    // the first branch ends first (the order of the parallel_for below).
    return cores >= 3 ? std::max(branch, free_run)
           : cores == 2 ? std::max(free_run, std::min(branch, free_run) + branch)
                        : 2 * branch + free_run;
  }

  PcsStudy run_pcs_sweep(const Scene &scene_in, const PcsStudySettings &settings, const std::string &dir)
  {
    // The model runs at its own step (the FE at the scene's FE time step).
    Scene scene                   = scene_in;
    scene.time_stepping.time_step = scene_model(scene, settings.model).time_step;
    settings.sweep.validate(scene);
    if (!(settings.free_time >= 0.))
      throw InputError("--free-time " + std::to_string(settings.free_time) + " s is outside [0, inf)");
    const auto start        = std::chrono::steady_clock::now();
    const ModalBasis basis  = modal_basis_of(scene);
    const double L          = scene.beam.length;
    PcsStudy study;

    // The Eq. 5 resonance curve on a fine grid over the swept range (needs
    // the geometric nonlinearity: without it the curve is a vertical line).
    if (scene.discretisation.geometric_nonlinearity)
      {
        const ReducedOrderModel rom(basis, scene.damping_ratio, true);
        const ResonanceCurveData data =
          ResonanceCurveData::from_model(rom, scene.slider_mass(), scene.slider_inertia(), scene.beam.thickness);
        CsvWriter csv(dir + "/resonance.csv", {"x_over_L", "amplitude_over_h"});
        const unsigned int n = 200;
        for (unsigned int i = 0; i <= n; ++i)
          {
            const double x = settings.sweep.low_over_L + (settings.sweep.high_over_L - settings.sweep.low_over_L) * i / n;
            const double a = resonance_amplitude_over_h(rom, data, x * L, scene.excitation.frequency_hz);
            csv.row({CsvWriter::cell(x), std::isfinite(a) ? CsvWriter::cell(a) : ""});
          }
      }

    CsvOptions in_place; // rows as positions finish: kept by a stopped sweep
    in_place.in_place = true;
    CsvWriter pcs(dir + "/pcs.csv", {"x_over_L", "direction", "amplitude_over_h", "mean_fx_N", "amplitude_std_over_h",
                                     "mean_fx_std_N", "n_periods", "t_end_s", "mean_fx_ci95_N"},
                  in_place);
    // The grid's own count (the far end is a position of its own when the
    // range is not a whole number of steps).
    const long n_positions = static_cast<long>(settings.sweep.positions(SweepDirection::up).size());
    // Whether each run reached its end: pcs.csv holds the positions a branch
    // reached, which its rows alone cannot tell from a complete branch.
    CsvWriter runs(dir + "/runs.csv", {"run", "status", "positions", "positions_planned", "t_end_s"}, in_place);

    // The two branches and the free slider are independent runs: each on its
    // own core. Rows of pcs.csv are written as positions finish (a branch's
    // rows stay in its order; the readers select by direction), and console
    // lines whole, under one lock.
    std::mutex output_mutex;
    auto say = [&](const std::string &line) {
      const std::lock_guard<std::mutex> lock(output_mutex);
      console() << line << std::endl;
    };
    auto sweep_branch = [&](const SweepDirection direction) {
      std::unique_ptr<BeamSystem> beam = make_beam_model(scene, scene_model(scene, settings.model));
      long done                        = 0;
      auto on_point                    = [&](const PcsPoint &p) {
        const std::lock_guard<std::mutex> lock(output_mutex);
        pcs.row({CsvWriter::cell(p.x_over_L), to_string(p.direction), CsvWriter::cell(p.amplitude_over_h),
                 CsvWriter::cell(p.mean_fx), CsvWriter::cell(p.amplitude_std_over_h), CsvWriter::cell(p.mean_fx_std),
                 std::to_string(p.n_periods), CsvWriter::cell(p.t_end), CsvWriter::cell(p.mean_fx_ci95)});
        ++done;
        if (settings.verbose && (done % 10 == 0 || done == n_positions))
          console() << "  sweep " << to_string(direction) << ": " << done << "/" << n_positions
                    << " positions, x_C/L = " << fixed(p.x_over_L, 3) << ", amplitude " << fixed(p.amplitude_over_h, 3)
                    << " h, F_x = " << sci(p.mean_fx, 2) << " N" << std::endl;
      };
      PcsBranch branch = run_pcs_branch(scene, *beam, settings.sweep, direction, on_point);
      if (branch.last_run.status != RunStatus::completed)
        say("  sweep " + to_string(direction) + " stopped early (" + to_string(branch.last_run.status) +
            "): " + branch.last_run.message);
      (direction == SweepDirection::up ? study.up : study.down) = std::move(branch);
    };

    // The free slider from the scene's own start, for the overlay.
    auto free_slider = [&]() {
      std::unique_ptr<BeamSystem> beam = make_beam_model(scene, scene_model(scene, settings.model));
      RunOptions options               = RunOptions::from_scene(scene);
      options.end_time                 = settings.free_time;
      options.output_rate              = 1.;
      options.progress_interval        = settings.verbose ? std::max(1., settings.free_time / 5.) : 1e300;
      AdaptationRun run(scene, *beam, options);
      CsvWriter periods(dir + "/free_periods.csv", period_csv_columns());
      std::vector<PeriodRecord> records;
      run.on_period = [&periods, &records](const PeriodRecord &r) {
        write_period_row(periods, r);
        records.push_back(r);
      };
      if (settings.verbose)
        run.on_progress = [&say](const RunProgress &p) {
          say("  free slider: t = " + fixed(p.t, 1) + " / " + fixed(p.end_time, 1) + " s, x_C/L = " +
              fixed(p.slider_x_over_L, 3) + ", amplitude " + fixed(p.amplitude_over_h, 3) + " h");
        };
      study.free_run            = run.run();
      study.free_final_x_over_L = run.state().s[0] / L;

      // The free slider's jump by the one trace analysis; the amplitude
      // after it is the envelope one second later (where the rule checks
      // that it lasts).
      const TraceAnalysis analysis = analyse_trace(records, study.free_run.status, trace_thresholds(scene));
      if (analysis.jumped)
        {
          std::size_t k = 0;
          while (k + 1 < records.size() && records[k].t_end < analysis.jump_time)
            ++k;
          const std::size_t later = std::min(records.size() - 1, k + static_cast<std::size_t>(std::lround(
                                                                       1. / (records[0].t_end - records[0].t_start))));
          study.free_jump = PcsStudy::FreeJump{analysis.jump_time, records[k].slider_x_over_L,
                                               analysis.level_before_jump, analysis.envelope[later]};
        }
      if (study.free_run.status != RunStatus::completed)
        say("  free slider stopped early (" + to_string(study.free_run.status) + "): " + study.free_run.message);
    };

    // The free run first: with two cores the second branch then goes to
    // whichever of the free run and the first branch ends first, which is
    // never later than starting both branches first (pcs_sweep_chain_time).
    const bool with_free_run = settings.free_time > 0.;
    const std::size_t first_branch = with_free_run ? 1 : 0;
    parallel_for(first_branch + 2, 0, [&](const std::size_t i) {
      if (i < first_branch)
        free_slider();
      else
        sweep_branch(i == first_branch ? SweepDirection::up : SweepDirection::down);
    });

    for (const PcsBranch *branch : {&study.up, &study.down})
      runs.row({to_string(branch->direction), to_string(branch->last_run.status), CsvWriter::cell(branch->points.size()),
                std::to_string(n_positions), CsvWriter::cell(branch->last_run.t_end)});
    if (with_free_run)
      runs.row({"free", to_string(study.free_run.status), "", "", CsvWriter::cell(study.free_run.t_end)});
    study.crossings_up   = force_zero_crossings(study.up.points);
    study.crossings_down = force_zero_crossings(study.down.points);
    study.jump_up        = largest_amplitude_jump(study.up.points);
    study.jump_down      = largest_amplitude_jump(study.down.points);

    study.plotted = run_plot_script("plot_pcs.py", {dir, scene.name});
    study.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return study;
  }

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
    const PcsStudy study = run_pcs_sweep(scene, settings, report.dir);

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
    if (study.plotted)
      report.text << "![PCS sweep](pcs.png)\n\n";
    report.text << "Data: `pcs.csv`, `resonance.csv`, `free_periods.csv`, `runs.csv`.\n\n";
  }
} // namespace beamslider
