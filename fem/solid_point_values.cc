#include "fem/solid_point_values.h"

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>

#include <limits>
#include <sstream>

namespace beamslider
{
  using namespace dealii;

  template <int dim>
  SolidPointValues<dim>::SolidPointValues(const SolidModel<dim> &model, const std::vector<Point<dim>> &points)
    : model(model)
    , n_points(points.size())
  {
    const MPI_Comm comm      = model.communicator();
    const unsigned int rank  = Utilities::MPI::this_mpi_process(comm);
    const unsigned int nobody = std::numeric_limits<unsigned int>::max();
    std::vector<Located> found;
    std::vector<unsigned int> owner(n_points, nobody);
    for (const auto &cell : model.get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto box = cell->bounding_box();
          for (unsigned int k = 0; k < n_points; ++k)
            {
              if (owner[k] == rank || !box.point_inside(points[k], 1e-12))
                continue;
              Point<dim> unit;
              try
                {
                  unit = model.mapping().transform_real_to_unit_cell(cell, points[k]);
                }
              catch (const typename Mapping<dim>::ExcTransformationFailed &)
                {
                  continue;
                }
              if (!cell->reference_cell().contains_point(unit, 1e-10))
                continue;
              owner[k] = rank;
              found.push_back({k, cell, unit});
            }
        }
    // A point on a face between two ranks' cells belongs to the lower rank.
    std::vector<unsigned int> lowest(n_points);
    MPI_Allreduce(owner.data(), lowest.data(), n_points, MPI_UNSIGNED, MPI_MIN, comm);
    for (unsigned int k = 0; k < n_points; ++k)
      if (lowest[k] == nobody)
        {
          std::ostringstream where;
          where << "(" << points[k] << ") m";
          throw InputError("The solid mesh has no cell at the point " + where.str() +
                           ", which the beam line of Beam/Length, Width and Thickness needs; the mesh must fill the "
                           "strip 0 <= x <= L, |y| <= b/2, |z| <= h/2");
        }
    for (const Located &l : found)
      if (lowest[l.index] == rank)
        mine.push_back(l);
  }

  template <int dim>
  void SolidPointValues<dim>::evaluate(const PETScWrappers::MPI::Vector &u, std::vector<Tensor<1, dim>> *values,
                                       std::vector<Tensor<2, dim>> *gradients) const
  {
    // Every point's value from its rank, zeros elsewhere, summed.
    std::vector<double> flat(n_points * (dim + dim * dim), 0.);
    const auto &fe = model.get_dof_handler().get_fe();
    const FEValuesExtractors::Vector displacement(0);
    std::vector<Tensor<1, dim>> value(1);
    std::vector<Tensor<2, dim>> gradient(1);
    for (const Located &l : mine)
      {
        FEValues<dim> fe_values(model.mapping(), fe, Quadrature<dim>(std::vector<Point<dim>>{l.unit}),
                                update_values | update_gradients);
        fe_values.reinit(l.cell);
        fe_values[displacement].get_function_values(u, value);
        fe_values[displacement].get_function_gradients(u, gradient);
        double *out = &flat[l.index * (dim + dim * dim)];
        for (unsigned int a = 0; a < dim; ++a)
          {
            out[a] = value[0][a];
            for (unsigned int b = 0; b < dim; ++b)
              out[dim + a * dim + b] = gradient[0][a][b];
          }
      }
    Utilities::MPI::sum(flat, model.communicator(), flat);
    if (values)
      values->assign(n_points, Tensor<1, dim>());
    if (gradients)
      gradients->assign(n_points, Tensor<2, dim>());
    for (unsigned int k = 0; k < n_points; ++k)
      {
        const double *in = &flat[k * (dim + dim * dim)];
        for (unsigned int a = 0; a < dim; ++a)
          {
            if (values)
              (*values)[k][a] = in[a];
            for (unsigned int b = 0; b < dim; ++b)
              if (gradients)
                (*gradients)[k][a][b] = in[dim + a * dim + b];
          }
      }
  }

  template class SolidPointValues<2>;
  template class SolidPointValues<3>;
} // namespace beamslider
