// A solid field at given points of the reference configuration (fem/solid_model.h):
// each point located once, in a locally owned cell of one rank (the lowest
// rank that owns a cell containing it), then the displacement and its
// gradient there for any vector of the model, known on every rank. For
// what a mesh does not describe as a cell structure: the mid-span section of
// a mesh file, the beam line along which a solid's modes are sampled.
#pragma once

#include "fem/solid_model.h"

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <vector>

namespace beamslider
{
  template <int dim>
  class SolidPointValues
  {
  public:
    // Collective. Throws InputError naming the first point no cell contains.
    SolidPointValues(const SolidModel<dim> &model, const std::vector<dealii::Point<dim>> &points);

    // u(p) and ∇u(p) (either may be null) at every point, on every rank
    // (collective); u ghosted.
    void evaluate(const dealii::PETScWrappers::MPI::Vector &u, std::vector<dealii::Tensor<1, dim>> *values,
                  std::vector<dealii::Tensor<2, dim>> *gradients) const;

  private:
    const SolidModel<dim> &model;
    unsigned int n_points;
    struct Located
    {
      unsigned int index;
      typename dealii::DoFHandler<dim>::active_cell_iterator cell;
      dealii::Point<dim> unit;
    };
    std::vector<Located> mine; // the points this rank evaluates
  };
} // namespace beamslider
