#include "fem/solid_model.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <stdexcept>

namespace beamslider
{
  using namespace dealii;

  namespace
  {
    // The generated strip; colorize gives the faces x = 0 and x = L the
    // boundary ids 0 and 1.
    template <int dim>
    void make_strip(Triangulation<dim> &tria, const BeamData &beam, const SolidData &solid)
    {
      std::vector<unsigned int> cells{solid.elements_along_length};
      Point<dim> lower, upper;
      lower[0] = 0;
      upper[0] = beam.length;
      if (dim == 3)
        {
          cells.push_back(solid.elements_across_width);
          lower[1] = -0.5 * beam.width;
          upper[1] = 0.5 * beam.width;
        }
      cells.push_back(solid.elements_through_thickness);
      lower[dim - 1] = -0.5 * beam.thickness;
      upper[dim - 1] = 0.5 * beam.thickness;
      GridGenerator::subdivided_hyper_rectangle(tria, cells, lower, upper, true);
    }
  } // namespace

  template <int dim>
  SolidModel<dim>::SolidModel(const Scene &scene, MPI_Comm communicator)
    : mpi_communicator(communicator)
    , beam(scene.beam)
    , triangulation(communicator)
    , fe(FE_Q<dim>(scene.solid.degree), dim)
    , dof_handler(triangulation)
  {
    if (!scene.solid.enabled() || scene.solid.dimension() != dim)
      throw std::invalid_argument("SolidModel<" + std::to_string(dim) + ">: the scene's Solid/Continuum is '" +
                                  scene.solid.continuum + "'");
    const double E = beam.youngs_modulus, nu = scene.solid.poissons_ratio;
    mu     = E / (2 * (1 + nu));
    lambda = dim == 2 ? E * nu / (1 - nu * nu) : E * nu / ((1 + nu) * (1 - 2 * nu));

    make_strip(triangulation, beam, scene.solid);
    dof_handler.distribute_dofs(fe);
    owned_dofs = dof_handler.locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant_dofs);

    clamp_constraints.reinit(relevant_dofs);
    DoFTools::make_hanging_node_constraints(dof_handler, clamp_constraints);
    for (const types::boundary_id face : {types::boundary_id(0), types::boundary_id(1)})
      VectorTools::interpolate_boundary_values(dof_handler, face, Functions::ZeroFunction<dim>(dim), clamp_constraints);
    clamp_constraints.close();

