#include "fem/solid_statics.h"

#include "fem/mpi_interruption.h"
#include "fem/solid_point_values.h"
#include "numerics/newton.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/petsc_solver.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace beamslider
{
  using namespace dealii;

  template <int dim>
  SolidStatics<dim>::SolidStatics(const SolidModel<dim> &model)
    : model(model)
    , tangent(model.communicator())
  {}

  // One solve() as numerics/newton.h's load-stepped problem: modified
  // Newton on the kept MUMPS factorisation, with a line search on the energy.
  template <int dim>
  struct SolidStatics<dim>::LoadSteppedSolve
  {
    // Converged when the residual or the correction (relative to the
    // displacement) is this small.
    static constexpr double relative_tolerance = 1e-10, correction_tolerance = 1e-10;
    // A residual this far above the load means the increment diverges (ICE's
    // small solves peak at ~1e3 of the load, from the bent strip's membrane
    // forces before the first refresh): cut it back at once.
    static constexpr double diverged = 1e8;
    static constexpr double line_search_tolerance = 0.5, line_search_above = 1e-3;

    SolidStatics<dim> &statics;
    const SolidModel<dim> &model;
    const PETScWrappers::MPI::Vector &F, *F_start;
    PETScWrappers::MPI::Vector &u;
    const double load_norm;
    NewtonControl control;
    PETScWrappers::MPI::Vector u_ghosted, f, residual, du, u_start, load, u_trial, f_trial, r_trial;
    PETScWrappers::MPI::SparseMatrix K;
    double load_scale = 0, relative = 0;
    bool have_residual = false; // residual = load − f(u) kept from the line search

    LoadSteppedSolve(SolidStatics<dim> &statics, const PETScWrappers::MPI::Vector &F,
                     const PETScWrappers::MPI::Vector *F_start, PETScWrappers::MPI::Vector &u)
      : statics(statics)
      , model(statics.model)
      , F(F)
      , F_start(F_start)
      , u(u)
      , load_norm(std::max(F.l2_norm(), 1e-300))
    {
      // The tangent's factorisation is refreshed when the corrections stop
      // shrinking fast, or after this many iterations on it.
      control.modified                         = true;
      control.max_iterations                   = 30;
      control.max_contraction                  = 0.25;
      control.max_iterations_per_factorisation = 10;
      control.max_factorisations               = 6;
      model.reinit_ghosted_vector(u_ghosted);
      model.reinit_vector(du);
    }

    void begin_increment(const double target)
    {
      load_at_fraction(F, F_start, target, load);
      load_scale    = std::max(load.l2_norm(), 1e-300 * load_norm);
      u_start       = u;
      relative      = 0;
      have_residual = false;
    }

    NewtonOutcome solve_increment()
    {
      statics.tangent_age.stale = !statics.tangent.factorised();
      return solve_newton(*this, control, statics.tangent_age);
    }

    NewtonState evaluate(const bool refresh)
    {
      stop_if_interrupted(model.communicator()); // every rank at the same iteration
      if (refresh || !have_residual)
        {
          u_ghosted = u;
          model.assemble_internal_force(u_ghosted, &f, refresh ? &K : nullptr);
          residual = load;
          residual -= f;
        }
      relative = residual.l2_norm() / load_scale;
      // The residual of a thin strip cannot fall far below ε times the
      // stiffness ratio of its membrane and bending (~1e-4 of the load at
      // L/h = 140): converged when either it or Newton's correction
      // relative to the displacement (small()) is small.
      if (relative < relative_tolerance)
        return NewtonState::converged;
      return relative < diverged ? NewtonState::go_on : NewtonState::diverged;
    }

    void factorise() { statics.tangent.factorise(K); }

    // The residual r(u + α du) = load − f(u + α du) and its work along the
    // correction, g(α) = du·r: the line search looks for g = 0, the minimum
    // of the total potential energy along du.
    double work_along(const double alpha)
    {
      u_trial = u;
      u_trial.add(alpha, du);
      model.distribute(u_trial);
      u_ghosted = u_trial;
      model.assemble_internal_force(u_ghosted, &f_trial, nullptr);
      r_trial = load;
      r_trial -= f_trial;
      return du * r_trial;
    }

    // Line search on the energy (see the header): the full correction when
    // |g(1)| ≤ ½ g(0), else secant steps toward g = 0. Small corrections
    // (converging) take the full step: there g is at the level of round-off
    // in the strip's membrane forces. Returns α; u_trial and r_trial hold
    // u + α du and its residual, g its work.
    double line_search(const double g_0, const double du_norm, double &g)
    {
      double alpha = 1;
      g            = work_along(1.);
      if (!(g_0 > 0 && du_norm > line_search_above * u.l2_norm()))
        return alpha;
      // [a_low, a_high] brackets the root: g > 0 at a_low, g < 0 (or not
      // finite: overflow) at a_high.
      double a_low = 0, g_low = g_0, a_high = 1, g_high = g;
      for (unsigned int ls = 0; ls < 3 && !(std::abs(g) <= line_search_tolerance * g_0); ++ls)
        {
          if (g > 0) // still descending at α: accept (at α = 1 the root lies beyond the full step)
            break;
          const double width  = a_high - a_low;
          const double secant = std::isfinite(g_high) ? a_low + width * g_low / (g_low - g_high) : a_low + 0.5 * width;
          alpha               = std::clamp(secant, a_low + 0.1 * width, a_high - 0.1 * width);
          g                   = work_along(alpha);
          if (g > 0)
            a_low = alpha, g_low = g;
          else
            a_high = alpha, g_high = g;
        }
      return alpha;
    }

    double correct()
    {
      statics.tangent.solve(du, residual);
      model.constraints().set_zero(du);
      const double g_0 = du * residual, du_norm = du.l2_norm();
      double g           = 0;
      const double alpha = line_search(g_0, du_norm, g);
      u.swap(u_trial); // u + α du, distributed: an elastic end's face follows its plate
      residual.swap(r_trial);
      have_residual = std::isfinite(g);
      ++statics.linear_solves;
      return std::abs(alpha) * du_norm;
    }

    bool small(const double correction) const { return correction < correction_tolerance * u.l2_norm(); }

    void restore()
    {
      u = u_start;
      // Start the smaller increment on the tangent at its start.
      statics.tangent_age.corrections_on_matrix = control.max_iterations_per_factorisation;
    }

    [[noreturn]] void give_up(const double lambda, const NewtonOutcome &last) const
    {
      std::ostringstream msg;
      msg << "Newton's method for the solid's statics did not converge: stuck at load fraction " << lambda
          << " (next increment below " << min_step << "): the last attempt ended at relative residual " << relative
          << " after " << last.iterations << " iterations and " << last.factorisations
          << " factorisations (limits: " << control.max_iterations << " iterations, " << control.max_factorisations
          << " factorisations, residual " << diverged << "); |F| = " << load_norm << " N";
      throw SolidStaticSolveError(msg.str());
    }

    static constexpr double min_step = 1e-4;
  };

  template <int dim>
  unsigned int SolidStatics<dim>::solve(const PETScWrappers::MPI::Vector &F, PETScWrappers::MPI::Vector &u,
                                       const PETScWrappers::MPI::Vector *F_start)
  {
    ++static_solves;
    LoadSteppedSolve problem(*this, F, F_start, u);
    return solve_load_stepped(problem, LoadSteps{1., LoadSteppedSolve::min_step});
  }


  template <int dim>
  PETScWrappers::MPI::Vector SolidStatics<dim>::line_load(const double q_n_per_m) const
  {
    const auto top = model.loaded_boundary();
    if (!top)
      throw InputError("Parameter 'Solid/Loaded boundary': the solid mesh has no boundary face in that group, so the "
                       "line load has nowhere to press; name the top face's physical group");
    PETScWrappers::MPI::Vector F;
    model.reinit_vector(F);
    const auto &fe = model.get_dof_handler().get_fe();
    FEFaceValues<dim> fe_face(model.mapping(), fe, model.face_quadrature(),
                              update_values | update_normal_vectors | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    Vector<double> cell_load(n);
    std::vector<types::global_dof_index> dofs(n);
    // The pressure q/b on the top face, per unit of its area projected on
    // the x–y plane (the factor |N_z|): Q N per metre of the beam's line
    // on a flat strip and on an arch alike. Each integral carries the
    // out-of-plane factor.
    const double traction = q_n_per_m / model.width() * model.out_of_plane_thickness();
    for (const auto &cell : model.get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int face : cell->face_indices())
          if (cell->face(face)->at_boundary() && cell->face(face)->boundary_id() == *top)
            {
              fe_face.reinit(cell, face);
              cell_load = 0;
              for (const unsigned int q : fe_face.quadrature_point_indices())
                {
                  const double projected = std::abs(fe_face.normal_vector(q)[dim - 1]) * fe_face.JxW(q);
                  for (unsigned int i = 0; i < n; ++i)
                    if (fe.system_to_component_index(i).first == dim - 1)
                      cell_load(i) += traction * fe_face.shape_value(i, q) * projected;
                }
              cell->get_dof_indices(dofs);
              model.constraints().distribute_local_to_global(cell_load, dofs, F);
            }
    F.compress(VectorOperation::add);
    return F;
  }

  template <int dim>
  double SolidStatics<dim>::section_deflection(const PETScWrappers::MPI::Vector &u, const double x) const
  {
    if (!(x >= 0 && x < model.length()))
      throw std::invalid_argument("section deflection: x = " + std::to_string(x) + " m lies outside [0, " +
                                  std::to_string(model.length()) + ") m");
    return model.generated() ? section_average_on_strip(u, x) : section_average_by_points(u, x);
  }

  template <int dim>
  double SolidStatics<dim>::section_average_on_strip(const PETScWrappers::MPI::Vector &u, const double x_section) const
  {
    // The cross-section x cuts the axis-aligned cells of the strip at
    // reference coordinate ξ_0 = (x − x_0)/Δx: a quadrature on that plane
    // of the reference cell (Gauss in the other directions) integrates u_z
    // over the section, whether or not it is a mesh plane. A cell whose
    // right face is the section is skipped: its neighbour has it on its left.
    // (On the arch the cells are sheared vertically, which keeps x linear
    // in ξ_0 and the section's extent in z.)
    const auto &fe = model.get_dof_handler().get_fe();
    const QGauss<dim - 1> section(fe.degree + 1);
    double integral = 0, area = 0;
    for (const auto &cell : model.get_dof_handler().active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const double x0 = cell->vertex(0)[0], dx = cell->vertex(1)[0] - x0;
          const double xi = (x_section - x0) / dx;
          if (xi < 0 || xi >= 1)
            continue;
          std::vector<Point<dim>> points;
          std::vector<double> weights;
          for (unsigned int q = 0; q < section.size(); ++q)
            {
              Point<dim> p;
              p[0] = xi;
              for (unsigned int d = 1; d < dim; ++d)
                p[d] = section.point(q)[d - 1];
              points.push_back(p);
              weights.push_back(section.weight(q));
            }
          FEValues<dim> fe_values(model.mapping(), fe, Quadrature<dim>(points, weights), update_values);
          fe_values.reinit(cell);
          std::vector<Vector<double>> values(points.size(), Vector<double>(dim));
          fe_values.get_function_values(u, values);
          // The section's area element: the cell's extent across x.
          double cross = 1;
          for (unsigned int d = 1; d < dim; ++d)
            cross *= cell->extent_in_direction(d);
          for (unsigned int q = 0; q < points.size(); ++q)
            {
              integral += values[q][dim - 1] * weights[q] * cross;
              area += weights[q] * cross;
            }
        }
    const MPI_Comm comm = model.communicator();
    return Utilities::MPI::sum(integral, comm) / Utilities::MPI::sum(area, comm);
  }

  template <int dim>
  double SolidStatics<dim>::section_average_by_points(const PETScWrappers::MPI::Vector &u, const double x) const
  {
    // A mesh file's cells need not follow the section: u_z is sampled at
    // 8 Gauss points per direction of the nominal section
    // y ∈ [−b/2, b/2], z ∈ [−h/2, h/2] at x.
    const QGauss<dim - 1> rule(8);
    std::vector<Point<dim>> points;
    for (unsigned int q = 0; q < rule.size(); ++q)
      {
        Point<dim> p;
        p[0] = x;
        if (dim == 3)
          p[1] = (rule.point(q)[0] - 0.5) * model.width();
        p[dim - 1] = (rule.point(q)[dim - 2] - 0.5) * model.thickness();
        points.push_back(p);
      }
    std::vector<Tensor<1, dim>> values;
    SolidPointValues<dim>(model, points).evaluate(u, &values, nullptr);
    double integral = 0;
    for (unsigned int k = 0; k < points.size(); ++k)
      integral += rule.weight(k) * values[k][dim - 1];
    return integral; // the weights sum to 1
  }

  template <int dim>
  void SolidStatics<dim>::load_path(
    const PETScWrappers::MPI::Vector &F, const unsigned int n_steps,
    const std::function<void(unsigned int, double, const PETScWrappers::MPI::Vector &, unsigned int)> &on_step)
  {
    PETScWrappers::MPI::Vector u, F_k, F_previous, u_ghosted;
    model.reinit_vector(u);
    model.reinit_vector(F_previous);
    model.reinit_ghosted_vector(u_ghosted);
    for (unsigned int k = 1; k <= n_steps; ++k)
      {
        const double lambda = double(k) / n_steps;
        F_k                 = F;
        F_k *= lambda;
        const std::string step = "load step " + std::to_string(k) + " of " + std::to_string(n_steps) + ": ";
        unsigned int iterations = 0;
        try
          {
            iterations = solve(F_k, u, &F_previous);
          }
        catch (const SolidStaticSolveError &e)
          {
            throw SolidStaticSolveError(step + e.what());
          }
        F_previous = F_k;
        u_ghosted  = u;
        on_step(k, lambda, u_ghosted, iterations);
      }
  }

  template class SolidStatics<2>;
  template class SolidStatics<3>;
} // namespace beamslider
