// The prescribed-slider-position study of seed §4.2–4.3 on one scene: both
// branches of the sweep (runs/prescribed_position_sweep.h), the free-slider
// run of the same scene for comparison, the Eq. 5 resonance curve
// (reduced/resonance_curve.h), and the features the seed reads off them: the
// jump (turning point) of each branch and the zero crossings of F̄_x.
//
// Files written into the output folder (SI units, named columns):
//   pcs.csv        x_over_L,direction,amplitude_over_h,mean_fx_N,
//                  amplitude_std_over_h,mean_fx_std_N,n_periods,t_end_s
//                  (direction: up = x_C increasing, down = decreasing;
//                  amplitude = mean over the averaged periods of
//                  (max − min)/2 of w(L/2) per period, over h; mean_fx_N =
//                  period-averaged horizontal contact force on the slider,
//                  + toward x = L; *_std = spread over those periods)
//   resonance.csv  x_over_L,amplitude_over_h (Eq. 5; empty cell = no resonance)
//   free_periods.csv  the free-slider run, one row per excitation period
//                  (periods.csv columns)
//   runs.csv       run,status,positions,positions_planned,t_end_s: whether
//                  each branch (and the free run) reached its end; status
//                  other than "completed" = stopped early, its pcs.csv rows
//                  are the positions it reached (also in PcsStudy and
//                  report.h's describe())
// The chart pcs.png (amplitude and F̄_x against x_C/L, seed Figs. 10b and 14)
// is the caller's: scripts/plot_pcs.py on the folder.
// Rows are flushed as they are computed: a stopped sweep keeps its points.
// The two branches and the free run are independent runs and go on the
// machine's cores at once (verification/studies/parallel_for.h): each
// branch's rows of pcs.csv are in its own order, the two branches' rows
// interleaved; runs.csv is written when all three are done.
#pragma once

#include "runs/prescribed_position_sweep.h"
#include "meshes/scene.h"

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
    bool verbose = true;        // progress on stdout
  };

  struct PcsStudy
  {
    PcsBranch up, down;
    std::vector<ForceZeroCrossing> crossings_up, crossings_down;
    std::optional<AmplitudeJump> jump_up, jump_down;
    RunResult free_run;           // status of the free-slider run
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

  PcsStudy run_pcs_sweep(const Scene &scene, const PcsStudySettings &settings, const std::string &dir);

  // The simulated time [s] of run_pcs_sweep's longest chain of runs on `cores`
  // cores (the free run and the two branches go at once, in that order): what
  // sets its wall time.
  double pcs_sweep_chain_time(const PcsStudySettings &settings, unsigned int cores);

} // namespace beamslider