    sparsity.reinit(relevant_dofs.size(), relevant_dofs.size(), relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, sparsity, clamp_constraints, false);
    SparsityTools::distribute_sparsity_pattern(sparsity, owned_dofs, mpi_communicator, relevant_dofs);
  }

  template <int dim>
  void SolidModel<dim>::reinit_matrix(PETScWrappers::MPI::SparseMatrix &A) const
  {
    A.reinit(owned_dofs, owned_dofs, sparsity, mpi_communicator);
  }

  template <int dim>
  void SolidModel<dim>::reinit_vector(PETScWrappers::MPI::Vector &v) const
  {
    v.reinit(owned_dofs, mpi_communicator);
  }

  template <int dim>
  void SolidModel<dim>::reinit_ghosted_vector(PETScWrappers::MPI::Vector &v) const
  {
    v.reinit(owned_dofs, relevant_dofs, mpi_communicator);
  }

  template <int dim>
  void SolidModel<dim>::assemble_mass_matrix(PETScWrappers::MPI::SparseMatrix &M) const
  {
    reinit_matrix(M);
    const QGauss<dim> quadrature(fe.degree + 1);
    FEValues<dim> fe_values(fe, quadrature, update_values | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n, n);
    std::vector<types::global_dof_index> dofs(n);
    const double rho = beam.density * out_of_plane_thickness();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n; ++i)
              {
                const unsigned int ci = fe.system_to_component_index(i).first;
                for (unsigned int j = 0; j < n; ++j)
                  if (fe.system_to_component_index(j).first == ci)
                    cell_matrix(i, j) += rho * fe_values.shape_value(i, q) * fe_values.shape_value(j, q) * fe_values.JxW(q);
              }
          cell->get_dof_indices(dofs);
          clamp_constraints.distribute_local_to_global(cell_matrix, dofs, M);
        }
    M.compress(VectorOperation::add);
  }

  template <int dim>
  void SolidModel<dim>::assemble_internal_force(const PETScWrappers::MPI::Vector &u, PETScWrappers::MPI::Vector *f,
                                                PETScWrappers::MPI::SparseMatrix *K_t) const
  {
    if (f)
      {
        reinit_vector(*f);
        *f = 0;
      }
    if (K_t)
      reinit_matrix(*K_t);

    const QGauss<dim> quadrature(fe.degree + 1);
    FEValues<dim> fe_values(fe, quadrature, update_gradients | update_JxW_values);
    const FEValuesExtractors::Vector displacement(0);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_matrix(n, n);
    Vector<double> cell_force(n);
    std::vector<types::global_dof_index> dofs(n);
    std::vector<Tensor<2, dim>> grad_u(quadrature.size());
    // A shape function φ_i of the vector FE_Q is e_c ⊗ N_i in one component
    // c = c_i, so ∇φ_i = e_c ⊗ ∇N_i: per i we keep c_i and g_i = ∇N_i, and
    // δE_i = sym(Fᵀ∇φ_i) = sym((Fᵀ e_c) ⊗ g_i), ∇φ_iᵀ∇φ_j = δ_{c_i c_j} g_i ⊗ g_j.
    std::vector<unsigned int> component(n);
    for (unsigned int i = 0; i < n; ++i)
      component[i] = fe.system_to_component_index(i).first;
    std::vector<Tensor<1, dim>> g(n), Sg(n);
    std::vector<Tensor<2, dim>> dE(n);
    std::vector<double> trace_dE(n);
    const Tensor<2, dim> I = unit_symmetric_tensor<dim>();
    const double factor    = out_of_plane_thickness();

    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacement].get_function_gradients(u, grad_u);
          cell_matrix = 0;
          cell_force  = 0;
          for (const unsigned int q : fe_values.quadrature_point_indices())
            {
              const Tensor<2, dim> F  = I + grad_u[q];
              const Tensor<2, dim> E  = 0.5 * (transpose(F) * F - I);
              const Tensor<2, dim> S  = lambda * trace(E) * I + 2 * mu * E;
              const double JxW        = fe_values.JxW(q) * factor;
              for (unsigned int i = 0; i < n; ++i)
                {
                  g[i] = fe_values.shape_grad_component(i, q, component[i]);
                  Tensor<1, dim> F_row; // Fᵀ e_c: row c of F
                  for (unsigned int a = 0; a < dim; ++a)
                    F_row[a] = F[component[i]][a];
                  const Tensor<2, dim> FtG = outer_product(F_row, g[i]);
                  dE[i]                    = 0.5 * (FtG + transpose(FtG));
                  trace_dE[i]              = trace(dE[i]);
                  Sg[i]                    = S * g[i];
                  cell_force(i) += scalar_product(S, dE[i]) * JxW;
                }
              if (K_t)
                for (unsigned int i = 0; i < n; ++i)
                  for (unsigned int j = 0; j < n; ++j)
                    {
                      // δE_i : C : δE_j + S : (∇φ_iᵀ ∇φ_j)
                      double k_ij = lambda * trace_dE[i] * trace_dE[j] + 2 * mu * scalar_product(dE[i], dE[j]);
                      if (component[i] == component[j])
                        k_ij += g[i] * Sg[j];
                      cell_matrix(i, j) += k_ij * JxW;
                    }
            }
          cell->get_dof_indices(dofs);
          if (f && K_t)
            clamp_constraints.distribute_local_to_global(cell_matrix, cell_force, dofs, *K_t, *f);
          else if (f)
            clamp_constraints.distribute_local_to_global(cell_force, dofs, *f);
          else
            clamp_constraints.distribute_local_to_global(cell_matrix, dofs, *K_t);
        }
    if (f)
      f->compress(VectorOperation::add);
    if (K_t)
      K_t->compress(VectorOperation::add);
  }

  template class SolidModel<2>;
  template class SolidModel<3>;
} // namespace beamslider
