// The attached-slider reduced model, see attached_slider_model.h.
#include "reduced/attached_slider_model.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <complex>

namespace beamslider
{
  AttachedSliderModel::AttachedSliderModel(const ReducedOrderModel &rom, const double slider_mass,
                                           const double slider_inertia, const double gravity,
                                           const BaseExcitation &base, const double thickness)
    : rom_(rom)
    , mass_(slider_mass)
    , inertia_(slider_inertia)
    , gravity_(gravity)
    , thickness_(thickness)
    , base_(base)
  {
    if (!(base.angular_frequency > 0.))
      throw std::invalid_argument("the attached-slider model needs a harmonic excitation (a positive frequency)");
    const double omega_max = rom.basis().omega.maxCoeff();
    steps_ = std::max(400u, static_cast<unsigned int>(std::ceil(base.period() * omega_max / 0.5)));
  }

  std::vector<std::string> AttachedSliderModel::observable_names() { return {"amplitude_over_h", "mean_fx_N"}; }

  PeriodMapValue AttachedSliderModel::operator()(const Eigen::VectorXd &y, const double x_over_L) const
  {
    if (!(x_over_L >= 0. && x_over_L <= 1.))
      throw PeriodMapFailure("the slider's position x_C/L = " + std::to_string(x_over_L) + " is off the beam [0, 1]");
    const ModalBasis &basis = rom_.basis();
    const Eigen::Index n    = rom_.n_modes();
    Eigen::VectorXd phi, dphi, phi_c, dphi_c;
    basis.evaluate(x_over_L * basis.length, phi, dphi);
    basis.evaluate(0.5 * basis.length, phi_c, dphi_c);
    const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n) + mass_ * phi * phi.transpose() +
                              inertia_ * dphi * dphi.transpose();
    const Eigen::LDLT<Eigen::MatrixXd> mass(M);

    // q̈ from (q, q̇) at t; also the slider's absolute vertical acceleration.
    auto acceleration = [&](const double t, const Eigen::VectorXd &q, const Eigen::VectorXd &v, double &slider_z) {
      const double a0   = base_.acceleration(t);
      Eigen::VectorXd f = basis.gamma * a0 - mass_ * (a0 + gravity_) * phi - rom_.linear_force(q, v) -
                          rom_.nonlinear_force(q);
      const Eigen::VectorXd a = mass.solve(f);
      slider_z                = a0 + phi.dot(a);
      return a;
    };

    const double T = base_.period(), h = T / steps_;
    Eigen::VectorXd q = y.head(n), v = y.tail(n);
    double w_min = phi_c.dot(q), w_max = w_min, fx_sum = 0;
    // F_x = −m (z̈ + g) w'(x_C) at each node, summed by the trapezoidal rule
    // (periodic: every node once).
    for (unsigned int i = 0; i < steps_; ++i)
      {
        const double t = i * h;
        double z1, z2, z3, z4;
        const Eigen::VectorXd a1 = acceleration(t, q, v, z1);
        fx_sum += -mass_ * (z1 + gravity_) * dphi.dot(q);
        const Eigen::VectorXd q2 = q + 0.5 * h * v, v2 = v + 0.5 * h * a1;
        const Eigen::VectorXd a2 = acceleration(t + 0.5 * h, q2, v2, z2);
        const Eigen::VectorXd q3 = q + 0.5 * h * v2, v3 = v + 0.5 * h * a2;
        const Eigen::VectorXd a3 = acceleration(t + 0.5 * h, q3, v3, z3);
        const Eigen::VectorXd q4 = q + h * v3, v4 = v + h * a3;
        const Eigen::VectorXd a4 = acceleration(t + h, q4, v4, z4);
        q += h / 6. * (v + 2. * v2 + 2. * v3 + v4);
        v += h / 6. * (a1 + 2. * a2 + 2. * a3 + a4);
        const double w = phi_c.dot(q);
        w_min          = std::min(w_min, w);
        w_max          = std::max(w_max, w);
      }
    PeriodMapValue out;
    out.end.resize(2 * n);
    out.end << q, v;
    if (!out.end.allFinite())
      throw PeriodMapFailure("the attached-slider model's state is not finite after one period");
    out.observables.resize(2);
    out.observables << 0.5 * (w_max - w_min) / thickness_, fx_sum / steps_;
    return out;
  }

  Eigen::VectorXd AttachedSliderModel::scale(const Eigen::VectorXd &y) const
  {
    const Eigen::Index n = rom_.n_modes();
    Eigen::VectorXd s(2 * n);
    s.head(n).setConstant(std::max(y.head(n).cwiseAbs().maxCoeff(), 1e-30));
    s.tail(n).setConstant(std::max(y.tail(n).cwiseAbs().maxCoeff(), 1e-30));
    return s;
  }

  Eigen::VectorXd AttachedSliderModel::linear_response(const double x_over_L) const
  {
    // (−Ω² M + iΩ C + K) Q = γ − m φ for ẅ₀ = Re(â e^{iΩt}) with the phase of
    // base_.acceleration: ẅ₀(t) = −â cos Ωt.
    const ModalBasis &basis = rom_.basis();
    const Eigen::Index n    = rom_.n_modes();
    Eigen::VectorXd phi, dphi;
    basis.evaluate(x_over_L * basis.length, phi, dphi);
    const double W = base_.angular_frequency;
    using C        = std::complex<double>;
    Eigen::MatrixXcd A =
      (-W * W * (Eigen::MatrixXd::Identity(n, n) + mass_ * phi * phi.transpose() + inertia_ * dphi * dphi.transpose()))
        .cast<C>();
    for (Eigen::Index k = 0; k < n; ++k)
      A(k, k) += C(basis.omega[k] * basis.omega[k], W * rom_.damping_coefficients()[k]);
    const Eigen::VectorXcd F = (-base_.acceleration_amplitude * (basis.gamma - mass_ * phi)).cast<C>();
    const Eigen::VectorXcd Q = A.partialPivLu().solve(F);
    Eigen::VectorXd y(2 * n);
    y.head(n) = Q.real();                  // q(0) = Re Q
    y.tail(n) = (C(0., W) * Q).real();     // q̇(0) = Re(iΩ Q)
    return y;
  }
} // namespace beamslider
