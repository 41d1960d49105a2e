// The FE beam as a BeamSystem: implicit midpoint (Moreau–Jean θ = 1/2), see fe_transient.h.
#include "fem/fe_transient.h"

#include "numerics/state_bytes.h"
#include "numerics/newton.h"

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string newton_failure_message(const double t_M, const unsigned int iteration, const double correction,
                                       const double velocity_norm)
    {
      std::ostringstream m;
      m << "FE transient: Newton on the von Karman forces did not converge in the step with midpoint t = " << t_M
        << " s: after " << iteration << " iterations the velocity correction is " << correction
        << " m/s (|u| = " << velocity_norm
        << " m/s); try a smaller time step or check the state for a blow-up; the step is not accepted";
      return m.str();
    }
  } // namespace

  TransientNewtonFailure::TransientNewtonFailure(const double t_M_, const unsigned int iteration_,
                                                 const double correction_, const double velocity_norm)
    : std::runtime_error(newton_failure_message(t_M_, iteration_, correction_, velocity_norm))
    , t_M(t_M_)
    , iteration(iteration_)
    , correction(correction_)
  {}

  FETransientBeam::FETransientBeam(const Scene &scene, const BaseExcitation &excitation,
                                   const unsigned int n_elements, const FETransientSettings settings)
    : beam_(std::make_unique<FEBeam>(scene, n_elements))
    , excitation_(excitation)
    , settings_(settings)
    , damping_ratio_(scene.damping_ratio)
  {
    if (!(settings_.theta >= 0.5 && settings_.theta <= 1.))
      throw std::invalid_argument("FE transient: theta = " + std::to_string(settings_.theta) +
                                  " of the Moreau-Jean scheme is outside the allowed range [0.5, 1] (0.5: the "
                                  "midpoint rule, no numerical damping; above: the unresolved modes are damped)");
    if (settings_.impulses_through_mass && settings_.redistributed_mass)
      throw std::invalid_argument("FE transient: impulses through the mass and a redistributed mass exclude each "
                                  "other (Time stepping/FE impulses is one of step, mass, redistributed)");
    find_support_constraints();
    assemble_mass_and_base_load();
    set_up_modal_damping(settings.damped_modes ? settings.damped_modes : scene.discretisation.n_modes);
    set_up_iteration_matrix_pattern();
    collect_cells();
    cache_cell_quadrature();
    pair_cell_quadrature();
    set_up_support_springs();
    if (settings_.impulses_through_mass || settings_.redistributed_mass)
      set_up_inverse_mass();
    if (settings_.redistributed_mass)
      set_up_redistribution();

    const unsigned int n = beam_->n_dofs();
    for (auto *v : {&q_bar_, &u_, &res_, &du_, &f_, &tmp_, &u_mean_, &u_theta_, &q_end_, &f_end_, &energy_q_, &energy_f_, &energy_Mu_})
      v->setZero(n);
  }

  void FETransientBeam::find_support_constraints()
  {
    const unsigned int n = beam_->n_dofs();
    const auto &c        = beam_->constraints();

    // The supports are homogeneous single-DoF constraints (w = 0, and θ = u =
    // 0 for the clamp): keeping those DoFs at zero is all they ask.
    constrained_.assign(n, false);
    for (unsigned int i = 0; i < n; ++i)
      if (c.is_constrained(i))
        {
          const auto *entries = c.get_constraint_entries(i);
          if (c.is_inhomogeneously_constrained(i) || (entries && !entries->empty()))
            throw std::logic_error("FE transient: support constraint on DoF " + std::to_string(i) +
                                   " is not of the form q_i = 0");
          constrained_[i] = true;
        }

    for (unsigned int i = 0; i < n; ++i)
      if (constrained_[i])
        constrained_list_.push_back(i);
  }

  void FETransientBeam::assemble_mass_and_base_load()
  {
    const FEBeam &beam = *beam_;
    const unsigned int n = beam.n_dofs();
    beam.assemble_mass_matrix(M_, beam.constraints());
    if (!settings_.axial_inertia)
      {
        // The free axial DoFs lose their mass: the axial block of M (it has
        // no coupling to the bending DoFs); the constrained DoFs keep their
        // diagonal filler.
        const std::vector<bool> &axial = beam.axial_dofs();
        for (unsigned int i = 0; i < n; ++i)
          if (axial[i] && !constrained_[i])
            massless_axial_.push_back(i);
        for (const unsigned int i : massless_axial_)
          for (auto e = M_.begin(i); e != M_.end(i); ++e)
            if (axial[e->column()] && !constrained_[e->column()])
              e->value() = 0.;
      }
    beam.assemble_base_load(r_);
    to_eigen(r_, r_eigen_);
  }

  void FETransientBeam::set_up_inverse_mass()
  {
    // The free bending DoFs' block of M, inverted densely (131 DoFs on the
    // default mesh: 0.1 MB, an impulse's velocity jump is a few columns of it).
    const unsigned int n            = n_dofs();
    const std::vector<bool> &axial = beam_->axial_dofs();
    std::vector<unsigned int> bending;
    for (unsigned int i = 0; i < n; ++i)
      if (!axial[i] && !constrained_[i])
        bending.push_back(i);
    const Eigen::Index m = static_cast<Eigen::Index>(bending.size());
    Eigen::MatrixXd M_bb = Eigen::MatrixXd::Zero(m, m);
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index b = 0; b < m; ++b)
        M_bb(a, b) = M_.el(bending[a], bending[b]);
    const Eigen::LLT<Eigen::MatrixXd> llt(M_bb);
    if (llt.info() != Eigen::Success)
      throw std::logic_error("FE transient: the bending block of the mass matrix is not positive definite");
    const Eigen::MatrixXd inverse = llt.solve(Eigen::MatrixXd::Identity(m, m));
    inverse_mass_.setZero(n, n);
    for (Eigen::Index a = 0; a < m; ++a)
      for (Eigen::Index b = 0; b < m; ++b)
        inverse_mass_(bending[a], bending[b]) = inverse(a, b);
  }

  void FETransientBeam::set_up_modal_damping(const unsigned int n_kept)
  {
    const unsigned int n = beam_->n_dofs();
    if (n_kept > 0)
      modes_ = compute_bending_modes(*beam_, n_kept);
    damping_ = std::make_unique<ModalDamping>(M_, modes_, damping_ratio_ > 0. ? n_kept : 0, damping_ratio_);
    const unsigned int rank = damping_->rank();
    U_.resize(n, rank);
    modal_c_.resize(rank);
    for (unsigned int k = 0; k < rank; ++k)
      {
        for (unsigned int i = 0; i < n; ++i)
          U_(i, k) = damping_->mass_weighted_modes()[k][i];
        modal_c_[k] = damping_->modal_coefficients()[k];
      }
    // The scratch of the solves, sized by n and the damping's rank.
    woodbury_rhs_.resize(rank);
    woodbury_v_.resize(rank);
    block_rhs_.resize(n, max_block_columns);
    block_v_.resize(rank, max_block_columns);
    block_w_.resize(rank, max_block_columns);
    block_column_.resize(n);
    block_solution_.resize(n);
    inverse_columns_.resize(n, n_inverse_columns);
    clear_inverse_columns();
    Z_.resize(n, rank);
    Dg_.resize(rank);
    capacitance_matrix_.resize(rank, rank);
    capacitance_ = Eigen::PartialPivLU<Eigen::MatrixXd>(rank);
  }

  void FETransientBeam::set_up_iteration_matrix_pattern()
  {
    // M in row-major form for the residual's product; S₀'s upper triangle
    // on the FE matrices' pattern with M's values in it, analysed once.
    const unsigned int n = beam_->n_dofs();
    std::vector<Eigen::Triplet<double>> triplets, upper;
    for (auto e = M_.begin(); e != M_.end(); ++e)
      {
        triplets.emplace_back(e->row(), e->column(), e->value());
        if (e->row() <= e->column())
          upper.emplace_back(e->row(), e->column(), e->value());
      }
    M_eigen_.resize(n, n);
    M_eigen_.setFromTriplets(triplets.begin(), triplets.end());
    M_eigen_.makeCompressed();
    M_blocks_.assign(M_eigen_); // empty on a band wider than 8: M_eigen_ multiplies then
    S0_.resize(n, n);
    S0_.setFromTriplets(upper.begin(), upper.end());
    S0_.makeCompressed();
    M_in_S0_ = Eigen::Map<const Eigen::VectorXd>(S0_.valuePtr(), S0_.nonZeros());
    ldlt_.analyzePattern(S0_);
  }

  std::ptrdiff_t FETransientBeam::iteration_matrix_entry(const unsigned int i, const unsigned int j)
  {
    if (constrained_[i] || constrained_[j] || i > j)
      return -1;
    return &S0_.coeffRef(i, j) - S0_.valuePtr(); // in the pattern: i, j share a cell
  }

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

  void FETransientBeam::factorise(const Eigen::VectorXd &q_bar, const double dt)
  {
    assemble_iteration_matrix(q_bar, dt);
    ldlt_.factorize_upper(S0_);
    if (ldlt_.info() != Eigen::Success)
      throw std::runtime_error("FE transient: the LDL^T factorisation of S = M + dt^2/4 K_t failed (dt = " +
                               std::to_string(dt) + " s)");
    const auto &L = ldlt_.matrixL().nestedExpression();
    inverse_D_    = ldlt_.diagonal().cwiseInverse();
    // The factors as 8 × 8 blocks for the solves (a band of half-width ≤ 8,
    // the beam meshes here); L row by row (see L_rows_) only on a wider band:
    // set up on its first factorisation, then only the values move.
    if (!block_factor_.assign(L, inverse_D_))
      {
        const Eigen::Index nnz = L.nonZeros();
        if (static_cast<Eigen::Index>(L_pattern_.size()) != nnz ||
            !std::equal(L_pattern_.begin(), L_pattern_.end(), L.innerIndexPtr()))
          {
            L_rows_ = L;
            L_rows_.makeCompressed();
            L_pattern_.assign(L.innerIndexPtr(), L.innerIndexPtr() + nnz);
            L_rows_entry_.resize(nnz);
            for (Eigen::Index j = 0; j < L.outerSize(); ++j)
              for (Eigen::Index k = L.outerIndexPtr()[j]; k < L.outerIndexPtr()[j + 1]; ++k)
                {
                  const int i    = L.innerIndexPtr()[k];
                  const int *row = L_rows_.innerIndexPtr();
                  const auto at  = std::lower_bound(row + L_rows_.outerIndexPtr()[i], row + L_rows_.outerIndexPtr()[i + 1], j);
                  L_rows_entry_[k] = at - row;
                }
          }
        for (Eigen::Index k = 0; k < nnz; ++k)
          L_rows_.valuePtr()[L_rows_entry_[k]] = L.valuePtr()[k];
      }

    // Woodbury terms of the rank-N damping, S = S₀ + U Dg Uᵀ.
    const unsigned int rank = damping_->rank();
    if (rank > 0)
      {
        // Into storage sized once (a refactorisation allocates nothing).
        for (unsigned int k = 0; k < rank; ++k)
          {
            block_column_ = U_.col(k);
            solve_factored(block_column_, block_solution_);
            Z_.col(k)     = block_solution_;
          }
        Dg_ = (settings_.theta * dt) * modal_c_;
        capacitance_matrix_.noalias() = U_.transpose() * Z_;
        capacitance_matrix_           = Dg_.asDiagonal() * capacitance_matrix_;
        capacitance_matrix_.diagonal().array() += 1.;
        capacitance_.compute(capacitance_matrix_);
      }
    clear_inverse_columns();
    factorised_       = true;
    factorised_dt_    = dt;
    factorised_theta_ = settings_.theta;
    factorised_step_  = stats_.steps;
    factorised_q_bar_ = q_bar;
    ++stats_.factorisations;
  }

  // The modified-Newton iteration reuses the last factorisation, so the
  // iterates of every later step depend on where it was made: a checkpoint
  // keeps that point (and the predictor's last step) and the restored model
  // factorises there again, which gives the same matrix to the bit.
  void FETransientBeam::save_state(CheckpointWriter &out) const
  {
    out.put(factorised_);
    out.put(factorised_ ? factorised_q_bar_ : Eigen::VectorXd::Zero(n_dofs()).eval());
    out.put(factorised_dt_);
    out.put(std::uint64_t(factorised_step_));
    out.put(std::uint64_t(stats_.steps));
    out.put(have_last_);
    out.put(last_dt_);
    out.put(last_acceleration_);
    out.put(have_last_ ? last_u_B_ : Eigen::VectorXd::Zero(n_dofs()).eval());
    out.put(have_last_ ? last_u_free_ : Eigen::VectorXd::Zero(n_dofs()).eval());
  }

  void FETransientBeam::load_state(CheckpointReader &in)
  {
    const bool factorised          = in.get_bool();
    const Eigen::VectorXd q_bar    = in.get_vector(n_dofs());
    const double factorised_dt     = in.get_double();
    const unsigned long step       = in.get_uint();
    stats_.steps                   = in.get_uint();
    have_last_                     = in.get_bool();
    last_dt_                       = in.get_double();
    last_acceleration_             = in.get_double();
    last_u_B_                      = in.get_vector(n_dofs());
    last_u_free_                   = in.get_vector(n_dofs());
    factorised_                    = false;
    if (factorised)
      {
        factorise(q_bar, factorised_dt);
        factorised_step_ = step;
      }
  }

  void FETransientBeam::solve_factored(const Eigen::VectorXd &b, Eigen::VectorXd &x) const
  {
    if (!block_factor_.empty())
      {
        block_factor_.solve(b, x);
        return;
      }
    // S₀ = L D Lᵀ on a wider band: forward row by row, scale, backward with
    // Lᵀ (which Eigen already walks row by row).
    x = b;
    L_rows_.triangularView<Eigen::UnitLower>().solveInPlace(x);
    x.array() *= inverse_D_.array();
    ldlt_.matrixU().solveInPlace(x);
  }

  void FETransientBeam::solve(const Eigen::VectorXd &b, Eigen::VectorXd &x) const
  {
    solve_factored(b, x);
    const unsigned int rank = damping_->rank();
    if (rank == 0)
      return;
    // x −= Z (I + Dg UᵀZ)⁻¹ Dg Uᵀ x, through scratch of size rank: no heap.
    woodbury_rhs_.noalias() = U_.transpose() * x;
    woodbury_rhs_.array() *= Dg_.array();
    woodbury_v_ = capacitance_.solve(woodbury_rhs_);
    x.noalias() -= Z_ * woodbury_v_;
  }

  // One step's smooth velocity as numerics/newton.h's problem: modified
  // Newton on the θ-method's residual with the last factorisation of S₀.
  struct FETransientBeam::NewtonStep
  {
    FETransientBeam &beam;
    const Eigen::VectorXd &q_M, &u_B;
    const double dt, theta, a;
    const unsigned int rank;
    const bool exact_in_one; // a linear beam without damping: S₀ is the exact Jacobian
    unsigned int iteration = 0;
    double tolerance       = 0; // on the last correction (correct())

    NewtonState evaluate(bool)
    {
      ++iteration;
      FETransientBeam &b = beam;
      // q̄ = (1 − θ) q_B + θ q_E = q_M + θ²Δt (u − u_B) + (2θ − 1)Δt u_B
      // (q_M + Δt/4 (u − u_B) for θ = 1/2).
      // (Each a single pass over the vectors, summed left to right as the
      // formula reads.)
      b.tmp_ = b.u_ - u_B;
      if (theta != 0.5)
        b.q_bar_ = q_M + (theta * theta * dt) * b.tmp_ + ((2. * theta - 1.) * dt) * u_B;
      else
        b.q_bar_ = q_M + (theta * theta * dt) * b.tmp_;
      b.internal_force_cached(b.q_bar_, b.f_);
      // R = M(u − u_B) + Δt [f(q̄) + C((1 − θ)u_B + θu) − r ẅ0], C = U diag(2Dω) Uᵀ.
      // Newton's first iterate is u_B itself unless extrapolated: then
      // M(u − u_B) is zero, and the first of a step's two products is
      // skipped.
      if (iteration == 1 && b.tmp_.isZero(0.))
        b.res_.setZero();
      else if (!b.M_blocks_.empty())
        b.M_blocks_.multiply(b.tmp_, b.res_);
      else
        b.res_.noalias() = b.M_eigen_ * b.tmp_;
      if (b.settings_.redistributed_mass)
        {
          // M̃ (u − u_B) and the base load of M̃.
          b.mrm_scratch_.noalias() = b.mrm_W_.transpose() * b.tmp_;
          b.res_.noalias() -= b.mrm_W_ * (b.mrm_A_ * b.mrm_scratch_);
          b.res_ = (b.res_ + dt * b.f_) - (dt * a) * b.r_tilde_;
        }
      else
        b.res_ = (b.res_ + dt * b.f_) - (dt * a) * b.r_eigen_;
      if (rank > 0)
        {
          // (θ = 1/2: C(u_B + u)/2, the same bits as 0.5 (u_B + u).)
          b.tmp_ = theta * b.u_ + (1. - theta) * u_B;
          // Column by column (rank N, a handful): dot products and axpys
          // over the DoFs cost less than two calls into Eigen's
          // matrix–vector kernel with their set-up.
          for (unsigned int k = 0; k < rank; ++k)
            b.res_ += (dt * b.modal_c_[k] * b.U_.col(k).dot(b.tmp_)) * b.U_.col(k);
        }
      if (!b.massless_axial_.empty())
        {
          // Massless axial DoFs: equilibrium at the step's end (see
          // FETransientSettings::axial_inertia).
          // θΔt f_axial(q_E): its Jacobian θ²Δt² K_axial is S₀'s axial block.
          b.q_end_ = q_M;
          b.q_end_.noalias() += (theta * dt) * b.u_;
          b.internal_force_cached(b.q_end_, b.f_end_);
          for (const unsigned int i : b.massless_axial_)
            b.res_[i] = theta * dt * b.f_end_[i];
        }
      for (const unsigned int i : b.constrained_list_)
        b.res_[i] = 0.;
      return NewtonState::go_on;
    }

    void factorise() { beam.factorise(beam.q_bar_, dt); }

    double correct()
    {
      // The correction with S₀ alone: the damping's part of S, θΔt C,
      // is of relative size Δt D ω_n ≤ 1e-4 on the N damped modes, so
      // leaving it out of the iteration matrix only adds that factor to
      // the contraction of this (already modified) Newton iteration; the
      // residual keeps the damping exactly, so the converged u_free is
      // the same. The contact impulses still see the full S (solve()).
      // With the mass redistributed, M̃ changes every step: the whole
      // S̃ = S − W A Wᵀ (damping included) by Woodbury on S's factor.
      if (beam.settings_.redistributed_mass)
        {
          beam.solve(beam.res_, beam.du_);
          beam.add_redistribution_term(beam.du_);
        }
      else
        beam.solve_factored(beam.res_, beam.du_);
      beam.u_ -= beam.du_;
      ++beam.stats_.newton_iterations;
      const FETransientSettings &settings = beam.settings_;
      tolerance = settings.relative_tolerance * (beam.u_.norm() + beam.q_bar_.norm() / dt) + settings.absolute_tolerance;
      return beam.du_.norm();
    }

    // Converged when the correction moves q_E by less than rtol of the
    // step's scale (Δt/2 δu against Δt u and q̄): this also sets the
    // floor above the round-off of f(q̄), which grows with ‖q̄‖/Δt. (The
    // driver also accepts on the contraction estimate of the remaining
    // error.) With damping the correction left out θΔt C, so only the
    // undamped linear beam is solved in one step.
    bool small(const double correction) const { return correction <= tolerance || (exact_in_one && iteration == 1); }
  };

  void FETransientBeam::compute_free_velocity(const double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B,
                                      const double dt, Eigen::VectorXd &u_free)
  {
    if (!(dt > 0.))
      throw std::invalid_argument("FE transient: time step Delta t = " + std::to_string(dt) + " s must be positive");
    const bool nonlinear = beam_->geometric_nonlinearity();
    // The smooth forces act at t_θ = t_B + θΔt, and t_M = t_B + (1 − θ)Δt
    // (both the midpoint for θ = 1/2).
    const double theta      = settings_.theta;
    const unsigned int rank = damping_->rank();
    NewtonStep step{*this, q_M, u_B, dt, theta, excitation_.acceleration(t_M + (2. * theta - 1.) * dt), rank,
                    !nonlinear && rank == 0};

    // Predictor: the start velocity (plus, optionally, the last step's smooth
    // velocity change).
    u_ = u_B;
    if (settings_.extrapolate && have_last_ && last_dt_ == dt)
      u_ += last_u_free_ - last_u_B_;
    for (const unsigned int i : constrained_list_)
      u_[i] = 0.;

    // Modified Newton: S₀ is refactorised when stale, or when a correction
    // shrinks by less than max_contraction against the one before (the
    // contraction measured across a refresh too).
    NewtonMatrixAge age;
    age.stale = !factorised_ || factorised_dt_ != dt || factorised_theta_ != theta ||
                (nonlinear && settings_.refactor_interval > 0 &&
                 stats_.steps - factorised_step_ >= settings_.refactor_interval);
    NewtonControl control;
    control.modified                       = true;
    control.max_iterations                 = settings_.max_iterations;
    control.max_contraction                = nonlinear ? settings_.max_contraction : std::numeric_limits<double>::infinity();
    control.accept_on_contraction_estimate = true;
    control.restart_contraction_at_refresh = false;
    const NewtonOutcome outcome = solve_newton(step, control, age);
    if (!outcome.converged())
      throw TransientNewtonFailure(t_M, outcome.iterations, outcome.correction, u_.norm());

    u_free             = u_;
    last_u_B_          = u_B;
    last_u_free_       = u_free;
    last_dt_           = dt;
    last_acceleration_ = step.a;
    have_last_         = true;
    ++stats_.steps;
  }

  void FETransientBeam::finish_step(const Eigen::VectorXd &q_B, const Eigen::VectorXd &q_E, const double dt,
                                    Eigen::VectorXd &u_E) const
  {
    for (const unsigned int i : massless_axial_)
      u_E[i] = (q_E[i] - q_B[i]) / dt;
  }

  void FETransientBeam::clear_inverse_columns()
  {
    inverse_column_dof_.fill(-1);
    next_inverse_column_ = 0;
    mrm_current_         = false;
  }

  const double *FETransientBeam::inverse_column(const unsigned int dof) const
  {
    if (settings_.impulses_through_mass)
      return inverse_mass_.col(dof).data();
    for (unsigned int k = 0; k < n_inverse_columns; ++k)
      if (inverse_column_dof_[k] == static_cast<int>(dof))
        return inverse_columns_.col(k).data();
    const unsigned int k = next_inverse_column_;
    next_inverse_column_ = (k + 1) % n_inverse_columns;
    block_column_.setZero();
    block_column_[dof] = 1.;
    solve(block_column_, block_solution_);
    inverse_columns_.col(k) = block_solution_;
    inverse_column_dof_[k]  = static_cast<int>(dof);
    ++stats_.inverse_column_solves;
    return inverse_columns_.col(k).data();
  }

  void FETransientBeam::apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                               Eigen::Ref<Eigen::MatrixXd> X) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: iteration matrix used before its first factorisation");
    if (X.rows() != B.rows() || X.cols() != B.cols())
      throw std::logic_error("FE transient: apply_inverse_iteration_matrix needs X of B's size");
    // All right-hand sides at once (the contact directions, up to 8): one
    // pass of the sparse triangular solves over a block, then the Woodbury
    // correction as a block.
    // Scratch of the largest block (the contact directions: at most
    // max_block_columns), used by its leading columns: no allocation.
    const Eigen::Index m = B.cols();
    if (m > block_rhs_.cols())
      throw std::logic_error("FE transient: more right-hand sides than the scratch holds");
    // A block whose columns each touch a few DoFs (the contact directions:
    // four) is combined from the kept columns of S⁻¹.
    // One pass over each column finds its entries (free DoFs only).
    const unsigned int n = n_dofs();
    constexpr unsigned int max_sparse_entries = 8;
    std::array<std::array<unsigned int, max_sparse_entries>, max_block_columns> entries;
    std::array<unsigned int, max_block_columns> n_entries{};
    bool sparse = true;
    for (Eigen::Index j = 0; j < m && sparse; ++j)
      {
        const double *b = B.col(j).data();
        for (unsigned int i = 0; i < n; ++i)
          if (b[i] != 0. && !constrained_[i])
            {
              if (n_entries[j] == max_sparse_entries)
                {
                  sparse = false;
                  break;
                }
              entries[j][n_entries[j]++] = i;
            }
      }
    if (sparse)
      {
        for (Eigen::Index j = 0; j < m; ++j)
          {
            auto x = X.col(j);
            x.setZero();
            for (unsigned int k = 0; k < n_entries[j]; ++k)
              {
                const unsigned int i = entries[j][k];
                x += B(i, j) * Eigen::Map<const Eigen::VectorXd>(inverse_column(i), n);
              }
            if (settings_.redistributed_mass)
              {
                block_column_ = x;
                add_redistribution_term(block_column_);
                x = block_column_;
              }
          }
        stats_.iteration_matrix_solves += B.cols();
        return;
      }
    if (settings_.impulses_through_mass)
      {
        X.noalias() = inverse_mass_ * B; // zero rows and columns on the constrained and axial DoFs
        stats_.iteration_matrix_solves += B.cols();
        return;
      }
    auto rhs = block_rhs_.leftCols(m);
    rhs      = B;
    for (const unsigned int i : constrained_list_)
      rhs.row(i).setZero();
    for (Eigen::Index j = 0; j < m; ++j)
      {
        // Through plain vectors: Eigen's permuted solve into a column of a
        // Ref allocates a temporary.
        block_column_ = rhs.col(j);
        solve_factored(block_column_, block_solution_);
        X.col(j)      = block_solution_;
      }
    const unsigned int rank = damping_->rank();
    if (rank > 0)
      {
        auto v = block_v_.leftCols(m);
        auto w = block_w_.leftCols(m);
        v.noalias() = U_.transpose() * X;
        for (Eigen::Index j = 0; j < m; ++j)
          {
            woodbury_rhs_ = Dg_.cwiseProduct(v.col(j));
            woodbury_v_   = capacitance_.solve(woodbury_rhs_);
            w.col(j)      = woodbury_v_;
          }
        X.noalias() -= Z_ * w;
      }
    if (settings_.redistributed_mass)
      for (Eigen::Index j = 0; j < m; ++j)
        {
          block_column_ = X.col(j);
          add_redistribution_term(block_column_);
          X.col(j) = block_column_;
        }
    stats_.iteration_matrix_solves += B.cols();
  }

  void FETransientBeam::inverse_iteration_matrix_block(const unsigned int *index, const unsigned int k,
                                                     Eigen::Ref<Eigen::MatrixXd> out) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: iteration matrix used before its first factorisation");
    // Column b of the block is S⁻¹ e_{index[b]} read at the k coordinates;
    // each column is read before the next is asked for (a kept column may
    // be replaced by the next one solved).
    for (unsigned int b = 0; b < k; ++b)
      {
        const double *column = inverse_column(index[b]);
        for (unsigned int a = 0; a < k; ++a)
          out(a, b) = column[index[a]];
      }
    if (settings_.redistributed_mass)
      {
        // + Y C⁻¹ Yᵀ on the k coordinates.
        update_redistribution();
        for (unsigned int b = 0; b < k; ++b)
          {
            mrm_scratch_ = mrm_C_.solve(mrm_Y_.row(index[b]).transpose());
            for (unsigned int a = 0; a < k; ++a)
              out(a, b) += mrm_Y_.row(index[a]).dot(mrm_scratch_);
          }
      }
    ++stats_.contact_blocks;
  }

  void FETransientBeam::add_inverse_iteration_matrix_times(const unsigned int *index, const unsigned int k,
                                                         const double *y, Eigen::VectorXd &u) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: iteration matrix used before its first factorisation");
    const unsigned int n = n_dofs();
    for (unsigned int a = 0; a < k; ++a)
      if (y[a] != 0.)
        u += y[a] * Eigen::Map<const Eigen::VectorXd>(inverse_column(index[a]), n);
    if (settings_.redistributed_mass)
      {
        // + Y C⁻¹ Yᵀ (Σ y_a e_a).
        update_redistribution();
        Eigen::Vector2d v = Eigen::Vector2d::Zero();
        for (unsigned int a = 0; a < k; ++a)
          v += y[a] * mrm_Y_.row(index[a]).transpose();
        mrm_scratch_ = mrm_C_.solve(v);
        u.noalias() += mrm_Y_ * mrm_scratch_;
      }
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

  double FETransientBeam::energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const
  {
    energy_Mu_.noalias() = M_eigen_ * u;
    double kinetic = 0.5 * u.dot(energy_Mu_);
    if (settings_.redistributed_mass)
      {
        const Eigen::Vector2d Wu = mrm_W_.transpose() * u;
        kinetic -= 0.5 * Wu.dot(mrm_A_ * Wu);
      }
    return kinetic + strain_energy(q);
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

  void FETransientBeam::compute_step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const
  {
    if (!have_last_)
      {
        damping_work = excitation_work = 0.;
        return;
      }
    // The damping impulse Δt C u_θ, u_θ = (1 − θ)u_B + θu_E, times ū:
    // ū·C u_θ = Σ 2Dω_n (M φ_n · ū)(M φ_n · u_θ), C = U diag(2Dω) Uᵀ
    // (θ = 1/2: u_θ = ū to the bit, and the work is ū·C ū).
    const double theta = settings_.theta;
    u_mean_  = 0.5 * (last_u_B_ + u_E);
    u_theta_ = (1. - theta) * last_u_B_ + theta * u_E;
    double c_work = 0;
    for (Eigen::Index k = 0; k < U_.cols(); ++k)
      c_work += modal_c_[k] * U_.col(k).dot(u_mean_) * U_.col(k).dot(u_theta_);
    damping_work    = -last_dt_ * c_work;
    excitation_work = last_dt_ * last_acceleration_ * (settings_.redistributed_mass ? r_tilde_ : r_eigen_).dot(u_mean_);
  }
} // namespace beamslider
