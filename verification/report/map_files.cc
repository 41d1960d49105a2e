// The files of a map, see map_files.h.
#include "verification/report/map_files.h"
#include "io/input_file.h"

#include "io/csv_writer.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // Results: 8 significant digits (far below the ensemble spread).
    std::string result_field(const double x) { return CsvWriter::cell(x, 8); }
  } // namespace

  std::vector<std::string> map_csv_columns(const MapGrid &grid)
  {
    std::vector<std::string> columns;
    for (const MapAxis &a : grid.axes)
      columns.push_back(a.column);
    for (const char *c : {"member", "perturbation", "status", "outcome", "final_x_over_L", "late_amplitude_over_h",
                          "adaptation_time_s", "jump_count", "first_jump_time_s"})
      columns.emplace_back(c);
    return columns;
  }

  std::string map_cell_key(const MapGrid &grid, const std::size_t cell)
  {
    std::string key;
    const std::vector<double> values = grid.cell_values(cell);
    for (std::size_t k = 0; k < values.size(); ++k)
      key += (k ? "," : "") + grid_value_text(values[k]);
    return key;
  }

  std::string map_row_cell_key(const std::string &row, const std::size_t n_axes)
  {
    std::size_t end = 0;
    for (std::size_t k = 0; k < n_axes; ++k)
      {
        end = row.find(',', end);
        if (end == std::string::npos)
          return row;
        ++end;
      }
    return row.substr(0, end == 0 ? 0 : end - 1);
  }

  std::string format_map_rows(const MapGrid &grid, const std::size_t cell, const std::vector<MapMember> &members)
  {
    // The axis values, one cell each (as map_cell_key writes them).
    std::vector<std::string> axis_cells;
    for (const double v : grid.cell_values(cell))
      axis_cells.push_back(grid_value_text(v));
    std::string rows;
    for (const MapMember &m : members)
      {
        const TraceAnalysis &a = m.analysis;
        const auto if_valid    = [&](const double x) { return a.valid ? result_field(x) : std::string(); };
        std::vector<std::string> row = axis_cells;
        row.insert(row.end(), {CsvWriter::cell(m.index), result_field(m.perturbation), to_string(m.status),
                               to_string(a.outcome), if_valid(a.final_position), if_valid(a.final_amplitude),
                               if_valid(a.adaptation_time), CsvWriter::cell(a.n_upward_jumps),
                               a.jumped ? result_field(a.jump_time) : std::string()});
        rows += CsvWriter::line(row) + '\n';
      }
    return rows;
  }

  void write_map_csv(const std::string &path, const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells)
  {
    CsvWriter csv(path, map_csv_columns(grid));
    for (std::size_t c = 0; c < cells.size(); ++c)
      if (!cells[c].empty())
        {
          std::istringstream lines(format_map_rows(grid, c, cells[c]));
          for (std::string line; std::getline(lines, line);)
            csv.row(CsvWriter::cells(line));
        }
    csv.close();
  }

  std::map<std::string, std::string> read_finished_cells(const std::string &path,
                                                         const std::vector<std::string> &columns,
                                                         const unsigned int n_members)
  {
    std::map<std::string, std::string> finished;
    std::istringstream in(read_text_file_if_present(path));
    std::string header;
    if (!std::getline(in, header) || in.eof())
      return finished; // empty or only a cut header: start afresh
    std::string expected;
    for (std::size_t k = 0; k < columns.size(); ++k)
      expected += (k ? "," : "") + columns[k];
    if (header != expected)
      throw InputError("the output folder's map.csv has the columns '" + header + "', this map writes '" + expected +
                       "': use another --output or remove it");
    const std::size_t n_axes = columns.size() - 9;
    std::map<std::string, std::vector<std::string>> rows;
    std::string line;
    while (std::getline(in, line))
      {
        if (in.eof())
          break; // the last line had no '\n': cut short by a kill
        if (CsvWriter::cells(line).size() != columns.size())
          continue;
        rows[map_row_cell_key(line, n_axes)].push_back(line);
      }
    for (auto &[key, lines] : rows)
      {
        // Complete: members 0 … K−1, each once.
        std::vector<bool> seen(n_members, false);
        bool complete = lines.size() == n_members;
        for (const std::string &l : lines)
          {
            const std::vector<std::string> f = CsvWriter::cells(l);
            const long m = std::strtol(f[n_axes].c_str(), nullptr, 10);
            if (m < 0 || m >= static_cast<long>(n_members) || seen[m])
              complete = false;
            else
              seen[m] = true;
          }
        if (!complete)
          continue;
        std::string block;
        for (const std::string &l : lines)
          block += l + '\n';
        finished[key] = block;
      }
    return finished;
  }
} // namespace beamslider
