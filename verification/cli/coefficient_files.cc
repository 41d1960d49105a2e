#include "verification/cli/coefficient_files.h"

#include "io/csv_writer.h"

namespace beamslider
{
  void write_coefficients_csv(const std::string &filename, const std::vector<CubicTerm> &terms)
  {
    CsvWriter csv(filename, {"n", "j", "k", "l", "value"});
    for (const auto &t : terms)
      csv.row({CsvWriter::cell(t.n + 1), CsvWriter::cell(t.j + 1), CsvWriter::cell(t.k + 1), CsvWriter::cell(t.l + 1),
               CsvWriter::cell(t.value, 17)});
    csv.close();
  }

  void write_quadratic_coefficients_csv(const std::string &filename, const std::vector<QuadraticTerm> &terms)
  {
    CsvWriter csv(filename, {"n", "j", "k", "value"});
    for (const auto &t : terms)
      csv.row({CsvWriter::cell(t.n + 1), CsvWriter::cell(t.j + 1), CsvWriter::cell(t.k + 1), CsvWriter::cell(t.value, 17)});
    csv.close();
  }
} // namespace beamslider
