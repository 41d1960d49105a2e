#include "fem/solid_modal_basis.h"

#include "fem/mode_table_basis.h"
#include "fem/solid_point_values.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <memory>

namespace beamslider
{
  using namespace dealii;

  template <int dim>
  ModalBasis make_solid_modal_basis(const SolidModel<dim> &model, const SolidModes &modes, const unsigned int n_modes,
                                    const Scene &scene, const unsigned int n_intervals)
  {
    if (scene.solid.arch_rise != 0)
      throw InputError("Parameter 'Solid/Arch rise' = " + std::to_string(scene.solid.arch_rise) +
                       " m: a reduced model for the slider needs the straight strip (the contact code's beam line)");
    if (n_modes > modes.bending.size())
      throw std::invalid_argument("make_solid_modal_basis: " + std::to_string(n_modes) + " modes asked, " +
                                  std::to_string(modes.bending.size()) + " bending modes computed");
    const double L = model.length(), b = model.width();
    // Across the width: 2 Gauss points on each eighth, exact for the
    // piecewise polynomials of a mesh whose width divisions are multiples
    // of b/8 (the generated strip's 1, 2, 4 or 8).
    const QIterated<1> across(QGauss<1>(2), 8);
    const unsigned int n_across = dim == 3 ? across.size() : 1;
    std::vector<Point<dim>> points;
    for (unsigned int i = 0; i <= n_intervals; ++i)
      for (unsigned int q = 0; q < n_across; ++q)
        {
          Point<dim> p;
          p[0] = L * i / n_intervals;
          if (dim == 3)
            p[1] = (across.point(q)[0] - 0.5) * b;
          points.push_back(p); // z = 0
        }
    const SolidPointValues<dim> line(model, points);

    auto table         = std::make_shared<HermiteModeTable>();
    table->length      = L;
    table->n_intervals = n_intervals;
    table->n_modes     = n_modes;
    for (unsigned int i = 0; i <= n_intervals; ++i)
      table->vertices.push_back(i == n_intervals ? L : L * i / n_intervals);
    table->coefficients.assign(4 * n_modes * n_intervals, 0.);

    Eigen::VectorXd omega(n_modes), gamma(n_modes);
    std::vector<Tensor<1, dim>> values;
    std::vector<Tensor<2, dim>> gradients;
    for (unsigned int n = 0; n < n_modes; ++n)
      {
        const SolidMode &mode = modes.all[modes.bending[n]];
        omega[n]              = mode.omega;
        line.evaluate(mode.vector, &values, &gradients);
        for (unsigned int i = 0; i <= n_intervals; ++i)
          {
            double w = 0, slope = 0;
            for (unsigned int q = 0; q < n_across; ++q)
              {
                const double weight = dim == 3 ? across.weight(q) : 1.;
                w += weight * values[i * n_across + q][dim - 1];
                slope += weight * gradients[i * n_across + q][dim - 1][0];
              }
            // The vertex is the right end of interval i − 1 and the left of i.
            if (i > 0)
              {
                table->coefficients[4 * (n_modes * (i - 1) + n) + 2] = w;
                table->coefficients[4 * (n_modes * (i - 1) + n) + 3] = slope;
              }
            if (i < n_intervals)
              {
                table->coefficients[4 * (n_modes * i + n) + 0] = w;
                table->coefficients[4 * (n_modes * i + n) + 1] = slope;
              }
          }

        // γ_n = −∫ ρ φ_z dV over the whole solid.
        const auto &fe = model.get_dof_handler().get_fe();
        FEValues<dim> fe_values(model.mapping(), fe, model.quadrature(), update_values | update_JxW_values);
        const FEValuesExtractors::Vector displacement(0);
        std::vector<Tensor<1, dim>> phi(model.quadrature().size());
        double integral = 0;
        for (const auto &cell : model.get_dof_handler().active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              fe_values[displacement].get_function_values(mode.vector, phi);
              const double rho = model.material(cell->material_id()).density * model.out_of_plane_thickness();
              for (const unsigned int q : fe_values.quadrature_point_indices())
                integral += rho * phi[q][dim - 1] * fe_values.JxW(q);
            }
        gamma[n] = -Utilities::MPI::sum(integral, model.communicator());
      }
    return modal_basis_from_table(table, omega, gamma, scene.supports.membrane_stiffness(scene.beam));
  }

  template ModalBasis make_solid_modal_basis(const SolidModel<2> &, const SolidModes &, unsigned int, const Scene &,
                                             unsigned int);
  template ModalBasis make_solid_modal_basis(const SolidModel<3> &, const SolidModes &, unsigned int, const Scene &,
                                             unsigned int);
} // namespace beamslider
