// Constructed per-period records for tests of the trace analysis and the
// case verdicts: periods of a 124 Hz excitation from t = 0 to t_end, with
// the slider position x_C/L and the amplitude/h given as functions of the
// period's start time.
#pragma once

#include "runs/adaptation_run.h"

#include <functional>
#include <vector>

namespace beamslider
{
  inline std::vector<PeriodRecord> synthetic_periods(const double t_end, const std::function<double(double)> &x,
                                                     const std::function<double(double)> &amplitude)
  {
    const double T = 1. / 124.;
    std::vector<PeriodRecord> p;
    for (unsigned int k = 0; (k + 1) * T <= t_end; ++k)
      {
        PeriodRecord r;
        r.index            = k;
        r.t_start          = k * T;
        r.t_end            = (k + 1) * T;
        r.slider_x_over_L  = x(r.t_start);
        r.amplitude_over_h = amplitude(r.t_start);
        p.push_back(r);
      }
    return p;
  }
} // namespace beamslider
