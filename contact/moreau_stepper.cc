// Moreau midpoint step for beam + slider, see moreau_stepper.h.
#include "contact/moreau_stepper.h"

#include "contact/contact_products.h"
#include "contact/moreau_step_skeleton.h"

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

namespace beamslider
{
  namespace
  {
    const char *corner_name(const unsigned int k)
    {
      static const char *names[n_slider_corners] = {"upper-left", "upper-right", "lower-left", "lower-right"};
      return names[k];
    }

    std::string solver_failure_message(const double t, const unsigned int n_active, const std::string &corners,
                                       const double residual, const unsigned int iterations)
    {
      std::ostringstream m;
      m << "contact solver failed at t = " << t << " s: " << n_active << " active contact(s) (" << corners
        << "), relative residual " << residual << " after " << iterations
        << " Gauss-Seidel sweeps (the iteration cap); the step is not accepted";
      return m.str();
    }

    std::string support_message(const double t, const double x_C, const double x_corner, const double L)
    {
      std::ostringstream m;
      m << "the slider reached the support at x = " << (x_corner < 0 ? "0" : "L") << " at t = " << t
        << " s: x_C = " << x_C << " m (x_C/L = " << x_C / L << "), a window corner at x = " << x_corner
        << " m is outside the beam [0, " << L << "] m; the run stops here, everything before t is kept";
      return m.str();
    }
  } // namespace

  ContactSolverFailure::ContactSolverFailure(const double t_, const unsigned int n_active_,
                                             std::string active_corners_, const double residual_,
                                             const unsigned int iterations_)
    : std::runtime_error(solver_failure_message(t_, n_active_, active_corners_, residual_, iterations_))
    , t(t_)
    , n_active(n_active_)
    , active_corners(std::move(active_corners_))
    , residual(residual_)
    , iterations(iterations_)
  {}

  SliderAtSupport::SliderAtSupport(const double t_, const double x_C_, const double x_corner_, const double length)
    : std::runtime_error(support_message(t_, x_C_, x_corner_, length))
    , t(t_)
    , x_C(x_C_)
    , x_corner(x_corner_)
    , support(x_corner_ < 0 ? 0. : length)
  {}

  MoreauStepper::MoreauStepper(BeamSystem &beam, const SliderParameters &slider, const ContactLaw &law,
                               const BaseExcitation &base, const double time_step, const ProxSolverSettings solver)
    : beam_(beam)
    , slider_(slider)
    , geometry_(slider, beam.thickness())
    , law_(law)
    , base_(base)
    , dt_(time_step)
    , solver_(solver)
  {
    const double limit = beam_.max_stable_time_step();
    if (!(dt_ > 0.) || dt_ > limit)
      {
        std::ostringstream m;
        m << "time step Delta t = " << dt_ << " s is outside the allowed range (0, " << limit
          << "] s (the beam model's stability limit)";
        throw std::invalid_argument(m.str());
      }
    if (!(law_.friction_coefficient >= 0.))
      {
        std::ostringstream m;
        m << "friction coefficient mu = " << law_.friction_coefficient << " is outside [0, inf)";
        throw std::invalid_argument(m.str());
      }
    if (!(law_.restitution >= 0. && law_.restitution <= 1.))
      {
        std::ostringstream m;
        m << "restitution e_N = " << law_.restitution << " is outside [0, 1]";
        throw std::invalid_argument(m.str());
      }
    if (!(law_.normal_stiffness >= 0. && law_.normal_damping >= 0.) || !std::isfinite(law_.normal_stiffness) ||
        !std::isfinite(law_.normal_damping))
      {
        std::ostringstream m;
        m << "normal stiffness k_N = " << law_.normal_stiffness << " N/m and damping c_N = " << law_.normal_damping
          << " N s/m must be finite and >= 0";
        throw std::invalid_argument(m.str());
      }
    for (auto &p : warm_)
      p.setZero();
    const Eigen::Index n = beam_.n_dofs();
    for (Eigen::VectorXd *v : {&q_M_, &u_free_, &u_E_, &u_mean_, &q_next_})
      v->setZero(n);
    W_b_.setZero(n, max_unknowns);
    X_b_.setZero(n, max_unknowns);
    corner_.beam_normal.setZero(n);
    corner_.beam_tangent.setZero(n);
    stretch_q_.setZero(n);
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      corner_position_[k] = {corner_side(k) * 0.5 * slider_.window_width,
                             corner_zeta(k) * 0.5 * slider_.window_height + slider_.com_offset};
    // The explicit modal step takes the midpoint rule of the form's model.
    modal_ = beam_.explicit_modal_form();
    if (modal_ && (modal_->n_modes != n || beam_.theta() != 0.5))
      throw std::logic_error("explicit modal form: its mode count or the model's theta disagrees with the model");
    set_state(resting_state(0.5 * beam_.length()));
  }

