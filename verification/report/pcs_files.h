// The files of the prescribed-position sweep (verification/studies/pcs_sweep.h
// computes it, verification/studies/pcs_comparison.h compares two sweeps):
// `beamslider sweep` and the report's sections write them through here.
//
// A sweep's folder (SI units, named columns):
//   pcs.csv        x_over_L,direction,amplitude_over_h,mean_fx_N,
//                  amplitude_std_over_h,mean_fx_std_N,n_periods,t_end_s,
//                  mean_fx_ci95_N
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
// pcs.csv holds each branch's rows in its own order, the two branches' rows
// interleaved (they run at once); resonance.csv is written before the runs,
// free_periods.csv when the free run ends, runs.csv when all three are done.
//
// A comparison with another sweep (beamslider sweep --against DIR):
//   comparison.csv  direction,x_over_L,amplitude_over_h,other_amplitude_over_h,
//                   amplitude_relative_difference,mean_fx_N,mean_fx_ci95_N,
//                   other_mean_fx_N,other_mean_fx_ci95_N,fx_intervals_overlap
//   crossings.csv   sweep,direction,x_over_L,x_low_over_L,x_high_over_L,
//                   stable,resolved   (sweep: this | other)
//   pcs_compare.png both sweeps' amplitudes and F̄_x with intervals (the
//                   caller's: scripts/plot_pcs_compare.py)
#pragma once

#include "scene/scene.h"
#include "verification/studies/pcs_comparison.h"
#include "verification/studies/pcs_sweep.h"

#include <string>
#include <vector>

namespace beamslider
{
  // run_pcs_sweep with its files written into `dir` as the runs go and its
  // progress lines on the console.
  PcsStudy run_pcs_sweep_into(const Scene &scene, const PcsStudySettings &settings, const std::string &dir);

  // run_pcs_sweep with its progress lines on the console and no file.
  PcsStudy run_pcs_sweep_in_memory(const Scene &scene, const PcsStudySettings &settings);
  // The files run_pcs_sweep_into writes, of a sweep finished before (the
  // Python module's Sweep.save): each branch's rows in its own order, the up
  // branch first.
  void write_pcs_files(const PcsStudy &study, const std::string &dir);

  // comparison.csv and crossings.csv into dir.
  void write_pcs_comparison(const PcsComparison &comparison, const std::string &dir);

  // Reads a sweep's pcs.csv (the columns above); throws FileReadError for a
  // missing or unreadable file, InputError for a foreign one.
  std::vector<PcsPoint> read_pcs_csv(const std::string &path);
} // namespace beamslider
