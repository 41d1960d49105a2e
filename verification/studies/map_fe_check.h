// The operating-range map's classes checked by the FE: the map runs the
// cheap ROM (N = 5) on every cell, so a sample of its cells, most of them on
// class boundaries where a model error shows first, is run again with the
// scene's FE model at its step and at half of it. The FE's class of a cell
// counts as converged when both steps give it; the map's class agrees when
// it is that class. One member per run, as the map has: a boundary cell may
// fall either way for any model, which the count says beside it.
#pragma once

#include "verification/studies/operating_map.h"

#include <string>
#include <vector>

namespace beamslider
{
  struct MapSpotCheck
  {
    std::size_t cell = 0;
    std::vector<double> values; // the cell's axis values
    bool boundary = false;      // a 4-neighbour on the grid has another class
    AdaptationClass rom = AdaptationClass::no_adaptation, fe = AdaptationClass::no_adaptation,
                    fe_half = AdaptationClass::no_adaptation;
    double fe_final_position = 0, fe_half_final_position = 0; // x_C/L
    bool fe_converged() const { return fe == fe_half; }
    bool agrees() const { return fe_converged() && rom == fe; }
  };

  // The cells to check on a two-axis map: `n_boundary` cells whose class
  // differs from a 4-neighbour's and `n_interior` signature-move cells
  // whose neighbours all share it, each set evenly spread over its cells in
  // grid order (fewer where the map has fewer).
  std::vector<std::size_t> spot_check_cells(const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells,
                                            unsigned int n_boundary, unsigned int n_interior);

  // Runs each sampled cell with the scene's FE model at its step and at
  // half of it, one member from the map's start, over `end_time`, on the
  // cores of this process.
  std::vector<MapSpotCheck> run_map_spot_checks(const std::string &scene_file, const std::vector<std::string> &overrides,
                                                const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells,
                                                const std::vector<std::size_t> &sample, double end_time);
} // namespace beamslider
