// The FE beam as a BeamSystem: the implicit Moreau–Jean θ-scheme, see
// fe_transient.h. This file: set-up, the step's Newton iteration, the
// checkpoint state, energy and works; the per-cell forces and point
// kinematics are in fe_transient_cells.cc, the solves with the iteration
// matrix in fe_transient_solves.cc.
#include "fem/fe_transient.h"

#include "numerics/state_bytes.h"
#include "numerics/newton.h"

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
