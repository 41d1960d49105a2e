// The reduced model's basis on a Hermite mode table, see mode_table_basis.h.
#include "fem/mode_table_basis.h"

#include <deal.II/base/quadrature_lib.h>

namespace beamslider
{
  ModalBasis modal_basis_from_table(std::shared_ptr<const HermiteModeTable> table, const Eigen::VectorXd &omega,
                                    const Eigen::VectorXd &gamma, const double membrane_stiffness)
  {
    ModalBasis basis;
    basis.length             = table->length;
    basis.omega              = omega;
    basis.gamma              = gamma;
    basis.membrane_stiffness = membrane_stiffness;
    const unsigned int n_modes = table->n_modes;
    basis.stretch              = Eigen::MatrixXd::Zero(n_modes, n_modes);
    const dealii::QGauss<1> gauss(3);
    Eigen::VectorXd phi, dphi;
    for (unsigned int e = 0; e < table->n_intervals; ++e)
      {
        const double x_0 = table->vertices[e], h = table->vertices[e + 1] - x_0;
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            table->evaluate(x_0 + gauss.point(q)[0] * h, phi, dphi);
            basis.stretch += gauss.weight(q) * h * dphi * dphi.transpose();
          }
      }
    basis.table    = table;
    basis.evaluate = [table](double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) { table->evaluate(x, phi, dphi); };
    basis.displacement = [table](double x, const Eigen::VectorXd &q, double &w, double &dw) {
      table->displacement(x, q, w, dw);
    };
    return basis;
  }
} // namespace beamslider
