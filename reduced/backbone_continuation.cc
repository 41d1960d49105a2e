// The backbone continuation's set-up from the linear mode, its Newton
// corrector and tangent, and the natural continuation in the amplitude.
#include "reduced/backbone_continuation.h"

#include "numerics/newton.h"
#include "numerics/stop_request.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace beamslider
{
  namespace internal
  {
    BackboneContinuation::BackboneContinuation(const ConservativeSystem &system, const BackboneSettings &settings,
                                               Backbone &result)
      : system_(system)
      , settings_(settings)
      , result_(result)
      , residual_(system, result.harmonics, result.n_time_samples)
      , n_(system.n_dofs())
      , s_x_(settings.end_amplitude)
    {
      // The unknowns actually solved for: all (dof, harmonic) pairs, or
      // those the half-period symmetry allows (even_harmonic_dofs).
      const auto &even = settings.hb.even_harmonic_dofs;
      for (unsigned int b = 0; b < result.harmonics.size(); ++b)
        for (unsigned int i = 0; i < n_; ++i)
          if (even.empty() || even[i] == (result.harmonics[b] % 2 == 0))
            active_.push_back(b * n_ + i);
      m_ = active_.size();

      unsigned int first = 0;
      while (result.harmonics[first] != 1)
        ++first;
      // Start: the linear mode, normalised to cᵀφ = 1, at frequency ω_mode.
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(system.stiffness, system.mass);
      if (eig.info() != Eigen::Success)
        throw std::runtime_error("compute_backbone: the linear eigenproblem (K, M) failed; is M positive definite?");
      const double lambda = eig.eigenvalues()[settings.mode];
      if (!(lambda > 0))
        throw std::invalid_argument("compute_backbone: linear eigenvalue ω² = " + std::to_string(lambda) +
                                    " of mode " + std::to_string(settings.mode) + "; must be > 0");
      s_w_                   = std::sqrt(lambda);
      Eigen::VectorXd phi    = eig.eigenvectors().col(settings.mode);
      const double c_phi     = settings.output.dot(phi);
      if (std::abs(c_phi) < 1e-10 * settings.output.norm() * phi.norm())
        throw std::invalid_argument("compute_backbone: the output functional c does not see mode " +
                                    std::to_string(settings.mode) + " (cᵀφ ≈ 0); choose another output");
      phi /= c_phi;
      if (settings.normalise_by_mode)
        s_x_ = settings.end_amplitude * phi.norm();

      // The amplitude functional a = cᵀQ_1, as a row on the scaled unknowns.
      Eigen::VectorXd row = Eigen::VectorXd::Zero(residual_.n_unknowns());
      row.segment(first * n_, n_) = settings.output * s_x_;
      amplitude_row_ = restrict_to_active(row);
      Eigen::VectorXd shape = Eigen::VectorXd::Zero(residual_.n_unknowns());
      shape.segment(first * n_, n_) = phi / s_x_;
      mode_shape_ = restrict_to_active(shape);
    }

    void BackboneContinuation::run()
    {
      // First point, amplitude-constrained, from the linear mode.
      Eigen::VectorXd z = settings_.start_amplitude * mode_shape_;
      z[m_]             = 1.;
      BackbonePoint p;
      if (!correct_at_amplitude(z, settings_.start_amplitude, p))
        throw std::runtime_error(
          "compute_backbone: no convergence at the first point, amplitude " +
          std::to_string(settings_.start_amplitude) + " m, residual " + std::to_string(p.relative_residual) +
          "; reduce start_amplitude");
      store(z, p);
      start_norm_ = z.head(m_).norm();
      if (settings_.method == BackboneSettings::Method::arclength)
        run_arclength(z);
      else
        run_amplitude(z);
    }

    Eigen::VectorXd BackboneContinuation::expand(const Eigen::VectorXd &z) const
    {
      Eigen::VectorXd X = Eigen::VectorXd::Zero(residual_.n_unknowns());
      X(active_)        = z.head(m_) * s_x_;
      return X;
    }

    Eigen::VectorXd BackboneContinuation::restrict_to_active(const Eigen::VectorXd &X_scaled) const
    {
      Eigen::VectorXd z = Eigen::VectorXd::Zero(m_ + 1);
      z.head(m_)        = X_scaled(active_);
      return z;
    }

    void BackboneContinuation::linearise(const Eigen::VectorXd &z, const Eigen::VectorXd &row, Eigen::VectorXd &R,
                                         Eigen::MatrixXd &A)
    {
      Eigen::VectorXd Jw;
      Eigen::MatrixXd JX;
      residual_.evaluate(expand(z), z[m_] * s_w_, R, &JX, &Jw);
      A.resize(m_ + 1, m_ + 1);
      A.topLeftCorner(m_, m_) = JX(active_, active_) * s_x_;
      A.topRightCorner(m_, 1) = Jw(active_) * s_w_;
      A.row(m_)               = row.transpose();
    }

    double BackboneContinuation::relative_residual(const Eigen::VectorXd &z)
    {
      Eigen::VectorXd R;
      const double ref = residual_.evaluate(expand(z), z[m_] * s_w_, R, nullptr, nullptr);
      return R.norm() / std::max(ref, std::numeric_limits<double>::min());
    }

    bool BackboneContinuation::correct(Eigen::VectorXd &z, const Eigen::VectorXd &row, const double rhs,
                                       BackbonePoint &p)
    {
      struct Corrector
      {
        BackboneContinuation &c;
        Eigen::VectorXd &z;
        const Eigen::VectorXd &row;
        const double rhs;
        Eigen::VectorXd R, b;
        Eigen::MatrixXd A;

        NewtonState evaluate(bool)
        {
          stop_if_interrupted(); // Ctrl-C: compute_backbone keeps the converged points
          ++c.result_.n_newton_iterations;
          c.linearise(z, row, R, A);
          b.head(c.m_) = -R(c.active_);
          b[c.m_]      = rhs - row.dot(z);
          return NewtonState::go_on;
        }
        void factorise() {} // solve_newton_matrix factorises A itself
        double correct()
        {
          const Eigen::VectorXd dz = solve_newton_matrix(A, b);
          if (!dz.allFinite())
            return std::numeric_limits<double>::quiet_NaN();
          z += dz;
          const double step = dz.lpNorm<Eigen::Infinity>();
          if (step > 10. || !(z[c.m_] > 0))
            return std::numeric_limits<double>::infinity(); // diverging, or through ω = 0
          return step;
        }
        bool small(const double step) const { return step <= c.settings_.tolerance; }
      } corrector{*this, z, row, rhs, {}, Eigen::VectorXd(m_ + 1), {}};
      NewtonControl control;
      control.max_iterations = settings_.max_newton_iterations;
      p.relative_residual         = std::numeric_limits<double>::infinity();
      const NewtonOutcome outcome = solve_newton(corrector, control);
      if (outcome.stop == NewtonStop::diverged)
        return false;
      // The full residual, inactive rows included: they vanish only if the
      // symmetry assumed is really there.
      p.relative_residual = relative_residual(z);
      p.newton_iterations = outcome.iterations;
      return outcome.converged() && p.relative_residual < 1e-8;
    }

    bool BackboneContinuation::correct_at_amplitude(Eigen::VectorXd &z, const double amplitude, BackbonePoint &p)
    {
      return correct(z, amplitude_row_, amplitude, p);
    }

    Eigen::VectorXd BackboneContinuation::tangent(const Eigen::VectorXd &z, const Eigen::VectorXd &row)
    {
      Eigen::VectorXd R;
      Eigen::MatrixXd A;
      linearise(z, row, R, A);
      Eigen::VectorXd rhs     = Eigen::VectorXd::Zero(m_ + 1);
      rhs[m_]                 = 1.;
      const Eigen::VectorXd t = solve_newton_matrix(A, rhs);
      return t / t.norm();
    }

    void BackboneContinuation::store(const Eigen::VectorXd &z, BackbonePoint &p)
    {
      p.harmonics = expand(z);
      p.segment   = segment_;
      p.omega     = z[m_] * s_w_;
      p.amplitude = amplitude_of(z);
      result_.points.push_back(p);
      const unsigned int h_max = result_.harmonics.back();
      const Eigen::VectorXd y  = output_time_history(result_, result_.points.back(), settings_.output, 16 * h_max + 1);
      result_.points.back().peak = y.cwiseAbs().maxCoeff();
    }

    std::string BackboneContinuation::where(const Eigen::VectorXd &z, const BackbonePoint &p) const
    {
      std::ostringstream s;
      s << "amplitude " << amplitude_of(z) << " m, ω " << z[m_] * s_w_ << " rad/s (last converged: amplitude "
        << result_.points.back().amplitude << " m, ω " << result_.points.back().omega
        << " rad/s), relative residual " << p.relative_residual;
      return s.str();
    }

    void BackboneContinuation::run_amplitude(Eigen::VectorXd z)
    {
      double da = settings_.initial_step * settings_.end_amplitude;
      Eigen::VectorXd z_old;
      double a_old = 0;
      while (true)
        {
          if (result_.points.size() >= settings_.max_points)
            {
              result_.message = "stopped after max_points = " + std::to_string(settings_.max_points) +
                                " points at amplitude " + std::to_string(result_.points.back().amplitude) + " m";
              return;
            }
          const double a   = amplitude_of(z);
          const double a_n = std::min(a + da, settings_.end_amplitude);
          Eigen::VectorXd z_new;
          if (z_old.size() == 0) // first step: scale the first point
            {
              z_new = z;
              z_new.head(m_) *= a_n / a;
            }
          else // secant predictor in a
            z_new = z + (a_n - a) / (a - a_old) * (z - z_old);
          BackbonePoint p;
          if (!correct_at_amplitude(z_new, a_n, p))
            {
              da *= 0.5;
              if (da < settings_.min_step * settings_.end_amplitude)
                {
                  result_.message = "amplitude continuation failed near " + where(z_new, p) +
                                    " (a fold in amplitude, e.g. a loop from modal interaction, stops this "
                                    "method: use Method::arclength)";
                  return;
                }
              continue;
            }
          store(z_new, p);
          z_old = z;
          a_old = a;
          z     = z_new;
          if (a_n >= settings_.end_amplitude)
            {
              result_.completed = true;
              result_.message   = "reached end_amplitude";
              return;
            }
          if (p.newton_iterations <= 3)
            da = std::min(1.5 * da, settings_.max_step * settings_.end_amplitude);
          else if (p.newton_iterations >= 7)
            da *= 0.6;
        }
    }
  } // namespace internal
} // namespace beamslider
