// The reduced-order model as a BeamSystem, see rom_beam_system.h.
#include "reduced/rom_beam_system.h"

#include "reduced/hermite_mode_table.h"

#include <sstream>
#include <typeinfo>
#include <stdexcept>

namespace beamslider
{
  RomBeamSystem::RomBeamSystem(ReducedOrderModel rom, ThicknessProfile thickness, const BaseExcitation excitation)
    : rom_(std::move(rom))
    , thickness_(std::move(thickness))
    , excitation_(excitation)
  {
    const ModalBasis &basis = rom_.basis();
    if (rom_.n_modes() == 0)
      throw std::invalid_argument("reduced model: the modal basis has no modes (N = 0)");
    if (!basis.evaluate)
      throw std::invalid_argument("reduced model: the modal basis has no evaluate function for φ(x), φ'(x)");
    if (!(basis.length > 0.))
      {
        std::ostringstream m;
        m << "reduced model: beam length L = " << basis.length << " m must be positive";
        throw std::invalid_argument(m.str());
      }
    if (!(thickness_.largest() > 0.))
      {
        std::ostringstream m;
        m << "reduced model: beam thickness h = " << thickness_.largest() << " m must be positive";
        throw std::invalid_argument(m.str());
      }
    if (basis.gamma.size() != basis.omega.size() || (basis.omega.array() <= 0.).any())
      throw std::invalid_argument("reduced model: ω must be positive and γ must have one entry per mode");
    omega_max_     = basis.omega.maxCoeff();
    omega_squared_ = basis.omega.array().square();
    for (Eigen::VectorXd *v : {&h_, &scratch_, &last_u_B_, &last_damping_force_, &last_excitation_force_, &u_mean_,
                               &energy_force_, &energy_scratch_})
      v->resize(rom_.n_modes());
  }

  RomBeamSystem RomBeamSystem::from_scene(const Scene &scene, ModalBasis basis)
  {
    return RomBeamSystem(ReducedOrderModel(std::move(basis), scene.damping_ratio,
                                           scene.discretisation.geometric_nonlinearity),
                         scene.beam.thickness_profile(), BaseExcitation::from_scene(scene.excitation));
  }

