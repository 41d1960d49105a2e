// The files of the held slider's slow manifold (`beamslider branches` and
// report section 4): the study run with its rows written as they come, and
// its description in words.
//
//   attractor.csv      x_over_L, period_count, beam_spread, slider_spread,
//                      lyapunov_per_period, lyapunov_per_s, amplitude_over_h,
//                      mean_fx_N: the rattling held slider of the scene's ROM
//                      at each probe (period_count 0: no period ≤ 8 found);
//   branches.csv       x_over_L, amplitude_over_h, mean_fx_N, stable,
//                      largest_multiplier, integration_growth (every 50th
//                      orbit: the stability by time integration), period_count,
//                      branch, model: the
//                      attached-slider model's periodic orbits along x_C
//                      (period_count 1: orbits of one excitation period);
//   branch_events.csv  kind, x_over_L, amplitude_over_h, mean_fx_N: turning
//                      points, period doublings and tori met on the branch.
#pragma once

#include "scene/scene.h"
#include "verification/studies/slow_manifold.h"

#include <string>

namespace beamslider
{
  // compute_slow_manifold with its rows in `dir` as they come and its
  // progress on the console.
  SlowManifold run_slow_manifold_into(const Scene &scene, const SlowManifoldSettings &settings, const std::string &dir);

  // What it found, in Markdown (a table of the probes, the branch, its
  // events), its two parts under headings of the given level ("##").
  std::string describe_slow_manifold(const SlowManifold &m, const Scene &scene, const std::string &heading = "##");
} // namespace beamslider
