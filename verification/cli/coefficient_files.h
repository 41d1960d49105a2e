// The coefficient files of `coefficients` and `coefficients-solid`: the
// cubic (and quadratic) modal coefficients of reduced/cubic_fit.h as CSV.
#pragma once

#include "reduced/cubic_fit.h"

#include <string>
#include <vector>

namespace beamslider
{
  // coefficients.csv: header "n,j,k,l,value", 1-based mode numbers, SI with
  // mass-normalised modes [1/(s² m² kg)], 17 significant digits (the
  // doubles exactly). A failed open or write throws OutputError.
  void write_coefficients_csv(const std::string &filename, const std::vector<CubicTerm> &terms);
  // The quadratic ones: header "n,j,k,value", 1-based.
  void write_quadratic_coefficients_csv(const std::string &filename, const std::vector<QuadraticTerm> &terms);
} // namespace beamslider
