// The files of a map: map.csv, one row per cell and member, the axis values
// first, then how the member ended and its trace analysis
// (verification/studies/operating_map.h computes them).
//
// A cell's rows are formatted here so that the same cell always gives the
// same bytes (no wall time in them): that is what lets an interrupted map be
// resumed and end with the content of an uninterrupted one
// (verification/cli/command_map.cc).
#pragma once

#include "verification/studies/operating_map.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace beamslider
{
  // map.csv: the axis columns, then those of a member.
  std::vector<std::string> map_csv_columns(const MapGrid &grid);
  // The cell's rows of map.csv, each ending in '\n'.
  std::string format_map_rows(const MapGrid &grid, std::size_t cell, const std::vector<MapMember> &members);
  // A whole map.csv of computed cells (run_map_cells' result; empty cells,
  // not run, are left out). Throws OutputError if it cannot be written.
  void write_map_csv(const std::string &path, const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells);

  // The key of a cell: its axis fields as map.csv writes them.
  std::string map_cell_key(const MapGrid &grid, std::size_t cell);
  // The key of a row: its axis fields as written (the first n_axes fields).
  std::string map_row_cell_key(const std::string &row, std::size_t n_axes);

  // The rows of an existing map.csv grouped by cell key, keeping only the
  // cells with all K members (a map killed mid-write may have left a cell
  // incomplete or a last line cut short). Throws InputError if the header
  // differs from `columns`.
  std::map<std::string, std::string> read_finished_cells(const std::string &path,
                                                         const std::vector<std::string> &columns,
                                                         unsigned int n_members);
} // namespace beamslider
