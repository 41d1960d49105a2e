// Numbers in text (the report, progress lines, summaries): scientific
// (1.23e-04) or fixed (0.123) notation, a signed difference, a wall time.
#pragma once

#include "numerics/elapsed.h"

#include <chrono>
#include <iomanip>
#include <sstream>
#include <string>

namespace beamslider
{
  inline std::string sci(const double x, const int digits = 3)
  {
    std::ostringstream s;
    s << std::scientific << std::setprecision(digits) << x;
    return s.str();
  }
  inline std::string fixed(const double x, const int digits = 3)
  {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << x;
    return s.str();
  }
  // Wall time since `start`, as "12 s", for timing lines.
  inline std::string seconds_since(const std::chrono::steady_clock::time_point &start)
  {
    return fixed(elapsed_seconds(start), 0) + " s";
  }
  // With its sign always written: a shift or a difference.
  inline std::string signed_fixed(const double x, const int digits = 3)
  {
    return (x >= 0 ? "+" : "") + fixed(x, digits);
  }
} // namespace beamslider