  void RomBeamSystem::evaluate(const double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const
  {
    const double L = length();
    if (!(x >= 0. && x <= L))
      {
        std::ostringstream m;
        m << "reduced model: beam evaluated at x = " << x << " m, outside the beam [0, " << L << "] m";
        throw std::out_of_range(m.str());
      }
    // φ(x) and φ'(x) are the gradients of w and w': written in place.
    rom_.basis().evaluate(x, out.grad_w, out.grad_dw);
    out.w  = out.grad_w.dot(q);
    out.dw = out.grad_dw.dot(q);
  }

  void RomBeamSystem::evaluate_displacement(const double x, const Eigen::VectorXd &q, double &w, double &dw) const
  {
    if (!rom_.basis().displacement)
      {
        BeamSystem::evaluate_displacement(x, q, w, dw);
        return;
      }
    const double L = length();
    if (!(x >= 0. && x <= L))
      {
        std::ostringstream m;
        m << "reduced model: beam evaluated at x = " << x << " m, outside the beam [0, " << L << "] m";
        throw std::out_of_range(m.str());
      }
    rom_.basis().displacement(x, q, w, dw);
  }

  const ExplicitModalForm *RomBeamSystem::explicit_modal_form() const
  {
    const ModalBasis &basis = rom_.basis();
    if (typeid(*this) != typeid(RomBeamSystem) || !basis.table || basis.table->n_modes != rom_.n_modes() || (rom_.is_nonlinear() && !rom_.has_membrane_form()))
      return nullptr;
    // Filled on each call from this object's own members, so that a copied
    // or moved model never hands out pointers into another one.
    form_.n_modes            = rom_.n_modes();
    form_.omega_squared      = omega_squared_.data();
    form_.damping            = rom_.damping_coefficients().data();
    form_.gamma              = basis.gamma.data();
    form_.stretch            = basis.stretch.data();
    form_.membrane_stiffness = rom_.is_nonlinear() ? basis.membrane_stiffness : 0.;
    form_.excitation         = excitation_;
    form_.thickness          = &thickness_;
    form_.n_intervals        = basis.table->n_intervals;
    form_.vertices           = basis.table->vertices.data();
    form_.coefficients       = basis.table->coefficients.data();
    return &form_;
  }

  double RomBeamSystem::max_stable_time_step() const { return 2. / omega_max_; }

  void RomBeamSystem::compute_free_velocity(const double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B,
                                    const double dt, Eigen::VectorXd &u_free)
  {
    const double limit = max_stable_time_step();
    if (!(dt > 0.) || dt > limit)
      {
        std::ostringstream m;
        m << "reduced model: time step Delta t = " << dt << " s is outside the allowed range (0, " << limit
          << "] s; the explicit midpoint step is stable only for Delta t <= 2/omega_max with omega_max = "
          << omega_max_ << " rad/s of the highest kept mode";
        throw std::invalid_argument(m.str());
      }
    // In place, into storage sized once: the step allocates nothing. The
    // operations and their order are those of the plain formula
    //   h = (−c∘u_B − ω²∘q_M) − f_nl(q_M) + γ ẅ0,   c_n = 2 D ω_n (or 0),
    //   u_free = u_B + Δt h,
    // so that the results stay the same to the bit; the membrane force
    // f_nl = N K'q with N = ½ k_ax qᵀK'q is formed in the same pass.
    const double a = excitation_.acceleration(t_M);
    if (rom_.is_nonlinear() && !rom_.has_membrane_form())
      {
        // Explicit cubic terms: their own loop (ReducedOrderModel).
        const auto w = rom_.basis().omega.array(); // an expression, not a copy
        last_damping_force_.array() = -(rom_.damping_coefficients().array() * u_B.array());
        last_excitation_force_      = rom_.basis().gamma * a;
        h_.array()                  = last_damping_force_.array() - w * w * q_M.array();
        rom_.add_nonlinear_force(q_M, -1., h_, scratch_);
        h_ += last_excitation_force_;
        u_free = u_B;
        u_free.noalias() += dt * h_;
      }
    else
      {
        const bool membrane = rom_.is_nonlinear();
        // −N, the factor of K'q (in scratch_) in −f_nl
        const double minus_N = membrane ? -rom_.membrane_axial_force(q_M, scratch_) : 0.;
        const Eigen::VectorXd &omega = rom_.basis().omega, &gamma = rom_.basis().gamma,
                              &damping = rom_.damping_coefficients();
        u_free.resize(u_B.size()); // a no-op at the right size
        for (Eigen::Index n = 0; n < u_B.size(); ++n)
          {
            const double damping_force    = -(damping[n] * u_B[n]);
            const double excitation_force = gamma[n] * a;
            double h                      = damping_force - omega[n] * omega[n] * q_M[n];
            if (membrane)
              h += minus_N * scratch_[n];
            h += excitation_force;
            u_free[n]                 = u_B[n] + dt * h;
            last_damping_force_[n]    = damping_force;
            last_excitation_force_[n] = excitation_force;
          }
      }
    last_dt_  = dt;
    last_u_B_ = u_B;
  }

  BeamFieldSamples RomBeamSystem::sample_fields(const Eigen::VectorXd &q) const
  {
    BeamFieldSamples g = sample_by_evaluation(*this, q, 129);
    // N = k_ax · ½∫w'² dx, the integral by the trapezoidal rule.
    double stretch = 0;
    for (std::size_t i = 1; i < g.x.size(); ++i)
      stretch += 0.25 * (g.dw[i] * g.dw[i] + g.dw[i - 1] * g.dw[i - 1]) * (g.x[i] - g.x[i - 1]);
    const double k_ax = rom_.is_nonlinear() ? rom_.basis().membrane_stiffness : 0.;
    g.axial_force.assign(g.x.size(), k_ax * stretch);
    return g;
  }

  double RomBeamSystem::energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const
  {
    // Called at every period's start and end: into storage sized once, so
    // that a run allocates nothing after its start.
    const auto w = rom_.basis().omega.array(); // an expression, not a copy
    energy_force_.setZero();
    rom_.add_nonlinear_force(q, 1., energy_force_, energy_scratch_);
    return 0.5 * u.squaredNorm() + 0.5 * (w * w * q.array().square()).sum() + 0.25 * q.dot(energy_force_);
  }

  void RomBeamSystem::compute_step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const
  {
    u_mean_         = 0.5 * (last_u_B_ + u_E); // into storage sized once
    damping_work    = last_dt_ * last_damping_force_.dot(u_mean_);
    excitation_work = last_dt_ * last_excitation_force_.dot(u_mean_);
  }
} // namespace beamslider
