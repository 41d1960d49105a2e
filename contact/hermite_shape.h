// Cubic Hermite shape functions on a cell of length h at ξ ∈ [0, 1], for
// the nodal values (w0, θ0, w1, θ1), with their derivatives in x. Inline
// and free of deal.II: the reduced model evaluates them at the slider's
// corners every time step (reduced/hermite_mode_table.h, and the explicit
// modal step, contact/explicit_modal_step.cc), the FE beam in its
// assembly (fem/fe_beam.h).
#pragma once

#include <algorithm>
#include <array>

namespace beamslider
{
  // Values N and slopes N'.
  inline void hermite_shape(const double xi, const double h, std::array<double, 4> &N, std::array<double, 4> &dN)
  {
    const double xi2 = xi * xi, xi3 = xi2 * xi;
    N  = {{1 - 3 * xi2 + 2 * xi3, h * (xi - 2 * xi2 + xi3), 3 * xi2 - 2 * xi3, h * (-xi2 + xi3)}};
    dN = {{(-6 * xi + 6 * xi2) / h, 1 - 4 * xi + 3 * xi2, (6 * xi - 6 * xi2) / h, -2 * xi + 3 * xi2}};
  }

  // The same with 1/h given (the contact code's hot paths keep it per
  // evaluation: one division instead of three).
  inline void hermite_shape(const double xi, const double h, const double inv_h, std::array<double, 4> &N,
                            std::array<double, 4> &dN)
  {
    const double xi2 = xi * xi, xi3 = xi2 * xi;
    N  = {{1 - 3 * xi2 + 2 * xi3, h * (xi - 2 * xi2 + xi3), 3 * xi2 - 2 * xi3, h * (-xi2 + xi3)}};
    dN = {{(-6 * xi + 6 * xi2) * inv_h, 1 - 4 * xi + 3 * xi2, (6 * xi - 6 * xi2) * inv_h, -2 * xi + 3 * xi2}};
  }

  // Values, slopes and curvatures N''.
  inline void hermite_shape(const double xi, const double h, std::array<double, 4> &N, std::array<double, 4> &dN,
                            std::array<double, 4> &ddN)
  {
    hermite_shape(xi, h, N, dN);
    ddN = {{(-6 + 12 * xi) / (h * h), (-4 + 6 * xi) / h, (6 - 12 * xi) / (h * h), (-2 + 6 * xi) / h}};
  }

  // The interval of a line of n_intervals intervals with ends vertices[0..n]
  // (increasing) that holds x ∈ [vertices[0], vertices[n]]: the last left end
  // at or before x, the last interval for x at the right end. The caller
  // checks the range (reduced/hermite_mode_table.h, the explicit modal step).
  inline unsigned int interval_holding(const double *vertices, const unsigned int n_intervals, const double x)
  {
    const long e = std::upper_bound(vertices, vertices + n_intervals + 1, x) - vertices - 1;
    return static_cast<unsigned int>(std::clamp<long>(e, 0, static_cast<long>(n_intervals) - 1));
  }
} // namespace beamslider
