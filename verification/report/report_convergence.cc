// Convergence evidence as Markdown and CSV, see report_convergence.h.
#include "verification/report/report_convergence.h"

#include "io/csv_writer.h"
#include "verification/report/report.h"

#include <cmath>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string status(const ConvergenceCheck &c, const std::size_t k)
    {
      if (c.trials[k].witness)
        return "witness";
      if (c.converged)
        return k == c.accepted ? "accepted" : k < c.accepted ? "refined" : "check";
      if (c.trials.size() < 2)
        return "unchecked";
      return k + 1 == c.trials.size() ? "not converged" : "refined";
    }

    // An estimate of a check judged by order, empty where none was made.
    std::string estimate(const double x)
    {
      return std::isnan(x) ? std::string() : std::isinf(x) ? std::string("inf") : CsvWriter::cell(x);
    }

    std::string range(const OutcomeStatistics &s, const int digits)
    {
      if (s.n == 0)
        return "–";
      return fixed(s.median, digits) + " [" + fixed(s.min, digits) + ", " + fixed(s.max, digits) + "]";
    }
  } // namespace

  std::string describe_convergence(const std::vector<ConvergenceCheck> &checks)
  {
    std::ostringstream md;
    md << "| check | trial | final x_C/L median [min, max] | final amplitude [h] median [min, max] | W₁ to the next "
          "refinement [90 %] | spread | wall per member [s] | status |\n|---|---|---|---|---|---|---|---|\n";
    for (const ConvergenceCheck &c : checks)
      for (std::size_t k = 0; k < c.trials.size(); ++k)
        {
          const ConvergenceTrial &t = c.trials[k];
          const SampleComparison &d = t.position_to_next;
          md << "| " << c.name << " | " << t.model.label() << " | " << range(t.final_position, 4) << " | "
             << range(t.final_amplitude, 3) << " | "
             << (d.n_a == 0 || std::isnan(d.wasserstein)
                   ? std::string("–")
                   : fixed(d.wasserstein, 4) + " [" + fixed(d.interval_low, 4) + ", " + fixed(d.interval_high, 4) + "]")
             << " | " << (d.n_a == 0 ? std::string("–") : fixed(d.spread, 4)) << " | "
             << fixed(t.wall_seconds_per_member, 1) << " | " << status(c, k) << " |\n";
        }
    md << "\n";
    for (const ConvergenceCheck &c : checks)
      md << "- " << (c.converged ? "" : "**") << c.verdict() << (c.converged ? "" : "**") << ".\n";
    return md.str();
  }

  void write_convergence_csv(const std::string &dir, const std::vector<ConvergenceCheck> &checks,
                             const std::string &name)
  {
    CsvWriter csv(dir + "/" + name,
                  {"check", "parameter", "trial", "model", "time_step_s", "n_modes", "members", "final_x_median",
                   "final_x_min", "final_x_max", "final_amplitude_median", "w1_to_next", "w1_to_next_low",
                   "w1_to_next_high", "spread", "distinguishable", "observed_order", "remaining_error",
                   "tolerance", "wall_s_per_member", "status"});
    for (const ConvergenceCheck &c : checks)
      for (std::size_t k = 0; k < c.trials.size(); ++k)
        {
          const ConvergenceTrial &t = c.trials[k];
          const SampleComparison &d = t.position_to_next;
          const bool next           = d.n_a > 0;
          const auto maybe          = [next](const double x) { return next ? CsvWriter::cell(x) : std::string(); };
          csv.row({c.name, c.parameter, CsvWriter::cell(k), t.model.label(), CsvWriter::cell(t.model.time_step),
                   CsvWriter::cell(t.model.n_modes), CsvWriter::cell(t.members.size()),
                   CsvWriter::cell(t.final_position.median), CsvWriter::cell(t.final_position.min),
                   CsvWriter::cell(t.final_position.max), CsvWriter::cell(t.final_amplitude.median),
                   maybe(d.wasserstein), maybe(d.interval_low), maybe(d.interval_high), maybe(d.spread),
                   next ? (d.distinguishable ? "1" : "0") : "", estimate(t.observed_order),
                   estimate(t.remaining_error), estimate(t.tolerance), CsvWriter::cell(t.wall_seconds_per_member, 4),
                   status(c, k)});
        }
    csv.close();
  }
} // namespace beamslider
