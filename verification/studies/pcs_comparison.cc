// Two prescribed-position sweeps compared, see pcs_comparison.h.
#include "verification/studies/pcs_comparison.h"

#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
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
