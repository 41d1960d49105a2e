// The evidence of convergence checks (verification/studies/
// convergence_check.h) as a table in Markdown and as convergence.csv, for
// the ladder, `ensemble --model fe` and the report.
//
// convergence.csv: one row per trial of every check:
//   check,parameter,trial,model,time_step_s,n_modes,members,
//   final_x_median,final_x_min,final_x_max,final_amplitude_median,
//   w1_to_next,w1_to_next_low,w1_to_next_high,spread,distinguishable,
//   observed_order,remaining_error,tolerance,wall_s_per_member,status
// where the trials are sorted coarsest first, the W₁ columns compare the
// trial with the next refinement (empty for the last), the order columns
// are a check judged by order's estimates for that step (empty where none
// was made; an order of "inf" where the finer pair ended exactly alike) and
// status is accepted | refined | check | witness | not converged |
// unchecked.
#pragma once

#include "verification/studies/convergence_check.h"

#include <string>
#include <vector>

namespace beamslider
{
  // The table of every check's trials and one verdict line per check.
  std::string describe_convergence(const std::vector<ConvergenceCheck> &checks);

  // Writes `dir`/`name` (convergence.csv unless named).
  void write_convergence_csv(const std::string &dir, const std::vector<ConvergenceCheck> &checks,
                             const std::string &name = "convergence.csv");
} // namespace beamslider
