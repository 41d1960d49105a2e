// Operating-range maps: the adaptation run (or a K-member ensemble) on every
// cell of a grid over scene parameters — excitation frequency, acceleration
// amplitude, start position, or any other parameter by its scene path — each
// member classified by the one trace analysis (runs/trace_analysis.h).
//
// A cell's result is its members (MapMember); the files of a map, map.csv
// and the reading back of its finished cells for a restart, are the
// caller's (verification/report/map_files.h).
#pragma once

#include "runs/trace_analysis.h"
#include "scene/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  // One grid axis: a scene parameter and its values.
  struct MapAxis
  {
    std::string parameter;      // scene path, "Excitation/Frequency"
    std::string column;         // map.csv column, "frequency_hz"
    std::vector<double> values; // ascending
  };

  // A grid value as text (12 significant digits): as a cell's scene sets it
  // and as map.csv writes it, the same on every rank and every run.
  std::string grid_value_text(double x);

  // "A:B:STEP" (A, A + STEP, … up to B within 1e-9 STEP) or one value "A".
  // InputError naming `option` for anything else, STEP ≤ 0, B < A, non-finite
  // numbers or more than 10 000 values.
  std::vector<double> parse_grid_range(const std::string &text, const std::string &option);
  // "Section/Name=A:B:STEP" (the --axis option): the parameter, a column
  // named after it (lowercase, non-alphanumerics as '_').
  MapAxis parse_parameter_axis(const std::string &text);

  struct MapGrid
  {
    std::vector<MapAxis> axes; // the first varies slowest
    std::size_t n_cells() const;
    // The axis values of cell c (row-major over the axes).
    std::vector<double> cell_values(std::size_t c) const;
    // InputError, naming `command`, if a parameter is given as two axes.
    void check_distinct_parameters(const std::string &command) const;
  };

  struct MapSettings
  {
    ModelSetting model;          // family; Δt, modes, elements from each cell's scene, unless `chosen`
    bool chosen = false;         // `model` as it is in every cell (--model auto)
    unsigned int n_members = 1;  // K
    double perturbation    = 1e-9; // start x_C/L + m ε
    double end_time        = 60.;  // [s]
  };

  // The scene of a cell: the scene file with the user's overrides, then the
  // axes' values (an axis overrides a --set of the same parameter), the end
  // time; validated (InputError for a cell outside the allowed ranges).
  Scene map_cell_scene(const std::string &scene_file, const std::vector<std::string> &overrides,
                       const MapGrid &grid, std::size_t cell, double end_time);

  // One member of a cell: how its run ended and the trace analysis.
  struct MapMember
  {
    unsigned int index  = 0;
    double perturbation = 0; // m ε [-]
    RunStatus status    = RunStatus::completed;
    TraceAnalysis analysis;
  };
  // Runs cell c's K members (one thread). A member whose run fails has
  // status and outcome "failed", never an exception; an invalid cell scene
  // throws InputError. Empty if a member was interrupted (Ctrl-C): an
  // interrupted cell is no result.
  std::vector<MapMember> run_map_cell_members(const std::string &scene_file, const std::vector<std::string> &overrides,
                                              const MapGrid &grid, std::size_t cell, const MapSettings &settings);
  // Every cell of the grid in this process, on all cores (threads); a map
  // on many machines is `beamslider map` under mpirun. `on_cell(done, n)`
  // (optional, serialised) reports progress. After Ctrl-C the cells not yet
  // started stay empty, like an interrupted one.
  std::vector<std::vector<MapMember>> run_map_cells(const std::string &scene_file,
                                                    const std::vector<std::string> &overrides, const MapGrid &grid,
                                                    const MapSettings &settings,
                                                    const std::function<void(std::size_t, std::size_t)> &on_cell = {});

  // The published cases (simulation_cases.h) that differ from the scene
  // file only in frequency, acceleration and start position — those a map
  // over them can show — with the class their name says.
  struct PublishedMapCase
  {
    std::string name, expected_outcome;
    double frequency_hz = 0, acceleration = 0, start_over_L = 0, end_time = 0;
  };
  std::vector<PublishedMapCase> published_map_cases();
} // namespace beamslider
