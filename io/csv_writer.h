// The one CSV writer of the project: a header of named columns (SI units in
// the names where they are not obvious), then rows of formatted cells or of
// numbers. Every result table goes through it, so the format and the checks
// are the same everywhere: cells separated by commas, rows by '\n', and a
// cell that holds a comma, a double quote or a line break quoted as RFC 4180
// says ("a, b" and "say ""x""", which Python's csv module and spreadsheet
// programs read back as the one cell each was).
//
// The file is an OutputFile, written whole (renamed into place by close()
// or the destructor) unless it is a stream (CsvOptions::in_place, append): a failed open, write, flush or close throws
// OutputError naming the file and the reason. By default every row is
// flushed as it is written, so a stopped run never loses a finished row; a
// writer of many rows per second (trace.csv) may flush every n rows instead.
// A resumed run appends to the file it continues, without a second header.
#pragma once

#include "io/output_file.h"

#include <string>
#include <vector>

namespace beamslider
{
  struct CsvOptions
  {
    // Continue a file that has its header already (a resumed run): open it
    // for appending and write no header.
    bool append = false;
    // A stream that grows during a run and must be there after a kill
    // (trace.csv, statics.csv): written in place (FileMode::stream) rather
    // than whole into a temporary renamed by close().
    bool in_place = false;
    // Rows between flushes: 1 = each row reaches the file when written;
    // 0 = only when the caller flushes (a series of files flushed together).
    unsigned int flush_every = 1;
    // Written as "# comment" above the header (not when appending).
    std::string comment;
  };

  class CsvWriter
  {
  public:
    CsvWriter(const std::string &path, const std::vector<std::string> &columns, const CsvOptions &options = {});

    // A row of cells already formatted (cell() for numbers; "" for empty).
    void row(const std::vector<std::string> &cells);
    // A row of numbers, each with `digits` significant digits.
    void numbers(const std::vector<double> &values, int digits);

    // Pushes buffered rows to the file; throws OutputError on failure.
    void flush();
    // Flushes and closes; throws OutputError on failure. The destructor
    // closes too, but cannot report a failure.
    void close();
    const std::string &path() const { return file_.path(); }

    // `digits` significant digits (std::setprecision).
    static std::string cell(double x, int digits = 10);
    static std::string cell(unsigned long x) { return std::to_string(x); }
    static std::string cell(unsigned int x) { return std::to_string(x); }
    static std::string cell(int x) { return std::to_string(x); }
    // Cells joined into one line, without the '\n', each quoted if it needs
    // to be: for rows that travel as text before they reach a file (a map
    // cell's rows between MPI ranks).
    static std::string line(const std::vector<std::string> &cells);
    // The cells of such a line (the inverse of line(); "a,,b," has 4 cells).
    static std::vector<std::string> cells(const std::string &line);
    // A cell as it is written: as it is, or in double quotes with every
    // quote doubled if it holds a comma, a double quote or a line break.
    static std::string quoted(const std::string &cell);

  private:
    void check_width(std::size_t n_cells) const;
    void end_row();

    OutputFile file_;
    std::size_t n_columns_;
    unsigned int flush_every_, pending_ = 0;
  };
} // namespace beamslider
