// A small CSV writer: a header of named columns (SI units in the names where
// they are not obvious), then rows of numbers or strings. Rows are flushed as
// they are written, so a long run never loses finished work.
#pragma once

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
    {
      if (!out)
        throw std::runtime_error("Cannot open '" + filename + "' for writing");
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
  };
} // namespace beamslider
