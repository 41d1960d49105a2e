// Two prescribed-position sweeps of one scene compared on the slow manifold
// the adaptation follows (issue: FE against ROM, where single traces cannot
// be compared): the amplitude branches, which are deterministic, and the
// period-averaged horizontal force F̄_x with its 95 % batch-means interval,
// whose zero crossings are the free slider's equilibria.
//
// Per position and direction: the relative amplitude difference and whether
// the two F̄_x intervals overlap (|F̄_a − F̄_b| ≤ ci_a + ci_b: the sweeps do
// not tell the forces apart there). Per branch: each sweep's zero crossings
// with their intervals (runs/prescribed_position_sweep.h), and for each
// crossing of sweep A the nearest one of B of the same stability, with the
// distance and whether the intervals overlap.
//
// The comparison writes nothing: its files (comparison.csv, crossings.csv)
// and the reading of a sweep's pcs.csv are verification/report/pcs_files.h's.
#pragma once

#include "runs/prescribed_position_sweep.h"

#include <string>
#include <vector>

namespace beamslider
{
  struct PcsComparison
  {
    struct Position
    {
      SweepDirection direction = SweepDirection::up;
      double x_over_L = 0;
      double amplitude = 0, other_amplitude = 0;          // [h]
      double amplitude_relative_difference = 0;           // |a − b| / max(a, b)
      double fx = 0, fx_ci95 = 0, other_fx = 0, other_fx_ci95 = 0; // [N]
      bool fx_intervals_overlap = false;
    };
    struct Branch
    {
      SweepDirection direction = SweepDirection::up;
      std::vector<ForceZeroCrossing> crossings, other_crossings;
      // Amplitude agreement over the positions where both exceed 0.05 h
      // (below that the slider barely rattles and ratios mean little).
      double max_amplitude_difference = 0, median_amplitude_difference = 0;
      unsigned int n_compared = 0, n_fx_overlap = 0, n_positions = 0;
    };
    std::vector<Position> positions;
    Branch up, down;
  };

  // Throws InputError if the sweeps do not hold the same positions in each
  // direction (to 1e-9 in x_C/L), naming the first that differs; only
  // x_over_L and direction are read.
  void require_same_positions(const std::vector<PcsPoint> &points, const std::vector<PcsPoint> &other_points);

  // The comparison; require_same_positions first.
  PcsComparison compare_sweeps(const std::vector<PcsPoint> &points, const std::vector<PcsPoint> &other_points);

  // Markdown lines: amplitude agreement, F̄_x overlap, crossings side by side.
  std::string describe(const PcsComparison &comparison, const std::string &label, const std::string &other_label);
} // namespace beamslider
