// The reduced-order model with the FE's implicit midpoint step, see
// rom_implicit_beam_system.h.
#include "reduced/rom_implicit_beam_system.h"

#include "numerics/newton.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  RomImplicitBeamSystem::RomImplicitBeamSystem(ReducedOrderModel rom, ThicknessProfile thickness,
                                               BaseExcitation excitation, const double theta)
    : RomBeamSystem(std::move(rom), std::move(thickness), excitation)
    , theta_(theta)
  {
    if (!(theta >= 0.5 && theta <= 1.))
      throw std::invalid_argument("implicit reduced model: theta = " + std::to_string(theta) +
                                  " is outside [0.5, 1] (0.5: the midpoint rule; above it damps the modes the step "
                                  "cannot resolve)");
    const Eigen::ArrayXd w = model().basis().omega.array();
    c_                     = model().damping_coefficients();
    omega2_                = (w * w).matrix();
  }

  RomImplicitBeamSystem RomImplicitBeamSystem::from_scene(const Scene &scene, ModalBasis basis)
  {
    return RomImplicitBeamSystem(ReducedOrderModel(std::move(basis), scene.damping_ratio,
                                                   scene.discretisation.geometric_nonlinearity),
                                 scene.beam.thickness_profile(), BaseExcitation::from_scene(scene.excitation));
  }

  // One step as a Newton problem (numerics/newton.h), full Newton on
  // R(u) = (u − u_B) + Δt [C (u_B + u)/2 + Ω² q̄ + f_nl(q̄) − a γ],
  // q̄ = q_M + Δt/4 (u − u_B), with S = ∂R/∂u factorised every iteration
  // (θ = ½; the θ-method's terms in the header).
  struct RomImplicitBeamSystem::NewtonStep
  {
    RomImplicitBeamSystem &system;
    const Eigen::VectorXd &q_M, &u_B;
    const double dt, a;
    Eigen::VectorXd u, du, q_bar, R;

    NewtonState evaluate(bool)
    {
      const double theta = system.theta_;
      if (theta == 0.5)
        {
          q_bar = q_M + 0.25 * dt * (u - u_B);
          R     = (u - u_B) + dt * (0.5 * system.c_.cwiseProduct(u_B + u) + system.omega2_.cwiseProduct(q_bar) +
                                system.model().nonlinear_force(q_bar) - a * system.model().basis().gamma);
          return NewtonState::go_on;
        }
      q_bar = q_M + (theta * theta * dt) * (u - u_B) + ((2. * theta - 1.) * dt) * u_B;
      R     = (u - u_B) + dt * (system.c_.cwiseProduct(theta * u + (1. - theta) * u_B) +
                            system.omega2_.cwiseProduct(q_bar) + system.model().nonlinear_force(q_bar) -
                            a * system.model().basis().gamma);
      return NewtonState::go_on;
    }

    void factorise()
    {
      const ReducedOrderModel &model = system.model();
      if (system.structured_)
        {
          // S = D + α K' + β v vᵀ in the eigenbasis of D^-½ K' D^-½.
          // α = θ²Δt² k/2 q̄ᵀK'q̄, β = θ²Δt² k (θ = ½: Δt²k/8 and Δt²k/4).
          const double k          = model.is_nonlinear() ? model.basis().membrane_stiffness : 0.;
          const double theta      = system.theta_;
          system.Kq_.noalias()    = model.basis().stretch * q_bar;
          const double alpha      = theta == 0.5 ? 0.125 * dt * dt * k * q_bar.dot(system.Kq_)
                                                 : 0.5 * theta * theta * dt * dt * k * q_bar.dot(system.Kq_);
          system.beta_            = theta * theta * dt * dt * k;
          system.z_.noalias()     = system.W_.transpose() * system.Kq_;
          system.e_inv_           = (1. + alpha * system.lambda_.array()).inverse().matrix();
          system.e_inv_z_         = system.e_inv_.cwiseProduct(system.z_);
          system.sm_denominator_  = 1. + system.beta_ * system.z_.dot(system.e_inv_z_);
        }
      else
        {
          const Eigen::Index N = system.n_dofs();
          const double theta   = system.theta_;
          Eigen::MatrixXd S    = (theta * theta * dt * dt) * model.nonlinear_tangent(q_bar);
          S.diagonal() += Eigen::VectorXd::Ones(N) + theta * dt * system.c_ + (theta * theta * dt * dt) * system.omega2_;
          system.lu_.compute(S);
        }
      system.factorised_ = true;
    }

    double correct()
    {
      if (system.structured_)
        system.structured_solve(R, du);
      else
        du = system.lu_.solve(R);
      u -= du;
      ++system.newton_iterations_;
      return du.norm();
    }

    bool small(const double correction) const
    {
      return correction <= 1e-10 * (u.norm() + q_bar.norm() / dt) + 1e-14;
    }
  };

  void RomImplicitBeamSystem::compute_free_velocity(const double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B,
                                            const double dt, Eigen::VectorXd &u_free)
  {
    if (!(dt > 0.))
      {
        std::ostringstream m;
        m << "implicit reduced model: time step Delta t = " << dt << " s must be positive";
        throw std::invalid_argument(m.str());
      }
    structured_ = model().has_membrane_form();
    if (structured_ && structured_dt_ != dt)
      prepare_structure(dt);
    // The smooth forces act at t_B + θΔt = t_M + (2θ − 1)Δt (t_M for θ = ½).
    const double t_load = theta_ == 0.5 ? t_M : t_M + (2. * theta_ - 1.) * dt;
    NewtonStep step{*this, q_M, u_B, dt, excitation().acceleration(t_load), u_B, Eigen::VectorXd(n_dofs()), {}, {}};
    NewtonControl control;
    control.max_iterations = 30;
    if (solve_newton(step, control).converged())
      {
        u_free             = step.u;
        last_dt_           = dt;
        last_acceleration_ = step.a;
        last_u_B_          = u_B;
        return;
      }
    std::ostringstream m;
    m << "implicit reduced model: Newton did not converge in 30 iterations at t_M = " << t_M << " s (Delta t = " << dt
      << " s)";
    throw std::runtime_error(m.str());
  }

  void RomImplicitBeamSystem::apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                                     Eigen::Ref<Eigen::MatrixXd> X) const
  {
    if (!factorised_)
      throw std::logic_error("implicit reduced model: iteration matrix used before its first factorisation");
    if (!structured_)
      {
        X = lu_.solve(B);
        return;
      }
    for (Eigen::Index j = 0; j < B.cols(); ++j)
      structured_solve(B.col(j), X.col(j));
  }

  void RomImplicitBeamSystem::prepare_structure(const double dt)
  {
    const Eigen::VectorXd D = Eigen::VectorXd::Ones(n_dofs()) + theta_ * dt * c_ + (theta_ * theta_ * dt * dt) * omega2_;
    d_inv_sqrt_             = D.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd A = d_inv_sqrt_.asDiagonal() * model().basis().stretch * d_inv_sqrt_.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(A);
    if (eigen.info() != Eigen::Success)
      throw std::runtime_error("implicit reduced model: eigendecomposition of the scaled stretch matrix K' failed");
    lambda_        = eigen.eigenvalues();
    W_             = d_inv_sqrt_.asDiagonal() * eigen.eigenvectors();
    work_.resize(n_dofs());
    structured_dt_ = dt;
  }

  void RomImplicitBeamSystem::structured_solve(const Eigen::Ref<const Eigen::VectorXd> &r,
                                               Eigen::Ref<Eigen::VectorXd> x) const
  {
    // S⁻¹ = W (E + β z zᵀ)⁻¹ Wᵀ with W = D^-½ V, by Sherman–Morrison.
    work_.noalias() = W_.transpose() * r;
    work_           = e_inv_.cwiseProduct(work_);
    work_ -= (beta_ * z_.dot(work_) / sm_denominator_) * e_inv_z_;
    x.noalias() = W_ * work_;
  }

  void RomImplicitBeamSystem::compute_step_work(const Eigen::VectorXd &u_E, double &damping_work,
                                        double &excitation_work) const
  {
    if (last_u_B_.size() != u_E.size())
      {
        damping_work = excitation_work = 0.;
        return;
      }
    // The damping impulse Δt C u_θ times ū (θ = ½: u_θ = ū).
    const Eigen::VectorXd u_mean = 0.5 * (last_u_B_ + u_E);
    damping_work                 = theta_ == 0.5
                                     ? -last_dt_ * u_mean.dot(c_.cwiseProduct(u_mean))
                                     : -last_dt_ * u_mean.dot(c_.cwiseProduct((1. - theta_) * last_u_B_ + theta_ * u_E));
    excitation_work              = last_dt_ * last_acceleration_ * model().basis().gamma.dot(u_mean);
  }
} // namespace beamslider
