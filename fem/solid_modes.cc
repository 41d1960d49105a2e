#include "fem/solid_modes.h"

#include "fem/petsc_session.h"
#include "fem/shift_invert_eigensolver.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <numeric>
#include <sstream>

namespace beamslider
{
  using namespace dealii;

  namespace
  {
    // ∫ ρ φ_c² dV per component, ∫ ρ φ_z y dV and ∫ ρ y² dV (3D),
    // ∫ ρ φ_z (L − x) dV (for the sign) and ∫ ρ φ_z y ∂φ_z/∂y dV (3D),
    // summed over the ranks.
    template <int dim>
    std::array<double, 7> energy_integrals(const SolidModel<dim> &model, const PETScWrappers::MPI::Vector &phi)
    {
      const auto &fe = model.get_dof_handler().get_fe();
      const Quadrature<dim> &quadrature = model.quadrature();
      FEValues<dim> fe_values(model.mapping(), fe, quadrature,
                              update_values | update_gradients | update_quadrature_points | update_JxW_values);
      const FEValuesExtractors::Vector displacement(0);
      std::vector<Tensor<1, dim>> values(quadrature.size());
      std::vector<Tensor<2, dim>> gradients(quadrature.size());
      std::array<double, 7> sums{};
      for (const auto &cell : model.get_dof_handler().active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const double rho = model.material(cell->material_id()).density;
            fe_values.reinit(cell);
            fe_values[displacement].get_function_values(phi, values);
            fe_values[displacement].get_function_gradients(phi, gradients);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                const double dm = rho * fe_values.JxW(q);
                for (unsigned int c = 0; c < dim; ++c)
                  sums[c] += dm * values[q][c] * values[q][c];
                sums[5] += dm * values[q][dim - 1] * (model.length() - fe_values.quadrature_point(q)[0]);
                if (dim == 3)
                  {
                    const double y = fe_values.quadrature_point(q)[1];
                    sums[3] += dm * values[q][dim - 1] * y;
                    sums[4] += dm * y * y;
                    sums[6] += dm * values[q][dim - 1] * y * gradients[q][dim - 1][1];
                  }
              }
          }
      std::array<double, 7> total;
      Utilities::MPI::sum(ArrayView<const double>(sums.data(), 7), model.communicator(),
                          ArrayView<double>(total.data(), 7));
      return total;
    }

    // Classifies the mode; returns ∫ ρ φ_z (L − x) dV, whose sign fixes the mode's.
    template <int dim>
    double classify(const SolidModel<dim> &model, SolidMode &mode)
    {
      const std::array<double, 7> s = energy_integrals(model, mode.vector);
      double all = 0;
      for (unsigned int c = 0; c < dim; ++c)
        all += s[c];
      mode.energy_share.fill(0.);
      for (unsigned int c = 0; c < dim; ++c)
        mode.energy_share[dim == 3 ? c : 2 * c] = s[c] / all; // 2D: x, z
      mode.twist_correlation = dim == 3 ? s[3] * s[3] / (s[dim - 1] * s[4]) : 0.;
      mode.width_order       = dim == 3 ? s[6] / s[dim - 1] : 0.;
      const auto &e          = mode.energy_share;
      if (e[0] >= e[1] && e[0] >= e[2])
        mode.shape = "axial";
      else if (e[1] >= e[2])
        mode.shape = "lateral";
      else if (mode.width_order > 1.5)
        mode.shape = "plate";
      else
        mode.shape = mode.twist_correlation > 0.5 || mode.width_order > 0.5 ? "torsion" : "bending";
      return s[5];
    }

    // The n lowest eigenpairs of K φ = ω² M φ.
    template <int dim>
    unsigned int lowest_modes(const SolidModel<dim> &model, const PETScWrappers::MPI::SparseMatrix &K,
                              const PETScWrappers::MPI::SparseMatrix &M, const unsigned int n,
                              std::vector<double> &eigenvalues, std::vector<PETScWrappers::MPI::Vector> &vectors)
    {
      vectors.resize(n);
      for (auto &v : vectors)
        model.reinit_vector(v);
      ShiftInvertSettings settings;
      // Frequencies that agree to ~1e-12 whatever the partition (1 and 2
      // ranks factorise in different orders); MUMPS for any number of ranks.
      settings.tolerance = 1e-14;
      settings.mumps     = true;
      settings.what      = "the " + std::to_string(n) + " lowest modes of the " + std::to_string(dim) + "D solid (" +
                      std::to_string(model.n_dofs()) + " DoFs)";
      return lowest_eigenpairs(K, M, n, settings, eigenvalues, vectors);
    }
  } // namespace

  template <int dim>
  SolidModes compute_solid_modes(const SolidModel<dim> &model, const unsigned int n_bending,
                                 const unsigned int n_lowest)
  {
    require_petsc();
    PETScWrappers::MPI::SparseMatrix K, M;
    PETScWrappers::MPI::Vector zero;
    model.reinit_ghosted_vector(zero);
    model.assemble_internal_force(zero, nullptr, &K);
    model.assemble_mass_matrix(M);

    SolidModes modes;
    // Torsion (3D) and, higher up, lateral and axial modes lie between the
    // bending modes: ask for twice as many plus a few, and more if short.
    auto enough = [&]() { return modes.bending.size() == n_bending && modes.all.size() >= n_lowest; };
    for (unsigned int n = std::max(2 * n_bending + 4, n_lowest);; n *= 2)
      {
        if (n > model.n_dofs() - model.constraints().n_constraints())
          throw std::runtime_error("the solid mesh has too few DoFs (" + std::to_string(model.n_dofs()) + ") for " +
                                   std::to_string(n_bending) + " bending modes and " + std::to_string(n_lowest) +
                                   " modes in all: refine it");
        std::vector<double> eigenvalues;
        std::vector<PETScWrappers::MPI::Vector> vectors;
        modes.eigensolver_iterations += lowest_modes(model, K, M, n, eigenvalues, vectors);

        std::vector<unsigned int> order(eigenvalues.size());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return eigenvalues[a] < eigenvalues[b]; });
        modes.all.clear();
        modes.bending.clear();
        PETScWrappers::MPI::Vector Mphi;
        model.reinit_vector(Mphi);
        for (const unsigned int i : order)
          {
            SolidMode mode;
            mode.omega = std::sqrt(std::max(eigenvalues[i], 0.));
            // φᵀ M φ = 1 on the free DoFs (M's constrained rows hold a
            // filler diagonal), then the constrained ones follow them.
            model.constraints().set_zero(vectors[i]);
            M.vmult(Mphi, vectors[i]);
            vectors[i] /= std::sqrt(vectors[i] * Mphi);
            model.distribute(vectors[i]);
            model.reinit_ghosted_vector(mode.vector);
            mode.vector = vectors[i];
            // The sign: ∫ ρ φ_z (L − x) dV > 0, as the beam's modes
            // (reproducible across meshes and ranks).
            if (classify(model, mode) < 0)
              {
                vectors[i] *= -1.;
                mode.vector = vectors[i];
              }
            if (mode.shape == "bending" && modes.bending.size() < n_bending)
              modes.bending.push_back(modes.all.size());
            modes.all.push_back(std::move(mode));
            if (enough())
              break;
          }
        if (enough())
          return modes;
      }
  }

  template SolidModes compute_solid_modes(const SolidModel<2> &, unsigned int, unsigned int);
  template SolidModes compute_solid_modes(const SolidModel<3> &, unsigned int, unsigned int);
} // namespace beamslider
