// A small CSV writer: a header of named columns (SI units in the names where
// they are not obvious), then rows of numbers or strings. Rows are flushed as
// they are written, so a long run never loses finished work; a failed open or
// write throws OutputError.
#pragma once

#include "contact/output_file.h"

#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  class CsvWriter
  {
  public:
    CsvWriter(const std::string &filename, const std::vector<std::string> &columns)
      : out(filename)
      , n_columns(columns.size())
      , filename_(filename)
    {
      if (!out)
        throw OutputError("result file '" + filename + "' cannot be opened for writing");
      for (std::size_t i = 0; i < columns.size(); ++i)
        out << (i ? "," : "") << columns[i];
      out << '\n';
    }

    // A row of cells already formatted (use cell() for numbers).
    void row(const std::vector<std::string> &cells)
    {
      if (cells.size() != n_columns)
        throw std::logic_error("CSV row with " + std::to_string(cells.size()) + " cells, header has " +
                               std::to_string(n_columns));
      for (std::size_t i = 0; i < cells.size(); ++i)
        out << (i ? "," : "") << cells[i];
      out << '\n' << std::flush;
      if (!out)
        throw OutputError("result file '" + filename_ + "' could not be written");
    }

    static std::string cell(const double x, const int digits = 10)
    {
      std::ostringstream s;
      s << std::setprecision(digits) << x;
      return s.str();
    }
    static std::string cell(const unsigned int x) { return std::to_string(x); }
    static std::string cell(const int x) { return std::to_string(x); }

  private:
    std::ofstream out;
    std::size_t n_columns;
    std::string filename_;
  };
} // namespace beamslider
