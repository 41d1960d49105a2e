// Two prescribed-position sweeps compared, see pcs_comparison.h.
#include "verification/studies/pcs_comparison.h"

#include "io/csv_writer.h"
#include "meshes/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::vector<PcsPoint> of_direction(const std::vector<PcsPoint> &points, const SweepDirection d)
    {
      std::vector<PcsPoint> out;
      for (const auto &p : points)
        if (p.direction == d)
          out.push_back(p);
      std::sort(out.begin(), out.end(), [](const PcsPoint &a, const PcsPoint &b) { return a.x_over_L < b.x_over_L; });
      return out;
    }

    std::string fixed(const double x, const int digits)
    {
      std::ostringstream s;
      s << std::fixed << std::setprecision(digits) << x;
      return s.str();
    }

    std::string crossing_text(const ForceZeroCrossing &c)
    {
      return fixed(c.x_over_L, 4) + " [" + fixed(c.x_low_over_L, 4) + ", " + fixed(c.x_high_over_L, 4) + "]" +
             (c.resolved ? "" : " (unresolved)");
    }
  } // namespace

  void require_same_positions(const std::vector<PcsPoint> &points, const std::vector<PcsPoint> &other_points)
  {
    for (const SweepDirection d : {SweepDirection::up, SweepDirection::down})
      {
        const std::vector<PcsPoint> a = of_direction(points, d), b = of_direction(other_points, d);
        for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
          if (std::abs(a[i].x_over_L - b[i].x_over_L) > 1e-9)
            throw InputError("--against: position " + std::to_string(i + 1) + " of direction '" + to_string(d) +
                             "' is x_C/L = " + fixed(a[i].x_over_L, 6) + " here and " + fixed(b[i].x_over_L, 6) +
                             " there; run both with the same --from, --to and --step");
        if (a.size() != b.size())
          throw InputError("--against: the sweeps hold " + std::to_string(a.size()) + " and " +
                           std::to_string(b.size()) + " positions in direction '" + to_string(d) +
                           "'; run both with the same --from, --to and --step");
      }
  }

  PcsComparison compare_sweeps(const std::vector<PcsPoint> &points, const std::vector<PcsPoint> &other_points)
  {
    require_same_positions(points, other_points);
    PcsComparison result;
    for (const SweepDirection d : {SweepDirection::up, SweepDirection::down})
      {
        const std::vector<PcsPoint> a = of_direction(points, d), b = of_direction(other_points, d);
        PcsComparison::Branch &branch = d == SweepDirection::up ? result.up : result.down;
        branch.direction              = d;
        branch.n_positions            = a.size();
        std::vector<double> differences;
        for (std::size_t i = 0; i < a.size(); ++i)
          {
            PcsComparison::Position p;
            p.direction       = d;
            p.x_over_L        = a[i].x_over_L;
            p.amplitude       = a[i].amplitude_over_h;
            p.other_amplitude = b[i].amplitude_over_h;
            const double larger = std::max(p.amplitude, p.other_amplitude);
            p.amplitude_relative_difference = larger > 0. ? std::abs(p.amplitude - p.other_amplitude) / larger : 0.;
            p.fx                   = a[i].mean_fx;
            p.fx_ci95              = a[i].mean_fx_ci95;
            p.other_fx             = b[i].mean_fx;
            p.other_fx_ci95        = b[i].mean_fx_ci95;
            p.fx_intervals_overlap = std::abs(p.fx - p.other_fx) <= p.fx_ci95 + p.other_fx_ci95;
            branch.n_fx_overlap += p.fx_intervals_overlap;
            if (std::min(p.amplitude, p.other_amplitude) > 0.05)
              differences.push_back(p.amplitude_relative_difference);
            result.positions.push_back(p);
          }
        branch.n_compared = differences.size();
        if (!differences.empty())
          {
            std::sort(differences.begin(), differences.end());
            branch.max_amplitude_difference = differences.back();
            const std::size_t n             = differences.size();
            branch.median_amplitude_difference =
              n % 2 ? differences[n / 2] : 0.5 * (differences[n / 2 - 1] + differences[n / 2]);
          }
        branch.crossings       = force_zero_crossings(a);
        branch.other_crossings = force_zero_crossings(b);
      }
    return result;
  }

  std::vector<PcsPoint> read_pcs_csv(const std::string &path)
  {
    std::ifstream in(path);
    if (!in)
      throw InputError("--against: no pcs.csv at '" + path + "'");
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    {
      std::stringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');)
        header.push_back(cell);
    }
    std::map<std::string, std::size_t> column;
    for (const char *name : {"x_over_L", "direction", "amplitude_over_h", "mean_fx_N", "mean_fx_ci95_N"})
      {
        const auto it = std::find(header.begin(), header.end(), name);
        if (it == header.end())
          throw InputError("--against: '" + path + "' is not a sweep's pcs.csv (no column " + name + ")");
        column[name] = it - header.begin();
      }
    std::vector<PcsPoint> points;
    for (unsigned int row_number = 2; std::getline(in, line); ++row_number)
      {
        std::vector<std::string> cells;
        std::stringstream row(line);
        for (std::string cell; std::getline(row, cell, ',');)
          cells.push_back(cell);
        try
          {
            if (cells.size() != header.size())
              throw std::invalid_argument("wrong number of cells");
            PcsPoint p;
            p.x_over_L         = std::stod(cells[column["x_over_L"]]);
            const std::string d = cells[column["direction"]];
            if (d != "up" && d != "down")
              throw std::invalid_argument("direction '" + d + "'");
            p.direction        = d == "up" ? SweepDirection::up : SweepDirection::down;
            p.amplitude_over_h = std::stod(cells[column["amplitude_over_h"]]);
            p.mean_fx          = std::stod(cells[column["mean_fx_N"]]);
            p.mean_fx_ci95     = std::stod(cells[column["mean_fx_ci95_N"]]);
            points.push_back(p);
          }
        catch (const std::exception &e)
          {
            throw InputError("--against: row " + std::to_string(row_number) + " of '" + path +
                             "' cannot be read (" + e.what() + ")");
          }
      }
    return points;
  }

  void write_pcs_comparison(const PcsComparison &comparison, const std::string &dir)
  {
    CsvWriter positions(dir + "/comparison.csv",
                        {"direction", "x_over_L", "amplitude_over_h", "other_amplitude_over_h",
                         "amplitude_relative_difference", "mean_fx_N", "mean_fx_ci95_N", "other_mean_fx_N",
                         "other_mean_fx_ci95_N", "fx_intervals_overlap"});
    for (const auto &p : comparison.positions)
      positions.row({to_string(p.direction), CsvWriter::cell(p.x_over_L), CsvWriter::cell(p.amplitude),
                     CsvWriter::cell(p.other_amplitude), CsvWriter::cell(p.amplitude_relative_difference),
                     CsvWriter::cell(p.fx), CsvWriter::cell(p.fx_ci95), CsvWriter::cell(p.other_fx),
                     CsvWriter::cell(p.other_fx_ci95), p.fx_intervals_overlap ? "1" : "0"});
    CsvWriter crossings(dir + "/crossings.csv",
                        {"sweep", "direction", "x_over_L", "x_low_over_L", "x_high_over_L", "stable", "resolved"});
    for (const auto *branch : {&comparison.up, &comparison.down})
      for (const auto &[name, list] : {std::pair("this", &branch->crossings), std::pair("other", &branch->other_crossings)})
        for (const auto &c : *list)
          crossings.row({name, to_string(branch->direction), CsvWriter::cell(c.x_over_L),
                         CsvWriter::cell(c.x_low_over_L), CsvWriter::cell(c.x_high_over_L), c.stable ? "1" : "0",
                         c.resolved ? "1" : "0"});
  }

  std::string describe(const PcsComparison &comparison, const std::string &label, const std::string &other_label)
  {
    std::ostringstream s;
    for (const auto *branch : {&comparison.up, &comparison.down})
      {
        s << "- Branch " << to_string(branch->direction) << " (" << branch->n_positions << " positions): amplitudes ";
        if (branch->n_compared)
          s << "differ by " << fixed(100 * branch->median_amplitude_difference, 1) << " % (median), "
            << fixed(100 * branch->max_amplitude_difference, 1) << " % (largest) over the " << branch->n_compared
            << " positions where both exceed 0.05 h";
        else
          s << "stay below 0.05 h in one of the sweeps everywhere";
        s << "; the 95 % intervals of F̄_x overlap at " << branch->n_fx_overlap << " of " << branch->n_positions
          << " positions.\n";
        for (const bool stable : {true, false})
          for (const auto &c : branch->crossings)
            {
              if (c.stable != stable)
                continue;
              s << "  - " << (stable ? "stable" : "unstable") << " zero crossing of F̄_x, " << label << ": x_C/L = "
                << crossing_text(c) << "; " << other_label << ": ";
              const ForceZeroCrossing *nearest = nullptr;
              for (const auto &o : branch->other_crossings)
                if (o.stable == stable &&
                    (!nearest || std::abs(o.x_over_L - c.x_over_L) < std::abs(nearest->x_over_L - c.x_over_L)))
                  nearest = &o;
              if (!nearest)
                s << "none of this kind.\n";
              else
                {
                  const bool overlap = nearest->x_low_over_L <= c.x_high_over_L && c.x_low_over_L <= nearest->x_high_over_L;
                  s << crossing_text(*nearest) << ", " << fixed(std::abs(nearest->x_over_L - c.x_over_L), 4)
                    << " L apart, intervals " << (overlap ? "overlap (not distinguishable at this averaging)" : "disjoint")
                    << ".\n";
                }
            }
      }
    return s.str();
  }
} // namespace beamslider
