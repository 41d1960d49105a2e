// The reduced-order model with the FE's implicit midpoint step, see
// rom_implicit_beam_system.h.
#include "reduced/rom_implicit_beam_system.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  RomImplicitBeamSystem::RomImplicitBeamSystem(ReducedOrderModel rom, ThicknessProfile thickness,
                                               BaseExcitation excitation)
    : RomBeamSystem(std::move(rom), std::move(thickness), excitation)
  {
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

  void RomImplicitBeamSystem::compute_free_velocity(const double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B,
                                            const double dt, Eigen::VectorXd &u_free)
  {
    if (!(dt > 0.))
      {
        std::ostringstream m;
        m << "implicit reduced model: time step Delta t = " << dt << " s must be positive";
        throw std::invalid_argument(m.str());
      }
    const Eigen::Index N  = n_dofs();
    const double a        = excitation().acceleration(t_M);
    const Eigen::VectorXd &gamma = model().basis().gamma;
    structured_                  = model().has_membrane_form();
    if (structured_ && structured_dt_ != dt)
      prepare_structure(dt);
    Eigen::VectorXd u     = u_B;
    Eigen::VectorXd du(N);
    for (unsigned int it = 1; it <= 30; ++it)
      {
        const Eigen::VectorXd q_bar = q_M + 0.25 * dt * (u - u_B);
        const Eigen::VectorXd R =
          (u - u_B) + dt * (0.5 * c_.cwiseProduct(u_B + u) + omega2_.cwiseProduct(q_bar) +
                            model().nonlinear_force(q_bar) - a * gamma);
        if (structured_)
          {
            // S = D + α K' + β v vᵀ in the eigenbasis of D^-½ K' D^-½.
            const double k = model().is_nonlinear() ? model().basis().membrane_stiffness : 0.;
            Kq_.noalias()  = model().basis().stretch * q_bar;
            const double alpha = 0.125 * dt * dt * k * q_bar.dot(Kq_);
            beta_              = 0.25 * dt * dt * k;
            z_.noalias()       = W_.transpose() * Kq_;
            e_inv_             = (1. + alpha * lambda_.array()).inverse().matrix();
            e_inv_z_           = e_inv_.cwiseProduct(z_);
            sm_denominator_    = 1. + beta_ * z_.dot(e_inv_z_);
            structured_solve(R, du);
          }
        else
          {
            Eigen::MatrixXd S = (0.25 * dt * dt) * model().nonlinear_tangent(q_bar);
            S.diagonal() += Eigen::VectorXd::Ones(N) + 0.5 * dt * c_ + (0.25 * dt * dt) * omega2_;
            lu_.compute(S);
            du = lu_.solve(R);
          }
        factorised_ = true;
        u -= du;
        ++newton_iterations_;
        const double correction = du.norm();
        if (!std::isfinite(correction))
          break;
        if (correction <= 1e-10 * (u.norm() + q_bar.norm() / dt) + 1e-14)
          {
            u_free            = u;
            last_dt_          = dt;
            last_acceleration_ = a;
            last_u_B_         = u_B;
            return;
          }
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
    const Eigen::VectorXd D = Eigen::VectorXd::Ones(n_dofs()) + 0.5 * dt * c_ + (0.25 * dt * dt) * omega2_;
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
    const Eigen::VectorXd u_mean = 0.5 * (last_u_B_ + u_E);
    damping_work                 = -last_dt_ * u_mean.dot(c_.cwiseProduct(u_mean));
    excitation_work              = last_dt_ * last_acceleration_ * model().basis().gamma.dot(u_mean);
  }
} // namespace beamslider
