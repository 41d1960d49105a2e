// The FE beam's per-cell data (fe_transient.h): shape data cached at the
// quadrature points, the internal force and tangent from it, the Hermite
// kinematics of a point, the strain energy and the fields for pictures.
#include "fem/fe_transient.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace beamslider
{
  void FETransientBeam::collect_cells()
  {
    const FEBeam &beam = *beam_;
    for (const auto &cell : beam.get_dof_handler().active_cell_iterators())
      {
        CellData data;
        data.x0 = cell->vertex(0)[0];
        data.h  = cell->diameter();
        data.EA = beam.section(cell).axial_stiffness();
        data.EI = beam.section(cell).bending_stiffness();
        cells_.push_back(std::move(data));
      }
    std::sort(cells_.begin(), cells_.end(), [](const CellData &a, const CellData &b) { return a.x0 < b.x0; });
  }

  void FETransientBeam::cache_cell_quadrature()
  {
    // Quadrature data: the Gauss rule FEBeam::assemble_internal_force uses
    // (max(5, p + 2) points, exact for N w' N_a'), shape values from FEBeam.
    const FEBeam &beam = *beam_;
    const unsigned int degree = beam.get_dof_handler().get_fe().degree;
    const dealii::QGauss<1> gauss(std::max(5u, degree + 2));
    for (CellData &cell : cells_)
      {
        cell.first_qp = quadrature_.size();
        cell.n_qp     = gauss.size();
        for (unsigned int k = 0; k < gauss.size(); ++k)
          {
            const FEPointShape p = beam.point_shape(cell.x0 + gauss.point(k)[0] * cell.h);
            if (p.u_dofs.size() > max_axial_dofs)
              throw std::invalid_argument("FE transient: axial degree " + std::to_string(degree) +
                                          " has more than " + std::to_string(max_axial_dofs) +
                                          " axial DoFs per cell; the largest allowed degree is 6");
            if (k == 0)
              {
                cell.w_dofs = {{static_cast<unsigned int>(p.w_dofs[0]), static_cast<unsigned int>(p.w_dofs[1]),
                                static_cast<unsigned int>(p.w_dofs[2]), static_cast<unsigned int>(p.w_dofs[3])}};
                cell.n_u = p.u_dofs.size();
                for (unsigned int i = 0; i < cell.n_u; ++i)
                  cell.u_dofs[i] = p.u_dofs[i];
              }
            QuadraturePointData d;
            d.du.fill(0.);
            for (unsigned int a = 0; a < 4; ++a)
              {
                d.dN[a]  = p.slope_values[a];
                d.ddN[a] = p.curvature_values[a];
              }
            for (unsigned int i = 0; i < cell.n_u; ++i)
              d.du[i] = p.strain_values[i];
            d.JxW = gauss.weight(k) * cell.h;
            quadrature_.push_back(d);
          }
        const unsigned int n_local = 4 + cell.n_u;
        const auto global = [&](const unsigned int l) { return l < 4 ? cell.w_dofs[l] : cell.u_dofs[l - 4]; };
        cell.entry.resize(n_local * n_local);
        for (unsigned int i = 0; i < n_local; ++i)
          for (unsigned int j = 0; j < n_local; ++j)
            cell.entry[i * n_local + j] = iteration_matrix_entry(global(i), global(j));
      }
  }

  void FETransientBeam::pair_cell_quadrature()
  {
    // Cells in pairs; an odd last cell fills both lanes of its pair.
    for (std::size_t c = 0; c < cells_.size(); c += 2)
      {
        const CellData &first = cells_[c], &second = cells_[std::min(c + 1, cells_.size() - 1)];
        if (first.n_qp != second.n_qp)
          throw std::logic_error("FE transient: neighbouring cells with different quadratures");
        for (unsigned int k = 0; k < first.n_qp; ++k)
          {
            const QuadraturePointData &a = quadrature_[first.first_qp + k], &b = quadrature_[second.first_qp + k];
            QuadraturePointPair pair;
            for (unsigned int i = 0; i < 4; ++i)
              {
                pair.dN[i]  = Eigen::Array2d(a.dN[i], b.dN[i]);
                pair.ddN[i] = Eigen::Array2d(a.ddN[i], b.ddN[i]);
              }
            for (unsigned int i = 0; i < max_axial_dofs; ++i)
              pair.du[i] = Eigen::Array2d(a.du[i], b.du[i]);
            pair.JxW = Eigen::Array2d(a.JxW, b.JxW);
            paired_quadrature_.push_back(pair);
          }
      }
  }

  void FETransientBeam::set_up_support_springs()
  {
    const FEBeam &beam = *beam_;
    if (beam.support_data().elastic())
      for (unsigned int end = 0; end < 2; ++end)
        {
          const auto [u, w, theta] = beam.support_dofs(end);
          springs_.emplace_back(theta, beam.support_data().rotational_stiffness);
          springs_.emplace_back(u, beam.support_data().axial_spring_per_end());
        }
    for (const auto &[dof, k] : springs_)
      spring_entry_.push_back(iteration_matrix_entry(dof, dof));
  }

  void FETransientBeam::gather(const CellData &cell, const Eigen::VectorXd &q, std::array<double, 4> &qw,
                               std::array<double, max_axial_dofs> &qu)
  {
    for (unsigned int a = 0; a < 4; ++a)
      qw[a] = q[cell.w_dofs[a]];
    for (unsigned int i = 0; i < cell.n_u; ++i)
      qu[i] = q[cell.u_dofs[i]];
  }

  template <unsigned int n_u>
  void FETransientBeam::internal_force_cells(const Eigen::VectorXd &q, Eigen::VectorXd &f) const
  {
    // f = ∫ N δε + M δκ dx with N = EA ε, M = EI κ, δε = δu' + w' δw'
    // (doc/physics.md §2–3; FEBeam::assemble_internal_force), cell by cell,
    // the cell's DoF values gathered once. n_u, the axial DoFs per cell, is a
    // compile-time constant here so that the inner loops unroll: this runs
    // once per Newton iteration and was a fifth of the FE step.
    const bool nonlinear = beam_->geometric_nonlinearity();
    // Two cells at a time in the lanes of Eigen::Array2d (one SSE2 register):
    // each lane does one cell's operations in the order of a loop over single
    // cells, and the cells are added into f in their order, so f is the same
    // to the last bit. An odd last cell fills both lanes; one is added.
    using Pair                = Eigen::Array2d;
    const std::size_t n_cells = cells_.size(), n_pairs = (n_cells + 1) / 2;
    const unsigned int n_qp   = cells_.front().n_qp;
    for (std::size_t p = 0; p < n_pairs; ++p)
      {
        const unsigned int n_lanes = 2 * p + 1 < n_cells ? 2 : 1;
        const CellData &c0 = cells_[2 * p], &c1 = cells_[2 * p + n_lanes - 1];
        const Pair EA(c0.EA, c1.EA), EI(c0.EI, c1.EI);
        Pair qw[4], qu[n_u], fw[4], fu[n_u];
        for (unsigned int a = 0; a < 4; ++a)
          {
            qw[a] = Pair(q[c0.w_dofs[a]], q[c1.w_dofs[a]]);
            fw[a] = Pair::Zero();
          }
        for (unsigned int i = 0; i < n_u; ++i)
          {
            qu[i] = Pair(q[c0.u_dofs[i]], q[c1.u_dofs[i]]);
            fu[i] = Pair::Zero();
          }
        const QuadraturePointPair *d = &paired_quadrature_[p * n_qp];
        for (unsigned int k = 0; k < n_qp; ++k, ++d)
          {
            Pair du = Pair::Zero(), dw = Pair::Zero(), ddw = Pair::Zero();
            for (unsigned int i = 0; i < n_u; ++i)
              du += d->du[i] * qu[i];
            for (unsigned int a = 0; a < 4; ++a)
              {
                dw += d->dN[a] * qw[a];
                ddw += d->ddN[a] * qw[a];
              }
            const Pair stretch = nonlinear ? Pair(0.5 * dw * dw) : Pair(Pair::Zero());
            const Pair N       = EA * (du + stretch) * d->JxW;
            const Pair M = EI * ddw * d->JxW, Nw = nonlinear ? Pair(N * dw) : Pair(Pair::Zero());
            for (unsigned int i = 0; i < n_u; ++i)
              fu[i] += N * d->du[i];
            for (unsigned int a = 0; a < 4; ++a)
              fw[a] += Nw * d->dN[a] + M * d->ddN[a];
          }
        for (unsigned int lane = 0; lane < n_lanes; ++lane)
          {
            const CellData &cell = lane == 0 ? c0 : c1;
            for (unsigned int a = 0; a < 4; ++a)
              f[cell.w_dofs[a]] += fw[a][lane];
            for (unsigned int i = 0; i < n_u; ++i)
              f[cell.u_dofs[i]] += fu[i][lane];
          }
      }
  }

  void FETransientBeam::internal_force_cached(const Eigen::VectorXd &q, Eigen::VectorXd &f) const
  {
    f.setZero(q.size());
    // Every cell has the same axial degree p, so p + 1 axial DoFs.
    switch (cells_.front().n_u)
      {
        case 2: internal_force_cells<2>(q, f); break;
        case 3: internal_force_cells<3>(q, f); break;
        case 4: internal_force_cells<4>(q, f); break;
        case 5: internal_force_cells<5>(q, f); break;
        case 6: internal_force_cells<6>(q, f); break;
        case 7: internal_force_cells<7>(q, f); break;
        default: throw std::logic_error("FE transient: unexpected number of axial DoFs per cell");
      }
    for (const auto &[dof, k] : springs_)
      f[dof] += k * q[dof];
    for (const unsigned int i : constrained_list_)
      f[i] = 0.;
  }

  void FETransientBeam::cached_internal_force(const dealii::Vector<double> &q, dealii::Vector<double> &f) const
  {
    Eigen::VectorXd qe, fe;
    to_eigen(q, qe);
    internal_force_cached(qe, fe);
    to_dealii(fe, f);
  }

  void FETransientBeam::assemble_iteration_matrix(const Eigen::VectorXd &q_bar, const double dt)
  {
    // S₀ = M + θ²Δt² K_t(q̄) (Δt²/4 for θ = 1/2): K_t = ∂f/∂q of internal_force_cached, cell by
    // cell, with N = EA ε the membrane force:
    //   K_uu = ∫ EA u_i' u_j',   K_uw = ∫ EA w' u_i' N_b',
    //   K_ww = ∫ (EA w'² + N) N_a' N_b' + EI N_a'' N_b''.
    const bool nonlinear = beam_->geometric_nonlinearity();
    const double theta = settings_.theta;
    const double scale = theta * theta * dt * dt;
    double *values = S0_.valuePtr();
    Eigen::Map<Eigen::VectorXd>(values, S0_.nonZeros()) = M_in_S0_;
    for (const CellData &cell : cells_)
      {
        const double EA = cell.EA, EI = cell.EI;
        const unsigned int n_local = 4 + cell.n_u;
        std::array<double, max_cell_dofs * max_cell_dofs> K{};
        std::array<double, 4> qw;
        std::array<double, max_axial_dofs> qu;
        gather(cell, q_bar, qw, qu);
        for (unsigned int k = 0; k < cell.n_qp; ++k)
          {
            const QuadraturePointData &d = quadrature_[cell.first_qp + k];
            double du = 0, dw = 0;
            for (unsigned int i = 0; i < cell.n_u; ++i)
              du += d.du[i] * qu[i];
            for (unsigned int a = 0; a < 4; ++a)
              dw += d.dN[a] * qw[a];
            const double coupling = nonlinear ? dw : 0.;
            const double N        = nonlinear ? EA * (du + 0.5 * dw * dw) : 0.;
            for (unsigned int a = 0; a < 4; ++a)
              for (unsigned int b = 0; b < 4; ++b)
                K[a * n_local + b] +=
                  ((EA * coupling * coupling + N) * d.dN[a] * d.dN[b] + EI * d.ddN[a] * d.ddN[b]) * d.JxW;
            for (unsigned int i = 0; i < cell.n_u; ++i)
              {
                for (unsigned int j = 0; j < cell.n_u; ++j)
                  K[(4 + i) * n_local + 4 + j] += EA * d.du[i] * d.du[j] * d.JxW;
                for (unsigned int b = 0; b < 4; ++b)
                  {
                    const double kib = EA * coupling * d.du[i] * d.dN[b] * d.JxW;
                    K[(4 + i) * n_local + b] += kib;
                    K[b * n_local + 4 + i] += kib;
                  }
              }
          }
        for (unsigned int l = 0; l < n_local * n_local; ++l)
          if (cell.entry[l] >= 0)
            values[cell.entry[l]] += scale * K[l];
      }
    for (std::size_t s = 0; s < springs_.size(); ++s)
      if (spring_entry_[s] >= 0)
        values[spring_entry_[s]] += scale * springs_[s].second;
  }

  Eigen::MatrixXd FETransientBeam::cached_iteration_matrix(const Eigen::VectorXd &q_bar, const double dt)
  {
    assemble_iteration_matrix(q_bar, dt);
    // (The factorisation is a copy of its own: unchanged.)
    const Eigen::MatrixXd upper(S0_);
    return upper.selfadjointView<Eigen::Upper>();
  }

  void FETransientBeam::to_dealii(const Eigen::VectorXd &a, dealii::Vector<double> &b)
  {
    if (b.size() != static_cast<unsigned int>(a.size()))
      b.reinit(a.size());
    std::copy(a.data(), a.data() + a.size(), b.begin());
  }

  void FETransientBeam::to_eigen(const dealii::Vector<double> &a, Eigen::VectorXd &b)
  {
    b.resize(a.size());
    std::copy(a.begin(), a.end(), b.data());
  }

  const FETransientBeam::CellData &FETransientBeam::cell_at(const double x, double &xi) const
  {
    const double L = length();
    if (!(x >= 0. && x <= L))
      {
        std::ostringstream m;
        m << "FE beam evaluated at x = " << x << " m, outside the beam [0, " << L << "] m";
        throw std::out_of_range(m.str());
      }
    // The cell whose left vertex is the last one at or before x.
    const auto it = std::upper_bound(cells_.begin(), cells_.end(), x,
                                     [](const double x, const CellData &c) { return x < c.x0; });
    const CellData &cell = it == cells_.begin() ? *it : *std::prev(it);
    xi                   = std::clamp((x - cell.x0) * (1. / cell.h), 0., 1.);
    return cell;
  }

  void FETransientBeam::evaluate(const double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const
  {
    // The Hermite shape functions of the cell under x (the same numbers as
    // FEBeam::point_shape, without its axial part and its allocations).
    LocalPointKinematics local;
    evaluate_local(x, q, local);
    const unsigned int n = n_dofs();
    out.grad_w.setZero(n);
    out.grad_dw.setZero(n);
    for (unsigned int a = 0; a < local.n; ++a)
      {
        out.grad_w[local.index[a]] += local.grad_w[a];
        out.grad_dw[local.index[a]] += local.grad_dw[a];
      }
    out.w  = local.w;
    out.dw = local.dw;
  }

  void FETransientBeam::evaluate_local(const double x, const Eigen::VectorXd &q, LocalPointKinematics &out) const
  {
    double xi            = 0;
    const CellData &cell = cell_at(x, xi);
    std::array<double, 4> N, dN;
    hermite_shape(xi, cell.h, 1. / cell.h, N, dN);
    out.n = 0;
    out.w = out.dw = 0.;
    for (unsigned int a = 0; a < 4; ++a)
      {
        const auto dof = cell.w_dofs[a];
        if (constrained_[dof])
          continue;
        out.index[out.n]   = dof;
        out.grad_w[out.n]  = N[a];
        out.grad_dw[out.n] = dN[a];
        out.w += N[a] * q[dof];
        out.dw += dN[a] * q[dof];
        ++out.n;
      }
  }

  void FETransientBeam::evaluate_displacement(const double x, const Eigen::VectorXd &q, double &w, double &dw) const
  {
    LocalPointKinematics local;
    evaluate_local(x, q, local);
    w  = local.w;
    dw = local.dw;
  }

  Eigen::VectorXd FETransientBeam::internal_force(const Eigen::VectorXd &q) const
  {
    dealii::Vector<double> qd, f;
    to_dealii(q, qd);
    beam_->assemble_internal_force(qd, &f, nullptr, beam_->constraints());
    Eigen::VectorXd out;
    to_eigen(f, out);
    return out;
  }

  double FETransientBeam::strain_energy(const Eigen::VectorXd &q) const
  {
    // V(q) = ∫₀¹ f(s q)·q ds; f(s q)·q is a cubic in s (von Kármán), so
    // two-point Gauss–Legendre on [0, 1] is exact.
    // The forces from the cached quadrature data into scratch (this runs at
    // every period's end for the energy balance: FEBeam's FEValues assembly
    // allocated there).
    const double g = 0.5 / std::sqrt(3.);
    double V       = 0;
    for (const double s : {0.5 - g, 0.5 + g})
      {
        energy_q_ = s * q;
        internal_force_cached(energy_q_, energy_f_);
        V += 0.5 * energy_f_.dot(q);
      }
    return V;
  }

  BeamFieldSamples FETransientBeam::sample_fields(const Eigen::VectorXd &q) const
  {
    BeamFieldSamples g;
    const FEBeam &beam = *beam_;
    // Four samples per element, so that every element boundary (where a
    // mesh beam's section may change) is a sample.
    const unsigned int samples_per_element = 4;
    std::vector<double> xs;
    for (const CellData &cell : cells_)
      for (unsigned int k = 0; k < samples_per_element; ++k)
        xs.push_back(cell.x0 + cell.h * k / samples_per_element);
    xs.push_back(beam.length());
    for (const double x : xs)
      {
        const double EA      = beam.section_at(x).axial_stiffness();
        const FEPointShape p = beam.point_shape(x);
        double u = 0, du = 0, w = 0, dw = 0, ddw = 0;
        for (unsigned int a = 0; a < 4; ++a)
          {
            const double qa = q[p.w_dofs[a]];
            w += p.w_values[a] * qa;
            dw += p.slope_values[a] * qa;
            ddw += p.curvature_values[a] * qa;
          }
        for (unsigned int k = 0; k < p.u_dofs.size(); ++k)
          {
            u += p.u_values[k] * q[p.u_dofs[k]];
            du += p.strain_values[k] * q[p.u_dofs[k]];
          }
        g.x.push_back(x);
        g.u.push_back(u);
        g.w.push_back(w);
        g.dw.push_back(dw);
        g.curvature.push_back(ddw);
        g.axial_force.push_back(EA * (du + (beam.geometric_nonlinearity() ? 0.5 * dw * dw : 0.)));
      }
    return g;
  }
} // namespace beamslider
