// The prescribed-slider-position study of seed §4.2–4.3 on one scene: both
// branches of the sweep (runs/prescribed_position_sweep.h), the free-slider
// run of the same scene for comparison, the Eq. 5 resonance curve
// (reduced/resonance_curve.h), and the features the seed reads off them: the
// jump (turning point) of each branch and the zero crossings of F̄_x.
//
// The study writes and prints nothing: it returns a PcsStudy, and an
// observer (PcsSweepObserver) sees each result as it comes, so that the
// caller can keep its rows on disk while the runs go (a stopped sweep keeps
// its points) and show progress. The files of a sweep and their columns are
// verification/report/pcs_files.h's. The two branches and the free run are
// independent runs and go on the machine's cores at once
// (runtime/parallel_for.h): each branch's points reach the
// observer in its own order, the two branches' points interleaved.
#pragma once

#include "runs/prescribed_position_sweep.h"
#include "scene/scene.h"

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace beamslider
{
  struct PcsStudySettings
  {
    std::string model = "rom";  // rom | fe
    PcsSweepSettings sweep;     // range, step, settle and averaging times
    double free_time = 0;       // [s] of the free-slider run (0: none)
    bool verbose = true;        // progress lines to the observer (a stop is reported regardless)
  };

  // The Eq. 5 resonance curve at one position: amplitude not finite = no
  // resonance there.
  struct ResonancePoint
  {
    double x_over_L = 0, amplitude_over_h = 0;
  };

  struct PcsStudy
  {
    // The Eq. 5 resonance curve on a fine grid over the swept range; empty
    // without the geometric nonlinearity (the curve is then a vertical line).
    std::vector<ResonancePoint> resonance;
    std::size_t positions_planned = 0; // per branch: the grid's own count, far end included
    PcsBranch up, down;
    std::vector<ForceZeroCrossing> crossings_up, crossings_down;
    std::optional<AmplitudeJump> jump_up, jump_down;
    bool with_free_run = false;   // settings.free_time > 0
    RunResult free_run;           // status of the free-slider run
    std::vector<PeriodRecord> free_periods; // the free-slider run, one per excitation period
    double free_final_x_over_L = 0; // where the free slider ended [-]
    // The free slider's jump by the one trace analysis (contact/
    // trace_analysis.h): time [s], x_C/L, the envelope before it and one
    // second after it [h].
    struct FreeJump
    {
      double t = 0, x_over_L = 0, amplitude_before_over_h = 0, amplitude_after_over_h = 0;
    };
    std::optional<FreeJump> free_jump;
    double wall_seconds = 0;
  };

  // What run_pcs_sweep reports while it runs; every function may be empty.
  // They are called one at a time (under one lock) from the threads of the
  // runs, so they need no lock of their own.
  struct PcsSweepObserver
  {
    // Once the settings are checked, before any run starts: the study so
    // far (resonance, positions_planned, with_free_run).
    std::function<void(const PcsStudy &)> on_start;
    // A branch's finished position (its direction in the point).
    std::function<void(const PcsPoint &)> on_point;
    // One excitation period of the free-slider run, and that run's end.
    std::function<void(const PeriodRecord &)> on_free_period;
    std::function<void(const RunResult &)> on_free_run_end;
    // A progress line, without its '\n'.
    std::function<void(const std::string &)> on_progress;
  };

  PcsStudy run_pcs_sweep(const Scene &scene, const PcsStudySettings &settings, const PcsSweepObserver &observer = {});

  // The simulated time [s] of run_pcs_sweep's longest chain of runs on `cores`
  // cores (the free run and the two branches go at once, in that order): what
  // sets its wall time.
  double pcs_sweep_chain_time(const PcsStudySettings &settings, unsigned int cores);

} // namespace beamslider
