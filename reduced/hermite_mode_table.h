// Modes along a beam line as cubic Hermite polynomials per interval, from
// the values and slopes (w, θ = w') at the interval ends: φ_n(x) and
// φ_n'(x) anywhere in [0, L]. The FE beam's modes are exactly of this form
// (its elements are Hermite cubics); a solid's modes are sampled into it
// (fem/solid_modal_basis.h). The reduced model's basis is built on it
// (fem/mode_table_basis.h), and its explicit contact step reads the table
// directly (RomBeamSystem::explicit_modal_form).
#pragma once

#include <Eigen/Dense>

#include <vector>

namespace beamslider
{
  struct HermiteModeTable
  {
    double length           = 0;
    unsigned int n_intervals = 0, n_modes = 0;
    std::vector<double> vertices;     // x of the interval ends, increasing, from 0 to L [m]
    std::vector<double> coefficients; // [interval][mode][w0, θ0, w1, θ1]

    // φ_n(x), φ_n'(x) of every mode; throws std::out_of_range outside [0, L].
    void evaluate(double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) const;
    // w(x) = Σ φ_n(x) q_n and w'(x): the interval's nodal values of w and θ
    // for these coordinates, then the Hermite shape functions once.
    void displacement(double x, const Eigen::VectorXd &q, double &w, double &dw) const;
    // The interval holding x; throws std::out_of_range outside [0, L].
    unsigned int interval(double x) const;
  };
} // namespace beamslider
