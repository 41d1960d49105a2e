#include "fem/fe_modal_basis.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace beamslider
{
  namespace
  {
    // The Hermite coefficients (w0, θ0, w1, θ1) of every mode on every
    // element of the uniform mesh: enough to evaluate φ and φ' anywhere.
    struct ElementTable
    {
      double length = 0;
      unsigned int n_elements = 0, n_modes = 0;
      std::vector<double> vertices;     // x of the element boundaries, increasing [m]
      std::vector<double> coefficients; // [element][mode][4]

      void evaluate(const double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) const
      {
        if (!(x >= 0 && x <= length))
          throw std::out_of_range("modal basis evaluated at x = " + std::to_string(x) + " m, outside [0, " +
                                  std::to_string(length) + "] m");
        // The element whose left vertex is the last one at or before x.
        const auto it      = std::upper_bound(vertices.begin(), vertices.end(), x);
        const unsigned int e = std::min<unsigned int>(std::max<long>(it - vertices.begin() - 1, 0), n_elements - 1);
        const double h     = vertices[e + 1] - vertices[e];
        std::array<double, 4> N, dN, ddN;
        hermite_shape((x - vertices[e]) / h, h, N, dN, ddN);
        phi.resize(n_modes);
        dphi.resize(n_modes);
        const double *c = &coefficients[4 * n_modes * e];
        for (unsigned int n = 0; n < n_modes; ++n, c += 4)
          {
            phi[n]  = N[0] * c[0] + N[1] * c[1] + N[2] * c[2] + N[3] * c[3];
            dphi[n] = dN[0] * c[0] + dN[1] * c[1] + dN[2] * c[2] + dN[3] * c[3];
          }
      }
    };
  } // namespace

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
    ModalBasis basis;
    basis.length             = beam.length();
    basis.membrane_stiffness = beam.support_data().membrane_stiffness(beam.beam_data());
    basis.omega.resize(n_modes);
    basis.gamma.resize(n_modes);
    dealii::Vector<double> r;
    beam.assemble_base_load(r);
    for (unsigned int n = 0; n < n_modes; ++n)
      {
        basis.omega[n] = modes.omega[n];
        basis.gamma[n] = r * modes.shapes[n];
      }

    auto table        = std::make_shared<ElementTable>();
    table->length     = beam.length();
    table->n_elements = beam.n_elements();
    table->n_modes    = n_modes;
    table->coefficients.resize(4 * n_modes * table->n_elements);
    table->vertices.push_back(0.);
    for (unsigned int e = 0; e < table->n_elements; ++e)
      {
        const auto &cell = beam.cells_in_order()[e];
        const double x_0 = cell->vertex(0)[0], x_1 = cell->vertex(1)[0];
        table->vertices.push_back(e + 1 == table->n_elements ? beam.length() : x_1);
        const FEPointShape s = beam.point_shape(0.5 * (x_0 + x_1));
        for (unsigned int n = 0; n < n_modes; ++n)
          for (unsigned int a = 0; a < 4; ++a)
            table->coefficients[4 * (n_modes * e + n) + a] = modes.shapes[n][s.w_dofs[a]];
      }

    // K'_jk = ∫ φ_j' φ_k' dx: φ' is quadratic per element, 3 Gauss points are exact.
    basis.stretch = Eigen::MatrixXd::Zero(n_modes, n_modes);
    const dealii::QGauss<1> gauss(3);
    Eigen::VectorXd phi, dphi;
    for (unsigned int e = 0; e < table->n_elements; ++e)
      {
        const double x_0 = table->vertices[e], h = table->vertices[e + 1] - x_0;
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            table->evaluate(x_0 + gauss.point(q)[0] * h, phi, dphi);
            basis.stretch += gauss.weight(q) * h * dphi * dphi.transpose();
          }
      }

    basis.evaluate = [table](double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) { table->evaluate(x, phi, dphi); };
    return basis;
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
