#include "fem/fe_modal_basis.h"

#include "fem/mode_table_basis.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace beamslider
{
  Eigen::MatrixXd mode_matrix(const FEModes &modes, const unsigned int n_modes)
  {
    const unsigned int n = modes.shapes.at(0).size();
    Eigen::MatrixXd Phi(n, n_modes);
    for (unsigned int k = 0; k < n_modes; ++k)
      for (unsigned int i = 0; i < n; ++i)
        Phi(i, k) = modes.shapes.at(k)[i];
    return Phi;
  }

  ModalBasis make_modal_basis(const FEBeam &beam, const FEModes &modes, unsigned int n_modes)
  {
    if (n_modes == 0)
      n_modes = modes.omega.size();
    if (n_modes > modes.omega.size())
      throw std::invalid_argument("make_modal_basis: " + std::to_string(n_modes) + " modes requested, " +
                                  std::to_string(modes.omega.size()) + " computed");
    Eigen::VectorXd omega(n_modes), gamma(n_modes);
    dealii::Vector<double> r;
    beam.assemble_base_load(r);
    for (unsigned int n = 0; n < n_modes; ++n)
      {
        omega[n] = modes.omega[n];
        gamma[n] = r * modes.shapes[n];
      }

    // The FE modes are Hermite cubics on the elements: their nodal values
    // and slopes are the table.
    auto table         = std::make_shared<HermiteModeTable>();
    table->length      = beam.length();
    table->n_intervals = beam.n_elements();
    table->n_modes     = n_modes;
    table->coefficients.resize(4 * n_modes * table->n_intervals);
    table->vertices.push_back(0.);
    for (unsigned int e = 0; e < table->n_intervals; ++e)
      {
        const auto &cell = beam.cells_in_order()[e];
        const double x_0 = cell->vertex(0)[0], x_1 = cell->vertex(1)[0];
        table->vertices.push_back(e + 1 == table->n_intervals ? beam.length() : x_1);
        const FEPointShape s = beam.point_shape(0.5 * (x_0 + x_1));
        for (unsigned int n = 0; n < n_modes; ++n)
          for (unsigned int a = 0; a < 4; ++a)
            table->coefficients[4 * (n_modes * e + n) + a] = modes.shapes[n][s.w_dofs[a]];
      }
    return modal_basis_from_table(table, omega, gamma, beam.support_data().membrane_stiffness(beam.beam_data()));
  }

  Eigen::VectorXd max_abs_deflection(const FEBeam &beam, const FEModes &modes, const unsigned int n_modes)
  {
    Eigen::VectorXd peak = Eigen::VectorXd::Zero(n_modes);
    const unsigned int n_samples = 8 * beam.n_elements();
    for (unsigned int n = 0; n < n_modes; ++n)
      for (unsigned int s = 0; s <= n_samples; ++s)
        peak[n] = std::max(peak[n], std::abs(beam.deflection(modes.shapes[n], beam.length() * s / n_samples)));
    return peak;
  }

  double axial_weighted_slope_fourth_power(const FEBeam &beam, const dealii::Vector<double> &phi)
  {
    // φ'⁴ has degree 8 per element: 5 Gauss points are exact.
    const dealii::QGauss<1> gauss(5);
    double integral = 0;
    for (const auto &cell : beam.cells_in_order())
      {
        const double x_0 = cell->vertex(0)[0], h = cell->vertex(1)[0] - x_0;
        const double EA = beam.section(cell).axial_stiffness();
        for (unsigned int q = 0; q < gauss.size(); ++q)
          integral += gauss.weight(q) * h * EA * std::pow(beam.slope(phi, x_0 + gauss.point(q)[0] * h), 4);
      }
    return integral;
  }
} // namespace beamslider
