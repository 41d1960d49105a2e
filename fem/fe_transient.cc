// The FE beam as a BeamSystem: implicit midpoint (Moreau–Jean θ = 1/2), see fe_transient.h.
#include "fem/fe_transient.h"

#include "contact/checkpoint.h"

#include <deal.II/base/quadrature_lib.h>

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
    const FEBeam &beam = *beam_;
    const unsigned int n = beam.n_dofs();
    const auto &c        = beam.constraints();

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

    beam.assemble_mass_matrix(M_, c);
    beam.assemble_base_load(r_);
    K_.reinit(beam.sparsity_pattern());
    S0_.reinit(beam.sparsity_pattern());

    const unsigned int n_kept = scene.discretisation.n_modes;
    if (n_kept > 0)
      modes_ = compute_bending_modes(beam, n_kept);
    damping_ = std::make_unique<ModalDamping>(M_, modes_, damping_ratio_ > 0. ? n_kept : 0, damping_ratio_);
    const unsigned int rank = damping_->rank();
    U_.resize(n, rank);
    for (unsigned int k = 0; k < rank; ++k)
      for (unsigned int i = 0; i < n; ++i)
        U_(i, k) = damping_->mass_weighted_modes()[k][i];

    for (auto *v : {&tmp_a_, &tmp_b_, &tmp_c_, &q_bar_, &u_, &res_, &du_, &f_, &uB_, &qM_})
      v->reinit(n);

    // Quadrature data: the Gauss rule FEBeam::assemble_internal_force uses
    // (max(5, p + 2) points, exact for N w' N_a'), shape values from FEBeam.
    const unsigned int degree = beam.get_dof_handler().get_fe().degree;
    const dealii::QGauss<1> gauss(std::max(5u, degree + 2));
    for (const auto &cell : beam.get_dof_handler().active_cell_iterators())
      {
        const double x0 = cell->vertex(0)[0], h = cell->vertex(1)[0] - x0;
        for (unsigned int k = 0; k < gauss.size(); ++k)
          {
            const FEPointShape p = beam.point_shape(x0 + gauss.point(k)[0] * h);
            QuadraturePointData d;
            for (unsigned int a = 0; a < 4; ++a)
              {
                d.w_dofs[a] = p.w_dofs[a];
                d.dN[a]     = p.slope_values[a];
                d.ddN[a]    = p.curvature_values[a];
              }
            d.u_dofs.assign(p.u_dofs.begin(), p.u_dofs.end());
            d.du  = p.strain_values;
            d.JxW = gauss.weight(k) * h;
            quadrature_.push_back(std::move(d));
          }
      }
    if (!beam.support_data().ideal_clamp)
      for (unsigned int end = 0; end < 2; ++end)
        {
          const auto [u, w, theta] = beam.support_dofs(end);
          springs_.emplace_back(theta, beam.support_data().rotational_stiffness);
          springs_.emplace_back(u, beam.support_data().axial_spring_per_end());
        }
  }

  void FETransientBeam::cached_internal_force(const dealii::Vector<double> &q, dealii::Vector<double> &f) const
  {
    // f = ∫ N δε + M δκ dx with N = EA ε, M = EI κ, δε = δu' + w' δw'
    // (doc/physics.md §2–3; FEBeam::assemble_internal_force), plus the springs.
    if (f.size() != q.size())
      f.reinit(q.size());
    else
      f = 0.;
    const bool nonlinear = beam_->geometric_nonlinearity();
    const double EA = beam_->beam_data().axial_stiffness(), EI = beam_->beam_data().bending_stiffness();
    for (const QuadraturePointData &d : quadrature_)
      {
        double du = 0, dw = 0, ddw = 0;
        for (unsigned int i = 0; i < d.u_dofs.size(); ++i)
          du += d.du[i] * q[d.u_dofs[i]];
        for (unsigned int a = 0; a < 4; ++a)
          {
            dw += d.dN[a] * q[d.w_dofs[a]];
            ddw += d.ddN[a] * q[d.w_dofs[a]];
          }
        const double N = EA * (du + (nonlinear ? 0.5 * dw * dw : 0.)) * d.JxW;
        const double M = EI * ddw * d.JxW, Nw = nonlinear ? N * dw : 0.;
        for (unsigned int i = 0; i < d.u_dofs.size(); ++i)
          f[d.u_dofs[i]] += N * d.du[i];
        for (unsigned int a = 0; a < 4; ++a)
          f[d.w_dofs[a]] += Nw * d.dN[a] + M * d.ddN[a];
      }
    for (const auto &[dof, k] : springs_)
      f[dof] += k * q[dof];
    for (unsigned int i = 0; i < f.size(); ++i)
      if (constrained_[i])
        f[i] = 0.;
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

  void FETransientBeam::evaluate(const double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const
  {
    const double L = length();
    if (!(x >= 0. && x <= L))
      {
        std::ostringstream m;
        m << "FE beam evaluated at x = " << x << " m, outside the beam [0, " << L << "] m";
        throw std::out_of_range(m.str());
      }
    const FEPointShape p = beam_->point_shape(x);
    const unsigned int n = n_dofs();
    out.grad_w.setZero(n);
    out.grad_dw.setZero(n);
    for (unsigned int a = 0; a < 4; ++a)
      {
        const auto dof = p.w_dofs[a];
        if (constrained_[dof])
          continue;
        out.grad_w[dof] += p.w_values[a];
        out.grad_dw[dof] += p.slope_values[a];
      }
    out.w  = out.grad_w.dot(q);
    out.dw = out.grad_dw.dot(q);
  }

  void FETransientBeam::factorise(const dealii::Vector<double> &q_bar, const double dt)
  {
    beam_->assemble_internal_force(q_bar, nullptr, &K_, beam_->constraints());
    S0_.copy_from(M_);
    S0_.add(0.25 * dt * dt, K_);
    if (S0_entry_.empty())
      {
        // The pattern of S₀ in Eigen's compressed columns, once: the map from
        // deal.II's entry order to Eigen's value array, and the fill-reducing
        // ordering and symbolic factorisation.
        std::vector<Eigen::Triplet<double>> triplets;
        for (auto e = S0_.begin(); e != S0_.end(); ++e)
          triplets.emplace_back(e->row(), e->column(), 0.);
        S0_eigen_.resize(n_dofs(), n_dofs());
        S0_eigen_.setFromTriplets(triplets.begin(), triplets.end());
        S0_eigen_.makeCompressed();
        for (auto e = S0_.begin(); e != S0_.end(); ++e)
          S0_entry_.push_back(&S0_eigen_.coeffRef(e->row(), e->column()) - S0_eigen_.valuePtr());
        ldlt_.analyzePattern(S0_eigen_);
      }
    {
      double *values = S0_eigen_.valuePtr();
      std::size_t k  = 0;
      for (auto e = S0_.begin(); e != S0_.end(); ++e, ++k)
        values[S0_entry_[k]] = e->value();
    }
    ldlt_.factorize(S0_eigen_);
    if (ldlt_.info() != Eigen::Success)
      throw std::runtime_error("FE transient: the LDL^T factorisation of S = M + dt^2/4 K_t failed (dt = " +
                               std::to_string(dt) + " s)");

    // Woodbury terms of the rank-N damping, S = S₀ + U Dg Uᵀ.
    const unsigned int rank = damping_->rank();
    if (rank > 0)
      {
        const unsigned int n = n_dofs();
        Z_.resize(n, rank);
        Dg_.resize(rank);
        for (unsigned int k = 0; k < rank; ++k)
          {
            const dealii::Vector<double> &Mphi = damping_->mass_weighted_modes()[k];
            Z_.col(k) = ldlt_.solve(Eigen::Map<const Eigen::VectorXd>(Mphi.begin(), Mphi.size()));
            Dg_[k] = 0.5 * dt * damping_->modal_coefficients()[k];
          }
        const Eigen::MatrixXd cap =
          Eigen::MatrixXd::Identity(rank, rank) + Dg_.asDiagonal() * (U_.transpose() * Z_);
        capacitance_.compute(cap);
      }
    factorised_      = true;
    factorised_dt_   = dt;
    factorised_step_ = stats_.steps;
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
    Eigen::VectorXd q_bar;
    to_eigen(factorised_q_bar_, q_bar);
    out.put(q_bar);
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
        dealii::Vector<double> q(n_dofs());
        to_dealii(q_bar, q);
        factorise(q, factorised_dt);
        factorised_step_ = step;
      }
  }

  void FETransientBeam::solve(const dealii::Vector<double> &b, dealii::Vector<double> &x) const
  {
    if (x.size() != b.size())
      x.reinit(b.size());
    Eigen::Map<Eigen::VectorXd> y(x.begin(), x.size());
    y = ldlt_.solve(Eigen::Map<const Eigen::VectorXd>(b.begin(), b.size()));
    const unsigned int rank = damping_->rank();
    if (rank == 0)
      return;
    // y −= Z (I + Dg UᵀZ)⁻¹ Dg Uᵀ y, through scratch of size rank: no heap.
    woodbury_rhs_.noalias() = U_.transpose() * y;
    woodbury_rhs_.array() *= Dg_.array();
    woodbury_v_ = capacitance_.solve(woodbury_rhs_);
    y.noalias() -= Z_ * woodbury_v_;
  }

  void FETransientBeam::free_velocity(const double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B,
                                      const double dt, Eigen::VectorXd &u_free)
  {
    if (!(dt > 0.))
      throw std::invalid_argument("FE transient: time step Delta t = " + std::to_string(dt) + " s must be positive");
    const unsigned int n = n_dofs();
    const auto &c        = beam_->constraints();
    const bool nonlinear = beam_->geometric_nonlinearity();
    to_dealii(q_M, qM_);
    to_dealii(u_B, uB_);
    const double a = excitation_.acceleration(t_M);

    // Predictor: the start velocity plus the last step's smooth velocity change.
    u_ = uB_;
    if (settings_.extrapolate && have_last_ && last_dt_ == dt)
      for (unsigned int i = 0; i < n; ++i)
        u_[i] += last_u_free_[i] - last_u_B_[i];
    for (unsigned int i = 0; i < n; ++i)
      if (constrained_[i])
        u_[i] = 0.;

    bool refactor = !factorised_ || factorised_dt_ != dt ||
                    (nonlinear && settings_.refactor_interval > 0 &&
                     stats_.steps - factorised_step_ >= settings_.refactor_interval);
    double previous = std::numeric_limits<double>::infinity(), correction = 0;
    unsigned int it = 0;
    bool converged  = false;
    while (it < settings_.max_iterations)
      {
        ++it;
        // q̄ = q_M + Δt/4 (u − u_B).
        q_bar_ = qM_;
        q_bar_.add(0.25 * dt, u_, -0.25 * dt, uB_);
        cached_internal_force(q_bar_, f_);
        if (refactor)
          {
            factorise(q_bar_, dt);
            refactor = false;
          }
        // R = M(u − u_B) + Δt [f(q̄) + C(u_B + u)/2 − r ẅ0].
        tmp_a_ = u_;
        tmp_a_ -= uB_;
        M_.vmult(res_, tmp_a_);
        tmp_b_ = u_;
        tmp_b_ += uB_;
        damping_->vmult(tmp_c_, tmp_b_); // C (u + u_B)
        res_.add(dt, f_, 0.5 * dt, tmp_c_);
        res_.add(-dt * a, r_);
        for (unsigned int i = 0; i < n; ++i)
          if (constrained_[i])
            res_[i] = 0.;
        solve(res_, du_);
        u_ -= du_;
        ++stats_.newton_iterations;

        correction = du_.l2_norm();
        if (!std::isfinite(correction))
          break;
        // Converged when the correction moves q_E by less than rtol of the
        // step's scale (Δt/2 δu against Δt u and q̄): this also sets the
        // floor above the round-off of f(q̄), which grows with ‖q̄‖/Δt.
        // With the contraction c = ‖δu_k‖/‖δu_{k−1}‖ of the (modified) Newton
        // iteration the remaining error is about c/(1 − c) ‖δu_k‖ (Hairer &
        // Wanner, Solving ODEs II, §IV.8): accept on that estimate too, which
        // saves the iteration that would only confirm convergence.
        const double tolerance =
          settings_.relative_tolerance * (u_.l2_norm() + q_bar_.l2_norm() / dt) + settings_.absolute_tolerance;
        const double c = correction / previous;
        if (correction <= tolerance || (it > 1 && c < 0.5 && c / (1. - c) * correction <= tolerance))
          {
            converged = true;
            break;
          }
        // A linear beam with an exact factorisation is solved in one step
        // (up to round-off).
        if (!nonlinear && it == 1)
          {
            converged = true;
            break;
          }
        if (nonlinear && correction > settings_.max_contraction * previous)
          refactor = true;
        previous = correction;
      }
    if (!converged)
      throw TransientNewtonFailure(t_M, it, correction, u_.l2_norm());

    to_eigen(u_, u_free);
    last_u_B_          = u_B;
    last_u_free_       = u_free;
    last_dt_           = dt;
    last_acceleration_ = a;
    have_last_         = true;
    ++stats_.steps;
  }

  void FETransientBeam::solve_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                               Eigen::Ref<Eigen::MatrixXd> X) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: solve_iteration_matrix called before free_velocity");
    const unsigned int n = n_dofs();
    if (X.rows() != B.rows() || X.cols() != B.cols())
      throw std::logic_error("FE transient: solve_iteration_matrix needs X of B's size");
    // All right-hand sides at once (the contact directions, up to 8): one
    // pass of the sparse triangular solves over a block, then the Woodbury
    // correction as a block.
    Eigen::MatrixXd rhs = B;
    for (unsigned int i = 0; i < n; ++i)
      if (constrained_[i])
        rhs.row(i).setZero();
    X = ldlt_.solve(rhs);
    const unsigned int rank = damping_->rank();
    if (rank > 0)
      {
        const Eigen::MatrixXd V = capacitance_.solve(Dg_.asDiagonal() * (U_.transpose() * X));
        X.noalias() -= Z_ * V;
      }
    stats_.iteration_matrix_solves += B.cols();
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
    const double g = 0.5 / std::sqrt(3.);
    double V       = 0;
    for (const double s : {0.5 - g, 0.5 + g})
      V += 0.5 * internal_force(s * q).dot(q);
    return V;
  }

  double FETransientBeam::energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const
  {
    dealii::Vector<double> ud, Mu(n_dofs());
    to_dealii(u, ud);
    M_.vmult(Mu, ud);
    return 0.5 * (ud * Mu) + strain_energy(q);
  }

  void FETransientBeam::step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const
  {
    if (!have_last_)
      {
        damping_work = excitation_work = 0.;
        return;
      }
    const Eigen::VectorXd u_mean = 0.5 * (last_u_B_ + u_E);
    dealii::Vector<double> um, Cum;
    to_dealii(u_mean, um);
    damping_->vmult(Cum, um);
    damping_work = -last_dt_ * (um * Cum);
    excitation_work = last_dt_ * last_acceleration_ * (r_ * um);
  }
} // namespace beamslider
