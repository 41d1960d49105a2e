// A number in a one-line message, in the stream's default notation with a
// given count of significant digits (0.0125, 1.5e-07): the mesh readers'
// positions, lengths and Jacobians.
#pragma once

#include <sstream>
#include <string>

namespace beamslider
{
  inline std::string number_with_digits(const double x, const int significant_digits)
  {
    std::ostringstream s;
    s.precision(significant_digits);
    s << x;
    return s.str();
  }
} // namespace beamslider
