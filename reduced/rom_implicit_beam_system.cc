// The reduced-order model with the FE's implicit midpoint step, see
// rom_implicit_beam_system.h.
#include "reduced/rom_implicit_beam_system.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  RomImplicitBeamSystem::RomImplicitBeamSystem(ReducedOrderModel rom, const double thickness,
                                               BaseExcitation excitation)
    : RomBeamSystem(std::move(rom), thickness, excitation)
  {
    const Eigen::ArrayXd w = model().basis().omega.array();
    c_                     = (2. * model().damping_ratio() * w).matrix();
    omega2_                = (w * w).matrix();
  }

  RomImplicitBeamSystem RomImplicitBeamSystem::from_scene(const Scene &scene, ModalBasis basis)
  {
    return RomImplicitBeamSystem(ReducedOrderModel(std::move(basis), scene.damping_ratio,
                                                   scene.discretisation.geometric_nonlinearity),
                                 scene.beam.thickness, BaseExcitation::from_scene(scene.excitation));
  }

  void RomImplicitBeamSystem::free_velocity(const double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B,
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
    Eigen::VectorXd u     = u_B;
    for (unsigned int it = 1; it <= 30; ++it)
      {
        const Eigen::VectorXd q_bar = q_M + 0.25 * dt * (u - u_B);
        const Eigen::VectorXd R =
          (u - u_B) + dt * (0.5 * c_.cwiseProduct(u_B + u) + omega2_.cwiseProduct(q_bar) +
                            model().nonlinear_force(q_bar) - a * gamma);
        Eigen::MatrixXd S = (0.25 * dt * dt) * model().nonlinear_tangent(q_bar);
        S.diagonal() += Eigen::VectorXd::Ones(N) + 0.5 * dt * c_ + (0.25 * dt * dt) * omega2_;
        lu_.compute(S);
        factorised_               = true;
        const Eigen::VectorXd du  = lu_.solve(R);
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

  void RomImplicitBeamSystem::solve_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                                     Eigen::Ref<Eigen::MatrixXd> X) const
  {
    if (!factorised_)
      throw std::logic_error("implicit reduced model: solve_iteration_matrix called before free_velocity");
    X = lu_.solve(B);
  }

  void RomImplicitBeamSystem::step_work(const Eigen::VectorXd &u_E, double &damping_work,
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
