// The CSV writer, see csv_writer.h.
#include "io/csv_writer.h"

#include <cerrno>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  CsvWriter::CsvWriter(const std::string &path, const std::vector<std::string> &columns, const CsvOptions &options)
    : file_(path, options.append     ? FileMode::append
                  : options.in_place ? FileMode::stream
                                     : FileMode::whole)
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

  std::string CsvWriter::quoted(const std::string &cell)
  {
    if (cell.find_first_of(",\"\n\r") == std::string::npos)
      return cell;
    std::string text = "\"";
    for (const char c : cell)
      text += c == '"' ? std::string("\"\"") : std::string(1, c);
    return text + "\"";
  }

  std::string CsvWriter::line(const std::vector<std::string> &cells)
  {
    std::string text;
    for (std::size_t i = 0; i < cells.size(); ++i)
      (text += i ? "," : "") += quoted(cells[i]);
    return text;
  }

  std::vector<std::string> CsvWriter::cells(const std::string &line)
  {
    std::vector<std::string> cells(1);
    bool in_quotes = false;
    for (std::size_t i = 0; i < line.size(); ++i)
      {
        const char c = line[i];
        if (in_quotes)
          {
            if (c != '"')
              cells.back() += c;
            else if (i + 1 < line.size() && line[i + 1] == '"')
              cells.back() += line[++i]; // "" inside quotes: one quote
            else
              in_quotes = false;
          }
        else if (c == '"')
          in_quotes = true;
        else if (c == ',')
          cells.emplace_back();
        else
          cells.back() += c;
      }
    return cells;
  }
} // namespace beamslider