  SystemState MoreauStepper::resting_state(const double x_C, const double t) const
  {
    SystemState s;
    s.t = t;
    s.q = Eigen::VectorXd::Zero(beam_.n_dofs());
    s.u = Eigen::VectorXd::Zero(beam_.n_dofs());
    s.s = geometry_.resting_position(x_C, t, beam_, base_, s.q);
    s.v.setZero();
    return s;
  }

  SystemState MoreauStepper::slider_moved_to(const double x_C) const
  {
    const double L = beam_.length();
    SystemState s  = state_;
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      {
        const double x = x_C + geometry_.corner_offset(k, s.s[2])[0];
        if (!(x >= 0. && x <= L))
          {
            std::ostringstream m;
            m << "slider position x_C = " << x_C << " m puts the " << corner_name(k) << " corner at x = " << x
              << " m, outside the beam [0, " << L << "] m";
            throw std::invalid_argument(m.str());
          }
      }

    // Beam displacement, slope and their rates under the old and the new x_C.
    BeamPointKinematics p;
    auto at = [&](const double x, const Eigen::VectorXd &q) {
      beam_.evaluate(x, q, p);
      return Eigen::Vector2d(p.w, p.dw);
    };
    const Eigen::Vector2d old_pos = at(s.s[0], s.q), new_pos = at(x_C, s.q);
    const Eigen::Vector2d old_rate = at(s.s[0], s.u), new_rate = at(x_C, s.u);
    const double angle_rate_old = old_rate[1] / (1. + old_pos[1] * old_pos[1]); // d/dt atan w'
    const double angle_rate_new = new_rate[1] / (1. + new_pos[1] * new_pos[1]);
    s.s[0] = x_C;
    s.s[1] += new_pos[0] - old_pos[0];
    s.s[2] += std::atan(new_pos[1]) - std::atan(old_pos[1]);
    s.v[1] += new_rate[0] - old_rate[0];
    s.v[2] += angle_rate_new - angle_rate_old;

    // The side (upper or lower corners) nearer the beam keeps its smallest
    // gap, so that a resting slider stays resting: the change of curvature
    // under the window shifts the corners' gaps by about Δw'' B²/8
    // (micrometres here), which would otherwise drop the slider for a
    // millisecond or push it into the beam. g_N is linear in z_C with slope
    // ∂g_N/∂z_C = ζ cos α, so one correction is exact.
    CornerKinematics corner;
    auto smallest_gaps = [&](const SystemState &state, double dz_dgap[2]) {
      std::array<double, 2> g{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
      for (unsigned int k = 0; k < n_slider_corners; ++k)
        {
          geometry_.evaluate(k, state.t, beam_, base_, state.q, state.s, corner);
          const unsigned int side = corner_zeta(k) > 0 ? 0 : 1;
          if (corner.gap < g[side])
            {
              g[side] = corner.gap;
              if (dz_dgap)
                dz_dgap[side] = 1. / corner.slider_normal[1];
            }
        }
      return g;
    };
    const std::array<double, 2> before = smallest_gaps(state_, nullptr);
    double dz_dgap[2]                  = {0., 0.};
    const std::array<double, 2> after  = smallest_gaps(s, dz_dgap);
    const unsigned int near_side       = before[0] <= before[1] ? 0 : 1;
    s.s[1] += (before[near_side] - after[near_side]) * dz_dgap[near_side];
    return s;
  }

  void MoreauStepper::set_state(const SystemState &state)
  {
    if (state.q.size() != beam_.n_dofs() || state.u.size() != beam_.n_dofs())
      {
        std::ostringstream m;
        m << "state has " << state.q.size() << " coordinates and " << state.u.size() << " velocities, the beam "
          << beam_.n_dofs();
        throw std::invalid_argument(m.str());
      }
    state_       = state;
    t_origin_    = state.t;
    steps_taken_ = 0;
    for (auto &p : warm_)
      p.setZero();
  }

  void MoreauStepper::save(CheckpointWriter &out) const
  {
    out.put(state_.t);
    out.put(state_.q);
    out.put(state_.u);
    out.put(state_.s);
    out.put(state_.v);
    out.put(t_origin_);
    out.put(std::uint64_t(steps_taken_));
    for (const auto &p : warm_)
      out.put(p);
    out.put(prescribed_x_);
    beam_.save_state(out);
  }

  void MoreauStepper::load(CheckpointReader &in)
  {
    const Eigen::Index n = beam_.n_dofs();
    state_.t             = in.get_double();
    state_.q             = in.get_vector(n);
    state_.u             = in.get_vector(n);
    in.get(state_.s);
    in.get(state_.v);
    t_origin_    = in.get_double();
    steps_taken_ = in.get_uint();
    for (auto &p : warm_)
      in.get(p);
    prescribed_x_ = in.get_bool();
    beam_.load_state(in);
  }

  double MoreauStepper::slider_kinetic_energy() const
  {
    const auto &v = state_.v;
    return 0.5 * slider_.mass * (v[0] * v[0] + v[1] * v[1]) + 0.5 * slider_.inertia * v[2] * v[2];
  }

  void MoreauStepper::check_corners_on_beam(const double t_B, const Eigen::Vector3d &s_M,
                                            const SliderFrame &frame) const
  {
    const double L = beam_.length();
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      {
        // x of the corner: SliderGeometry::corner_offset's, from the
        // positions kept at construction (no call per corner).
        const double x = s_M[0] + (frame.cos_beta * corner_position_[k][0] - frame.sin_beta * corner_position_[k][1]);
        if (!(x >= 0. && x <= L))
          {
            // A physical arrival overshoots by |v_x| Δt/2, micrometres; a
            // jump past the support by more than the window itself is a
            // diverging state, not a slider that reached the end.
            const double overshoot = x < 0. ? -x : x - L;
            if (!(overshoot <= slider_.window_width))
              {
                std::ostringstream msg;
                msg << "unphysical state at t = " << t_B << " s: a window corner jumped to x = " << x
                    << " m, past the support by more than the window width B = " << slider_.window_width
                    << " m within half a step (x_C = " << state_.s[0] << " m, v_x = " << state_.v[0]
                    << " m/s): the integration diverges; the step is not accepted";
                throw UnphysicalState(msg.str());
              }
            throw SliderAtSupport(t_B, state_.s[0], x, L);
          }
      }
  }

  bool MoreauStepper::corner_is_closed_or_throw(const unsigned int k, const double gap, const double thickness,
                                                const double t_B) const
  {
    const double clearance = slider_.window_height - thickness;
    if (gap < -clearance)
      {
        std::ostringstream msg;
        msg << "unphysical state at t = " << t_B << " s: the " << corner_name(k)
            << " corner penetrates the beam by " << -gap << " m, more than the whole clearance R - h = "
            << clearance << " m (the slider would be through the beam; x_C = " << state_.s[0]
            << " m): the integration diverges or the time step cannot resolve the contact; the step is not "
               "accepted";
        throw UnphysicalState(msg.str());
      }
    if (gap <= 0.)
      return true;
    if (!std::isfinite(gap))
      {
        std::ostringstream msg;
        msg << "non-finite gap at corner " << corner_name(k) << " at t = " << t_B << " s";
        throw NonFiniteState(msg.str());
      }
    return false;
  }

  void MoreauStepper::solve_contact_impulses(const double t_B, const std::array<unsigned int, n_slider_corners> &active,
                                             const unsigned int m,
                                             const Eigen::Matrix<double, max_unknowns, 1> &gamma_B)
  {
    const Eigen::Index m2 = 2 * m;
    auto c                = c_.head(m2);
    auto P                = P_.head(m2);
    for (unsigned int i = 0; i < m; ++i)
      {
        if (!law_.compliant())
          c[2 * i] += law_.restitution * gamma_B[2 * i];
        P.segment<2>(2 * i) = warm_[active[i]];
        mu_[i]              = law_.friction_coefficient;
      }
    if (law_.compliant())
      add_compliant_terms(active, m, gamma_B);
    // The step's forms read G_ after the solve as the beam's and slider's
    // Delassus matrix; the compliant law solves on a copy.
    const auto G                  = law_.compliant() ? G_compliant_.topLeftCorner(m2, m2) : G_.topLeftCorner(m2, m2);
    const ProxSolverResult result = solver_.solve(G, c, mu_.head(m), P);
    report_.iterations            = result.iterations;
    report_.residual              = result.residual;
    if (!result.converged)
      throw_solver_failure(t_B, active, m, result);
  }

  void MoreauStepper::add_compliant_terms(const std::array<unsigned int, n_slider_corners> &active,
                                          const unsigned int m,
                                          const Eigen::Matrix<double, max_unknowns, 1> &gamma_B)
  {
    // g_θ = g_M + θ Δt_E γ_E − (1 − θ) Δt_B γ_B, γ_θ = θ γ_E + (1 − θ) γ_B
    // (linear in the step, as the Moreau step itself); θ = ½ is the
    // trapezoidal rule on the spring, which keeps its energy.
    const double theta = beam_.theta();
    const double dt_B = (1. - theta) * dt_, dt_E = theta * dt_;
    const double k = law_.normal_stiffness, c_N = law_.normal_damping;
    const Eigen::Index m2 = 2 * m;
    G_compliant_.topLeftCorner(m2, m2) = G_.topLeftCorner(m2, m2);
    for (unsigned int i = 0; i < m; ++i)
      {
        // The parts of g_θ and γ_θ the start already knows.
        const double g_known = gap_M_[active[i]] - (1. - theta) * dt_B * gamma_B[2 * i];
        const double a       = dt_ * theta * (k * dt_E + c_N);
        const double b       = dt_ * (k * g_known + (1. - theta) * c_N * gamma_B[2 * i]);
        G_compliant_(2 * i, 2 * i) += 1. / a;
        c_[2 * i] += b / a;
      }
  }

  void MoreauStepper::throw_solver_failure(const double t_B, const std::array<unsigned int, n_slider_corners> &active,
                                           const unsigned int m, const ProxSolverResult &result)
  {
    std::string names;
    for (unsigned int i = 0; i < m; ++i)
      names += std::string(i ? ", " : "") + corner_name(active[i]);
    throw ContactSolverFailure(t_B, m, names, result.residual, result.iterations);
  }

  void MoreauStepper::throw_non_finite_end(const double t_B) const
  {
    std::ostringstream msg;
    msg << "non-finite state after the step from t = " << t_B << " s (x_C = " << state_.s[0]
        << " m); the step is not accepted";
    throw NonFiniteState(msg.str());
  }

  void MoreauStepper::accept_step(const Eigen::Vector3d &s_E, const Eigen::Vector3d &v_E,
                                  const std::array<Eigen::Vector2d, n_slider_corners> &new_warm)
  {
    // Swapping hands the buffers over without copying or allocating.
    state_.t = t_origin_ + (steps_taken_ + 1) * dt_;
    state_.q.swap(q_next_);
    state_.u.swap(u_E_);
    state_.s = s_E;
    state_.v = v_E;
    warm_    = new_warm;
    ++steps_taken_;
  }

  // The general form's stages (moreau_step_skeleton.h): everything through
  // the BeamSystem interface and its BeamStep. A model with local kinematics
  // (the FE beam) gives the directions' beam parts on the few coordinates
  // they touch (contact/local_directions.h); the others dense, as columns of
  // W_b. The dense form's products have 2m ≤ 8 columns or rows: written out
  // (contact/contact_products.h) rather than calls into Eigen's product
  // kernels, which cost more than their arithmetic for a reduced model's few
  // modes.
  namespace
  {
    struct General; // the tag of the general form's stages
  } // namespace

  template <>
  class MoreauStepper::Stages<General>
  {
  public:
    explicit Stages(MoreauStepper &stepper)
      : st(stepper)
      , theta(st.beam_.theta())
      , dt_B((1. - theta) * st.dt_)
      , dt_E(theta * st.dt_)
      , local(st.beam_.has_local_kinematics())
    {
      st.local_directions_.clear();
    }

    MoreauStepper &st;
    // The θ-scheme's weights (beam_system.h); θ = 1/2, the midpoint rule,
    // gives 0.5 and 0.5 exactly.
    const double theta;
    const double dt_B; // from the start to the detection configuration
    const double dt_E; // from there to the end
    const bool local;  // the directions' beam parts in local form

    SliderFrame detection_frame(const double t_M, const Eigen::Vector3d &s_M) const
    {
      return SliderGeometry::frame(t_M, st.base_, s_M[2]);
    }

    void free_velocity(const double t_M, const Eigen::Vector3d &s_M, const SliderFrame &frame)
    {
      // Where the left and right corner pairs are (the mean x of upper and
      // lower corner): a beam whose mass follows them needs it first.
      std::array<double, 2> x{};
      for (unsigned int k = 0; k < n_slider_corners; ++k)
        x[k % 2] += 0.5 * (s_M[0] + (frame.cos_beta * st.corner_position_[k][0] -
                                     frame.sin_beta * st.corner_position_[k][1]));
      st.beam_.set_contact_abscissae(x[0], x[1]);
      beam_step.emplace(st.beam_.free_velocity(t_M, st.q_M_, st.state_.u, st.dt_, st.u_free_));
    }

    bool closed_corner(const unsigned int k, const SliderFrame &frame, const Eigen::Vector3d &s_M, const double t_B,
                       const unsigned int m)
    {
      CornerKinematics &corner = st.corner_;
      st.geometry_.evaluate(k, frame, st.beam_, st.q_M_, s_M, corner, CornerDetail::for_step);
      if (!st.corner_is_closed(k, corner.gap, corner.thickness, t_B))
        return false;
      if (local)
        st.local_directions_.set_corner(2 * m, corner);
      else
        {
          st.W_b_.col(2 * m)     = corner.beam_normal;
          st.W_b_.col(2 * m + 1) = corner.beam_tangent;
        }
      st.W_s_.col(2 * m)     = corner.slider_normal;
      st.W_s_.col(2 * m + 1) = corner.slider_tangent;
      st.imposed_[2 * m]     = corner.imposed_normal;
      st.imposed_[2 * m + 1] = corner.imposed_tangent;
      return true;
    }

    // W_bᵀ u + W_sᵀ v + imposed, in the form of the directions' beam parts.
    template <typename Out>
    void relative_velocities(const Eigen::Index m2, const Eigen::VectorXd &u, const Eigen::Vector3d &v, Out &&out) const
    {
      const auto Ws  = st.W_s_.leftCols(m2);
      const auto imp = st.imposed_.head(m2);
      if (local)
        st.local_directions_.relative_velocities(m2, Ws, imp, u, v, out);
      else
        beamslider::relative_velocities(st.W_b_.leftCols(m2), Ws, imp, u, v, out);
    }

    void contact_problem(const Eigen::Index m2, const Eigen::Vector3d &v_B, const Eigen::Vector3d &v_free,
                         const Eigen::Vector3d &inv_mass)
    {
      const auto Wb = st.W_b_.leftCols(m2);
      auto X        = st.X_b_.leftCols(m2);
      auto G        = st.G_.topLeftCorner(m2, m2);
      // S⁻¹ W_b for the dense form (the local one never forms it): for a
      // unit iteration matrix (the explicit reduced model) that is W_b
      // itself, neither solved for nor copied.
      unit_S = !local && beam_step->iteration_matrix_is_identity();
      if (!local && !unit_S)
        beam_step->solve_iteration_matrix(Wb, X);

      // G = W_bᵀ S⁻¹ W_b + W_sᵀ M_s⁻¹ W_s.
      if (local)
        {
          // Wᵀ (Eᵀ S⁻¹ E) W on the K coordinates.
          const unsigned int K = st.local_directions_.n_coordinates();
          const auto W         = st.local_directions_.directions(m2);
          auto S_block         = st.S_block_.topLeftCorner(K, K);
          beam_step->inverse_iteration_matrix_block(st.local_directions_.index(), K, S_block);
          auto SW      = st.SW_.topLeftCorner(K, m2);
          SW.noalias() = S_block.lazyProduct(W);
          G.noalias()  = W.transpose().lazyProduct(SW);
        }
      else if (unit_S && st.beam_.n_dofs() + 2 * m2 < EIGEN_GEMM_TO_COEFFBASED_THRESHOLD)
        // Below Eigen's threshold for its blocked kernel, its product takes
        // each entry as a dot product; with S = I these are symmetric to
        // the bit (the same products, summed in the same order), so half of
        // them suffice.
        for (Eigen::Index j = 0; j < m2; ++j)
          for (Eigen::Index i = 0; i <= j; ++i)
            G(i, j) = G(j, i) = Wb.col(i).dot(Wb.col(j));
      else if (unit_S)
        G.noalias() = Wb.transpose() * Wb;
      else
        G.noalias() = Wb.transpose() * X;
      add_slider_part(st.W_s_.leftCols(m2), inv_mass, G);

      relative_velocities(m2, st.state_.u, v_B, st.gamma_B_.head(m2));
      relative_velocities(m2, st.u_free_, v_free, st.c_.head(m2));
    }

    void add_beam_impulse(const Eigen::Index m2)
    {
      const auto P = st.P_.head(m2);
      if (local)
        {
          const unsigned int K = st.local_directions_.n_coordinates();
          auto y               = st.y_.head(K);
          y.noalias()          = st.local_directions_.directions(m2).lazyProduct(P);
          beam_step->add_inverse_iteration_matrix_times(st.local_directions_.index(), K, y.data(), st.u_E_);
        }
      else if (unit_S)
        add_product(st.W_b_.leftCols(m2), P, st.u_E_);
      else
        add_product(st.X_b_.leftCols(m2), P, st.u_E_);
    }

    // The relative velocities at the mean velocities, from the beam's
    // coordinates.
    void contact_work(const Eigen::Index m2, const Eigen::Vector3d &v_B, const Eigen::Vector3d &v_E)
    {
      st.u_mean_ = st.state_.u;
      st.u_mean_ += st.u_E_;
      st.u_mean_ *= 0.5;
      const Eigen::Vector3d v_mean = 0.5 * (v_B + v_E);
      auto gamma_mean              = st.gamma_mean_.head(m2);
      relative_velocities(m2, st.u_mean_, v_mean, gamma_mean);
      const auto P = st.P_.head(m2);
      for (Eigen::Index i = 0; i < m2 / 2; ++i)
        {
          st.report_.work_impact += P[2 * i] * gamma_mean[2 * i];
          st.report_.work_friction += P[2 * i + 1] * gamma_mean[2 * i + 1];
        }
    }

    void finish_beam() const
    {
      beam_step->work(st.u_E_, st.report_.work_damping, st.report_.work_excitation);
      beam_step->finish(st.state_.q, st.q_next_, st.u_E_);
    }

  private:
    std::optional<BeamStep> beam_step; // from free_velocity on
    bool unit_S = false;               // S = I: S⁻¹ W_b is W_b
  };

  const StepReport &MoreauStepper::step()
  {
    if (modal_)
      return step_explicit_modal();
    Stages<General> stages(*this);
    return take_step(stages);
  }
} // namespace beamslider
