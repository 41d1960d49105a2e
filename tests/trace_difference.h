// The largest differences of two adaptation traces sampled at the same
// times (tests that compare one model's trace with another's over a short
// window, before the rattling amplifies any difference).
#pragma once

#include "runs/adaptation_run.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace beamslider::testing
{
  struct TraceDifference
  {
    double w = 0; // max |Δw(L/2)| / max |w(L/2)| of the first trace
    double z = 0; // max |Δz_C| / max |z_C − z_C(0)| of the first trace
    double x = 0; // max |Δx_C/L| (absolute)
  };

  // Over the rows with t ≤ t_end that both traces have; the two rows of a
  // pair must be at the same time within time_tolerance [s].
  inline TraceDifference trace_difference(const std::vector<TraceRow> &a, const std::vector<TraceRow> &b,
                                          const double t_end, const double time_tolerance)
  {
    double dw = 0, w = 0, dz = 0, z = 0, dx = 0;
    const std::size_t n = std::min(a.size(), b.size());
    for (std::size_t k = 0; k < n && a[k].t <= t_end + 1e-9; ++k)
      {
        EXPECT_NEAR(a[k].t, b[k].t, time_tolerance);
        dw = std::max(dw, std::abs(a[k].w_center - b[k].w_center));
        w  = std::max(w, std::abs(a[k].w_center));
        dz = std::max(dz, std::abs(a[k].slider_z - b[k].slider_z));
        z  = std::max(z, std::abs(a[k].slider_z - a[0].slider_z));
        dx = std::max(dx, std::abs(a[k].slider_x_over_L - b[k].slider_x_over_L));
      }
    return {dw / w, dz / z, dx};
  }
} // namespace beamslider::testing
