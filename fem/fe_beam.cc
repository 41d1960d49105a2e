// Assembly of the von Kármán beam: see fe_beam.h for the model and the
// discretisation.
#include "fem/fe_beam.h"

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace beamslider
{
  using namespace dealii;

  FEBeam::FEBeam(const Scene &scene, const unsigned int n_elements)
    : beam(scene.beam)
    , supports(scene.supports)
    , nonlinear(scene.discretisation.geometric_nonlinearity)
    , fe(FE_Q<1>(scene.discretisation.axial_degree), 1, FE_Q<1>(1), 2)
    , dof_handler(triangulation)
  {
    make_grid_and_dofs(n_elements > 0 ? n_elements : scene.discretisation.n_elements);
    make_constraints();
  }

  void FEBeam::make_grid_and_dofs(const unsigned int n_elements)
  {
    if (!beam.from_mesh())
      {
        sections = {beam.uniform_section()};
        GridGenerator::subdivided_hyper_cube(triangulation, n_elements, 0., beam.length);
      }
    else
      {
        // The mesh's elements, each split into equal parts, with the index
        // of its section as material id.
        const auto n_mesh = static_cast<unsigned int>(beam.mesh_cells.size());
        if (n_elements % n_mesh != 0)
          throw std::invalid_argument("FE beam: " + std::to_string(n_elements) +
                                      " elements requested on a mesh of " + std::to_string(n_mesh) +
                                      " elements; a mesh beam takes a whole multiple of its mesh's elements");
        const unsigned int parts = n_elements / n_mesh;
        std::map<unsigned int, types::material_id> index_of_tag;
        for (const auto &[tag, section] : beam.sections)
          {
            index_of_tag[tag] = sections.size();
            sections.push_back(section);
          }
        std::vector<Point<1>> vertices{Point<1>(0.)};
        std::vector<CellData<1>> cells;
        for (const BeamMeshCell &c : beam.mesh_cells)
          for (unsigned int k = 0; k < parts; ++k)
            {
              vertices.emplace_back(k + 1 == parts ? c.x_end : c.x_begin + (c.x_end - c.x_begin) * (k + 1) / parts);
              CellData<1> cell;
              cell.vertices    = {static_cast<unsigned int>(vertices.size() - 2),
                                  static_cast<unsigned int>(vertices.size() - 1)};
              cell.material_id = index_of_tag.at(c.tag);
              cells.push_back(cell);
            }
        triangulation.create_triangulation(vertices, cells, SubCellData());
      }
    dof_handler.distribute_dofs(fe);

    // Identify, once, which local DoF plays which role. For the FE_Q(1) bases
    // the index within the base element is the vertex number (0 = left).
    axial_local.clear();
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      {
        const auto [component, index] = fe.system_to_component_index(i);
        if (component == 0)
          axial_local.push_back(i);
        else if (component == 1)
          hermite_local[2 * index] = i; // w at vertex `index`
        else
          hermite_local[2 * index + 1] = i; // θ at vertex `index`
      }

    for (const auto &cell : dof_handler.active_cell_iterators())
      ordered_cells.push_back(cell);
    std::sort(ordered_cells.begin(), ordered_cells.end(),
              [](const auto &a, const auto &b) { return a->vertex(0)[0] < b->vertex(0)[0]; });

    is_axial.assign(n_dofs(), false);
    is_deflection.assign(n_dofs(), false);
    is_slope.assign(n_dofs(), false);
    std::vector<global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : ordered_cells)
      {
        Assert(cell->vertex(0)[0] < cell->vertex(1)[0], ExcInternalError());
        cell->get_dof_indices(dofs);
        for (const unsigned int i : axial_local)
          is_axial[dofs[i]] = true;
        for (unsigned int v = 0; v < 2; ++v)
          {
            is_deflection[dofs[hermite_local[2 * v]]] = true;
            is_slope[dofs[hermite_local[2 * v + 1]]]  = true;
          }
      }

    // The support DoFs: vertex 0 of the first cell, vertex 1 of the last.
    for (unsigned int end = 0; end < 2; ++end)
      {
        const auto &cell = end == 0 ? ordered_cells.front() : ordered_cells.back();
        cell->get_dof_indices(dofs);
        global_dof_index u_dof = 0;
        for (const unsigned int i : axial_local)
          if (fe.system_to_component_index(i).second == end)
            u_dof = dofs[i];
        end_dofs[end] = {{u_dof, dofs[hermite_local[2 * end]], dofs[hermite_local[2 * end + 1]]}};
      }

    DynamicSparsityPattern dsp(n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, dsp);
    sparsity.copy_from(dsp);
  }

  void FEBeam::make_constraints()
  {
    support_constraints.clear();
    for (unsigned int end = 0; end < 2; ++end)
      {
        const auto [u, w, theta] = end_dofs[end];
        support_constraints.add_line(w);
        if (supports.pinned_end[end])
          support_constraints.add_line(u); // immovable hinge: w' free
        else if (supports.ideal_clamp)
          {
            support_constraints.add_line(theta);
            support_constraints.add_line(u);
          }
      }
    support_constraints.close();

    bending_only_constraints.clear();
    bending_only_constraints.merge(support_constraints);
    for (global_dof_index i = 0; i < n_dofs(); ++i)
      if (is_axial[i] && !bending_only_constraints.is_constrained(i))
        bending_only_constraints.add_line(i);
    bending_only_constraints.close();
  }

  void FEBeam::assemble_mass_matrix(SparseMatrix<double> &M, const AffineConstraints<double> &c) const
  {
    M.reinit(sparsity);
    const QGauss<1> quadrature(std::max(3u, fe.degree + 1));
    FEValues<1> fe_values(fe, quadrature, update_values | update_quadrature_points | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_M(n, n);
    std::vector<global_dof_index> dofs(n);
    std::array<double, 4> N, dN, ddN;

    for (const auto &cell : ordered_cells)
      {
        const double rhoA = section(cell).mass_per_length();
        fe_values.reinit(cell);
        cell_M           = 0;
        const double h   = cell->diameter();
        const double x_0 = cell->vertex(0)[0];
        for (const unsigned int q : fe_values.quadrature_point_indices())
          {
            const double JxW = fe_values.JxW(q);
            for (const unsigned int i : axial_local)
              for (const unsigned int j : axial_local)
                cell_M(i, j) += rhoA * fe_values.shape_value_component(i, q, 0) *
                                fe_values.shape_value_component(j, q, 0) * JxW;
            hermite_shape((fe_values.quadrature_point(q)[0] - x_0) / h, h, N, dN, ddN);
            for (unsigned int a = 0; a < 4; ++a)
              for (unsigned int b = 0; b < 4; ++b)
                cell_M(hermite_local[a], hermite_local[b]) += rhoA * N[a] * N[b] * JxW;
          }
        cell->get_dof_indices(dofs);
        c.distribute_local_to_global(cell_M, dofs, M);
      }

    // Point bodies: m N_a N_b on w and J N_a' N_b' on w' at their position
    // (rows of support DoFs keep the diagonal the constraints put there).
    for (const PointMass &body : beam.point_masses)
      add_point_inertia(body.position, body.mass, body.rotary_inertia, M);
  }

  void FEBeam::assemble_internal_force(const Vector<double> &q, Vector<double> *f, SparseMatrix<double> *K_t,
                                       const AffineConstraints<double> &c) const
  {
    if (f)
      f->reinit(n_dofs());
    if (K_t)
      K_t->reinit(sparsity);

    // Degree of the integrand N w' N_a' with N = EA(u' + ½w'²): 4 + 2 + 2 = 8
    // for the cubic w; Gauss with 5 points integrates degree 9 exactly.
    const QGauss<1> quadrature(std::max(5u, fe.degree + 2));
    FEValues<1> fe_values(fe, quadrature, update_gradients | update_quadrature_points | update_JxW_values);
    const unsigned int n = fe.n_dofs_per_cell();
    FullMatrix<double> cell_K(n, n);
    Vector<double> cell_f(n);
    std::vector<global_dof_index> dofs(n);
    std::vector<double> q_local(n);
    std::array<double, 4> N, dN, ddN;

    for (const auto &cell : ordered_cells)
      {
        const double EA = section(cell).axial_stiffness(), EI = section(cell).bending_stiffness();
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < n; ++i)
          q_local[i] = q[dofs[i]];
        cell_K           = 0;
        cell_f           = 0;
        const double h   = cell->diameter();
        const double x_0 = cell->vertex(0)[0];

        for (const unsigned int qp : fe_values.quadrature_point_indices())
          {
            const double JxW = fe_values.JxW(qp);
            hermite_shape((fe_values.quadrature_point(qp)[0] - x_0) / h, h, N, dN, ddN);
            double du = 0, dw = 0, ddw = 0;
            for (const unsigned int i : axial_local)
              du += q_local[i] * fe_values.shape_grad_component(i, qp, 0)[0];
            for (unsigned int a = 0; a < 4; ++a)
              {
                dw += q_local[hermite_local[a]] * dN[a];
                ddw += q_local[hermite_local[a]] * ddN[a];
              }
            // Membrane strain and force, bending moment.
            const double strain = du + (nonlinear ? 0.5 * dw * dw : 0.);
            const double normal_force = EA * strain;
            const double moment       = EI * ddw;
            // δε = δu' + w' δw' (the second term only with the nonlinearity).
            const double coupling = nonlinear ? dw : 0.;

            for (const unsigned int i : axial_local)
              {
                const double gi = fe_values.shape_grad_component(i, qp, 0)[0];
                cell_f(i) += normal_force * gi * JxW;
                if (K_t)
                  {
                    for (const unsigned int j : axial_local)
                      cell_K(i, j) += EA * gi * fe_values.shape_grad_component(j, qp, 0)[0] * JxW;
                    for (unsigned int b = 0; b < 4; ++b)
                      {
                        const double k = EA * gi * coupling * dN[b] * JxW;
                        cell_K(i, hermite_local[b]) += k;
                        cell_K(hermite_local[b], i) += k;
                      }
                  }
              }
            for (unsigned int a = 0; a < 4; ++a)
              {
                cell_f(hermite_local[a]) += (normal_force * coupling * dN[a] + moment * ddN[a]) * JxW;
                if (K_t)
                  for (unsigned int b = 0; b < 4; ++b)
                    cell_K(hermite_local[a], hermite_local[b]) +=
                      (EA * coupling * coupling * dN[a] * dN[b] + (nonlinear ? normal_force : 0.) * dN[a] * dN[b] +
                       EI * ddN[a] * ddN[b]) *
                      JxW;
              }
          }
        if (f && K_t)
          c.distribute_local_to_global(cell_K, cell_f, dofs, *K_t, *f);
        else if (f)
          c.distribute_local_to_global(cell_f, dofs, *f);
        else
          c.distribute_local_to_global(cell_K, dofs, *K_t);
      }

    // Support springs: ½ k_r θ² and ½ (2 k_t) u² at both ends, so that the two
    // axial springs in series are the clamping's total k_t (the clamp has
    // constrained these DoFs instead).
    if (supports.elastic())
      for (unsigned int end = 0; end < 2; ++end)
        {
          const auto [u, w, theta] = end_dofs[end];
          for (const auto &[dof, k] : {std::pair{theta, supports.rotational_stiffness}, std::pair{u, supports.axial_spring_per_end()}})
            if (!c.is_constrained(dof))
              {
                if (f)
                  (*f)[dof] += k * q[dof];
                if (K_t)
                  K_t->add(dof, dof, k);
              }
        }
  }

  void FEBeam::add_distributed_load(const std::function<double(const BeamSection &)> &load, Vector<double> &r) const
  {
    const QGauss<1> quadrature(3); // exact for the cubic Hermite functions times a constant load
    FEValues<1> fe_values(fe, quadrature, update_quadrature_points | update_JxW_values);
    std::vector<global_dof_index> dofs(fe.n_dofs_per_cell());
    std::array<double, 4> N, dN, ddN;
    for (const auto &cell : ordered_cells)
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        const double h = cell->diameter(), x_0 = cell->vertex(0)[0], q = load(section(cell));
        for (const unsigned int qp : fe_values.quadrature_point_indices())
          {
            hermite_shape((fe_values.quadrature_point(qp)[0] - x_0) / h, h, N, dN, ddN);
            for (unsigned int a = 0; a < 4; ++a)
              r[dofs[hermite_local[a]]] += q * N[a] * fe_values.JxW(qp);
          }
      }
  }

  void FEBeam::assemble_base_load(Vector<double> &r) const
  {
    r.reinit(n_dofs());
    add_distributed_load([](const BeamSection &s) { return -s.mass_per_length(); }, r);
    for (const PointMass &body : beam.point_masses)
      {
        const FEPointShape s = point_shape(body.position);
        for (unsigned int a = 0; a < 4; ++a)
          r[s.w_dofs[a]] -= body.mass * s.w_values[a];
      }
    support_constraints.set_zero(r);
  }

  void FEBeam::assemble_line_load(const double q_n_per_m, Vector<double> &F) const
  {
    F.reinit(n_dofs());
    add_distributed_load([q_n_per_m](const BeamSection &) { return q_n_per_m; }, F);
    support_constraints.set_zero(F);
  }

  FEPointShape FEBeam::point_shape(const double x) const
  {
    const auto cell = cell_at(x);
    const double h  = cell->diameter();
    const double xi = std::clamp((x - cell->vertex(0)[0]) / h, 0., 1.);

    std::vector<global_dof_index> dofs(fe.n_dofs_per_cell());
    cell->get_dof_indices(dofs);
    FEPointShape s;
    hermite_shape(xi, h, s.w_values, s.slope_values, s.curvature_values);
    for (unsigned int a = 0; a < 4; ++a)
      s.w_dofs[a] = dofs[hermite_local[a]];
    // The axial shape functions at ξ on the unit cell (FE_Q is defined there).
    const Point<1> p(xi);
    for (const unsigned int i : axial_local)
      {
        s.u_dofs.push_back(dofs[i]);
        s.u_values.push_back(fe.shape_value_component(i, p, 0));
        s.strain_values.push_back(fe.shape_grad_component(i, p, 0)[0] / h);
      }
    return s;
  }

  typename DoFHandler<1>::active_cell_iterator FEBeam::cell_at(const double x) const
  {
    const double tol = 1e-12 * beam.length;
    AssertThrow(x >= -tol && x <= beam.length + tol,
                ExcMessage("FE beam evaluated at x = " + std::to_string(x) + " m, outside the beam [0, " +
                           std::to_string(beam.length) + "] m"));
    // The cell whose left vertex is the last one at or before x.
    auto it = std::upper_bound(ordered_cells.begin(), ordered_cells.end(), x,
                               [](const double x, const auto &cell) { return x < cell->vertex(0)[0]; });
    return *(it == ordered_cells.begin() ? it : std::prev(it));
  }

  namespace
  {
    // Σ_a values[a] q[dofs[a]] over the four Hermite DoFs of a point.
    double hermite_sum(const std::array<double, 4> &values, const FEPointShape &s, const Vector<double> &q)
    {
      double sum = 0;
      for (unsigned int a = 0; a < 4; ++a)
        sum += values[a] * q[s.w_dofs[a]];
      return sum;
    }
  } // namespace

  double FEBeam::deflection(const Vector<double> &q, const double x) const
  {
    const FEPointShape s = point_shape(x);
    return hermite_sum(s.w_values, s, q);
  }

  double FEBeam::slope(const Vector<double> &q, const double x) const
  {
    const FEPointShape s = point_shape(x);
    return hermite_sum(s.slope_values, s, q);
  }

  void FEBeam::add_point_inertia(const double x, const double m, const double J, SparseMatrix<double> &M) const
  {
    const FEPointShape s = point_shape(x);
    for (unsigned int a = 0; a < 4; ++a)
      for (unsigned int b = 0; b < 4; ++b)
        {
          const auto i = s.w_dofs[a], j = s.w_dofs[b];
          if (support_constraints.is_constrained(i) || support_constraints.is_constrained(j))
            continue;
          M.add(i, j, m * s.w_values[a] * s.w_values[b] + J * s.slope_values[a] * s.slope_values[b]);
        }
  }
} // namespace beamslider
