// The prescribed-slider-position study, see pcs_sweep.h.
#include "numerics/elapsed.h"
#include "verification/studies/pcs_sweep.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/simulation_cases.h"

#include "runs/trace_analysis.h"

#include "runs/adaptation_run.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "reduced/resonance_curve.h"
#include "reduced/rom_beam_system.h"
#include "verification/studies/number_text.h"
#include "runtime/parallel_for.h"

#include <chrono>
#include <cmath>
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

    // The Eq. 5 resonance curve on a fine grid over the swept range (needs
    // the geometric nonlinearity: without it the curve is a vertical line).
    std::vector<ResonancePoint> resonance_curve(const Scene &scene, const ModalBasis &basis,
                                                const PcsSweepSettings &sweep)
    {
      const double L = scene.beam.length;
      const ReducedOrderModel rom(basis, scene.damping_ratio, true);
      const ResonanceCurveData data =
        ResonanceCurveData::from_model(rom, scene.slider_mass(), scene.slider_inertia(), scene.beam.thickness);
      std::vector<ResonancePoint> curve;
      const unsigned int n = 200;
      for (unsigned int i = 0; i <= n; ++i)
        {
          const double x = sweep.low_over_L + (sweep.high_over_L - sweep.low_over_L) * i / n;
          curve.push_back({x, resonance_amplitude_over_h(rom, data, x * L, scene.excitation.frequency_hz)});
        }
      return curve;
    }

    // The free slider's jump by the one trace analysis; the amplitude
    // after it is the envelope one second later (where the rule checks
    // that it lasts).
    std::optional<PcsStudy::FreeJump> free_jump_of(const std::vector<PeriodRecord> &records,
                                                   const TraceAnalysis &analysis)
    {
      if (!analysis.jumped)
        return std::nullopt;
      std::size_t k = 0;
      while (k + 1 < records.size() && records[k].t_end < analysis.jump_time)
        ++k;
      const std::size_t later = std::min(records.size() - 1, k + static_cast<std::size_t>(std::lround(
                                                                   1. / (records[0].t_end - records[0].t_start))));
      return PcsStudy::FreeJump{analysis.jump_time, records[k].slider_x_over_L, analysis.level_before_jump,
                                analysis.envelope[later]};
    }

    // The two branches and the free slider are independent runs: each on its
    // own core. The observer hears of each position as it finishes (a
    // branch's points in its order) and of each progress line whole, one
    // call at a time under one lock.
    struct PcsRuns
    {
      const Scene &scene;
      const ModelSetting &model;
      const PcsStudySettings &settings;
      const PcsSweepObserver &observer;
      const long n_positions; // the grid's own count, per branch
      PcsStudy &study;
      std::mutex observer_mutex{};

      void say(const std::string &line)
      {
        const std::lock_guard<std::mutex> lock(observer_mutex);
        if (observer.on_progress)
          observer.on_progress(line);
      }

      // One finished position of a branch: the observer's, and every tenth
      // a progress line.
      void report_point(const SweepDirection direction, const PcsPoint &p, long &done)
      {
        const std::lock_guard<std::mutex> lock(observer_mutex);
        if (observer.on_point)
          observer.on_point(p);
        ++done;
        if (settings.verbose && (done % 10 == 0 || done == n_positions) && observer.on_progress)
          observer.on_progress("  sweep " + to_string(direction) + ": " + std::to_string(done) + "/" +
                               std::to_string(n_positions) + " positions, x_C/L = " + fixed(p.x_over_L, 3) +
                               ", amplitude " + fixed(p.amplitude_over_h, 3) + " h, F_x = " + sci(p.mean_fx, 2) + " N");
      }

      void report_free_period(const PeriodRecord &record)
      {
        const std::lock_guard<std::mutex> lock(observer_mutex);
        if (observer.on_free_period)
          observer.on_free_period(record);
      }

      void sweep_branch(const SweepDirection direction)
      {
        std::unique_ptr<BeamSystem> beam = make_beam_model(scene, model);
        long done                        = 0;
        PcsBranch branch                 = run_pcs_branch(scene, *beam, settings.sweep, model.time_step, direction,
                                                          [&](const PcsPoint &p) { report_point(direction, p, done); });
        if (branch.last_run.status != RunStatus::completed)
          say("  sweep " + to_string(direction) + " stopped early (" + to_string(branch.last_run.status) +
              "): " + branch.last_run.message);
        (direction == SweepDirection::up ? study.up : study.down) = std::move(branch);
      }

      // The free slider from the scene's own start, for the overlay.
      void free_slider()
      {
        std::unique_ptr<BeamSystem> beam = make_beam_model(scene, model);
        RunOptions options               = RunOptions::from_scene(scene, model.time_step);
        options.end_time                 = settings.free_time;
        options.output_rate              = 1.;
        options.progress_interval        = settings.verbose ? std::max(1., settings.free_time / 5.) : 1e300;
        AdaptationRun run(scene, *beam, options);
        std::vector<PeriodRecord> &records = study.free_periods;
        run.on_period = [this, &records](const PeriodRecord &r) {
          report_free_period(r);
          records.push_back(r);
        };
        if (settings.verbose)
          run.on_progress = [this](const RunProgress &p) {
            say("  free slider: t = " + fixed(p.t, 1) + " / " + fixed(p.end_time, 1) + " s, x_C/L = " +
                fixed(p.slider_x_over_L, 3) + ", amplitude " + fixed(p.amplitude_over_h, 3) + " h");
          };
        study.free_run            = run.run();
        study.free_final_x_over_L = run.state().s[0] / scene.beam.length;
        study.free_jump = free_jump_of(records, analyse_trace(records, study.free_run.status, trace_thresholds(scene)));
        if (study.free_run.status != RunStatus::completed)
          say("  free slider stopped early (" + to_string(study.free_run.status) + "): " + study.free_run.message);
        const std::lock_guard<std::mutex> lock(observer_mutex);
        if (observer.on_free_run_end)
          observer.on_free_run_end(study.free_run);
      }

      // The free run first: with two cores the second branch then goes to
      // whichever of the free run and the first branch ends first, which is
      // never later than starting both branches first (pcs_sweep_chain_time).
      void run_all(const bool with_free_run)
      {
        const std::size_t first_branch = with_free_run ? 1 : 0;
        parallel_for(first_branch + 2, 0, [&](const std::size_t i) {
          if (i < first_branch)
            free_slider();
          else
            sweep_branch(i == first_branch ? SweepDirection::up : SweepDirection::down);
        });
      }
    };

    // The features the seed reads off the branches: the zero crossings of
    // F̄_x and the jump of each branch.
    void find_branch_features(PcsStudy &study)
    {
      study.crossings_up   = force_zero_crossings(study.up.points);
      study.crossings_down = force_zero_crossings(study.down.points);
      study.jump_up        = largest_amplitude_jump(study.up.points);
      study.jump_down      = largest_amplitude_jump(study.down.points);
    }
  } // namespace

  double pcs_sweep_chain_time(const PcsStudySettings &settings, const unsigned int cores)
  {
    const double branch =
      settings.sweep.positions(SweepDirection::up).size() * (settings.sweep.settle_time + settings.sweep.average_time);
    const double free_run = settings.free_time;
    // With two cores the second branch goes to whichever of the free run and
    // the first branch ends first (the order of the parallel_for in PcsRuns).
    return cores >= 3 ? std::max(branch, free_run)
           : cores == 2 ? std::max(free_run, std::min(branch, free_run) + branch)
                        : 2 * branch + free_run;
  }

  PcsStudy run_pcs_sweep(const Scene &scene, const PcsStudySettings &settings, const PcsSweepObserver &observer)
  {
    // The model runs at its own step (the FE at the scene's FE time step).
    const ModelSetting model = scene_model(scene, settings.model);
    settings.sweep.validate(scene);
    if (!(settings.free_time >= 0.))
      throw InputError("--free-time " + std::to_string(settings.free_time) + " s is outside [0, inf)");
    const auto start       = std::chrono::steady_clock::now();
    const ModalBasis basis = modal_basis_of(scene);
    PcsStudy study;

    if (scene.discretisation.geometric_nonlinearity)
      study.resonance = resonance_curve(scene, basis, settings.sweep);
    // The grid's own count (the far end is a position of its own when the
    // range is not a whole number of steps).
    study.positions_planned = settings.sweep.positions(SweepDirection::up).size();
    study.with_free_run     = settings.free_time > 0.;
    if (observer.on_start)
      observer.on_start(study);

    PcsRuns branches_and_free_run{scene, model, settings, observer, static_cast<long>(study.positions_planned), study};
    branches_and_free_run.run_all(study.with_free_run);

    find_branch_features(study);
    study.wall_seconds = elapsed_seconds(start);
    return study;
  }

} // namespace beamslider
