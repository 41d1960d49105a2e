// Hermite mode table, see hermite_mode_table.h.
#include "reduced/hermite_mode_table.h"

#include "contact/hermite_shape.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace beamslider
{
  unsigned int HermiteModeTable::interval(const double x) const
  {
    if (!(x >= 0 && x <= length))
      throw std::out_of_range("modal basis evaluated at x = " + std::to_string(x) + " m, outside [0, " +
                              std::to_string(length) + "] m");
    return interval_holding(vertices.data(), n_intervals, x);
  }

  void HermiteModeTable::evaluate(const double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) const
  {
    const unsigned int e = interval(x);
    const double h       = vertices[e + 1] - vertices[e];
    std::array<double, 4> N, dN;
    hermite_shape((x - vertices[e]) / h, h, N, dN);
    phi.resize(n_modes);
    dphi.resize(n_modes);
    const double *c = &coefficients[4 * n_modes * e];
    for (unsigned int n = 0; n < n_modes; ++n, c += 4)
      {
        phi[n]  = N[0] * c[0] + N[1] * c[1] + N[2] * c[2] + N[3] * c[3];
        dphi[n] = dN[0] * c[0] + dN[1] * c[1] + dN[2] * c[2] + dN[3] * c[3];
      }
  }

  void HermiteModeTable::displacement(const double x, const Eigen::VectorXd &q, double &w, double &dw) const
  {
    const unsigned int e = interval(x);
    const double h = vertices[e + 1] - vertices[e], inv_h = 1. / h, xi = (x - vertices[e]) * inv_h;
    // (w0, θ0, w1, θ1) of the deflection Σ φ_n q_n at the interval's ends.
    std::array<double, 4> nodal{{0., 0., 0., 0.}};
    const double *c = &coefficients[4 * n_modes * e];
    for (unsigned int n = 0; n < n_modes; ++n, c += 4)
      for (unsigned int a = 0; a < 4; ++a)
        nodal[a] += c[a] * q[n];
    std::array<double, 4> N, dN;
    hermite_shape(xi, h, inv_h, N, dN);
    w  = N[0] * nodal[0] + N[1] * nodal[1] + N[2] * nodal[2] + N[3] * nodal[3];
    dw = dN[0] * nodal[0] + dN[1] * nodal[1] + dN[2] * nodal[2] + dN[3] * nodal[3];
  }
} // namespace beamslider
