// The CSV writer, see csv_writer.h.
#include "contact/csv_writer.h"

#include <cerrno>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  CsvWriter::CsvWriter(const std::string &path, const std::vector<std::string> &columns, const CsvOptions &options)
    : file_(path, options.append)
    , n_columns_(columns.size())
    , flush_every_(options.flush_every)
  {
    if (!options.append)
      {
        if (!options.comment.empty())
          file_.stream() << "# " << options.comment << '\n';
        file_.stream() << line(columns) << '\n';
      }
    file_.flush(); // an unwritable file fails here, before any work is done
  }

  void CsvWriter::check_width(const std::size_t n_cells) const
  {
    if (n_cells != n_columns_)
      throw std::logic_error("CSV row with " + std::to_string(n_cells) + " cells for '" + path() + "', header has " +
                             std::to_string(n_columns_));
  }

  void CsvWriter::row(const std::vector<std::string> &cells)
  {
    check_width(cells.size());
    errno = 0;
    file_.stream() << line(cells);
    end_row();
  }

  void CsvWriter::numbers(const std::vector<double> &values, const int digits)
  {
    check_width(values.size());
    errno      = 0;
    auto &out  = file_.stream();
    const auto old = out.precision(digits);
    for (std::size_t i = 0; i < values.size(); ++i)
      out << (i ? "," : "") << values[i];
    out.precision(old);
    end_row();
  }

  void CsvWriter::end_row()
  {
    file_.stream() << '\n';
    file_.check(); // a full buffer was written out just now and failed
    if (flush_every_ > 0 && ++pending_ >= flush_every_)
      flush();
  }

  void CsvWriter::flush()
  {
    file_.flush();
    pending_ = 0;
  }

  void CsvWriter::close() { file_.close(); }

  std::string CsvWriter::cell(const double x, const int digits)
  {
    std::ostringstream s;
    s << std::setprecision(digits) << x;
    return s.str();
  }

  std::string CsvWriter::line(const std::vector<std::string> &cells)
  {
    std::string text;
    for (std::size_t i = 0; i < cells.size(); ++i)
      (text += i ? "," : "") += cells[i];
    return text;
  }

  std::vector<std::string> CsvWriter::cells(const std::string &line)
  {
    std::vector<std::string> cells(1);
    for (const char c : line)
      if (c == ',')
        cells.emplace_back();
      else
        cells.back() += c;
    return cells;
  }
} // namespace beamslider
