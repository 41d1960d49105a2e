// Shooting and pseudo-arclength continuation of periodic orbits, see
// periodic_orbits.h. Both Newton iterations are Problems of the project's one
// Newton driver (numerics/newton.h).
#include "numerics/periodic_orbits.h"
#include "numerics/newton.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace beamslider
{
  namespace
  {
    constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

    // The Jacobian check: how far the monodromy matrices from two difference
    // steps disagree, relative to the larger entry.
    double jacobian_change(const PeriodMap &map, const Eigen::VectorXd &y, const double lambda,
                           const Eigen::VectorXd &phi, const Eigen::VectorXd &scale, const double h,
                           const Eigen::MatrixXd &at_h)
    {
      const Eigen::MatrixXd at_10h = scaled_monodromy(map, y, lambda, phi, scale, 10. * h);
      const double size            = std::max(at_h.cwiseAbs().maxCoeff(), 1e-300);
      return (at_10h - at_h).cwiseAbs().maxCoeff() / size;
    }

    // Newton on the scaled fixed-point residual r(z) = (Φ(y) − y)/s at fixed
    // λ, damped by halving a step until the residual decreases.
    class FixedPointProblem
    {
    public:
      FixedPointProblem(const PeriodMap &map, const Eigen::VectorXd &y, const double lambda,
                        const ShootingSettings &settings)
        : map_(map)
        , settings_(settings)
        , lambda_(lambda)
        , y_(y)
      {}

      NewtonState evaluate(const bool refresh)
      {
        if (!have_value_)
          set_value(map_(y_, lambda_));
        if (residual_norm_ <= settings_.tolerance)
          return NewtonState::converged;
        if (!std::isfinite(residual_norm_))
          {
            reason_ = "the period's end state is not finite";
            return NewtonState::diverged;
          }
        if (refresh)
          {
            monodromy_ = scaled_monodromy(map_, y_, lambda_, value_.end, settings_.scale, settings_.difference_step);
            A_         = monodromy_ - Eigen::MatrixXd::Identity(y_.size(), y_.size());
          }
        return NewtonState::go_on;
      }

      void factorise() { lu_.compute(A_); }

      double correct()
      {
        const Eigen::VectorXd dz = lu_.solve(-r_);
        double alpha             = 1.;
        for (unsigned int k = 0; k <= settings_.max_halvings; ++k, alpha *= 0.5)
          {
            const Eigen::VectorXd y_try = y_ + alpha * dz.cwiseProduct(settings_.scale);
            try
              {
                PeriodMapValue v = map_(y_try, lambda_);
                const double n   = (v.end - y_try).cwiseQuotient(settings_.scale).lpNorm<Eigen::Infinity>();
                if (std::isfinite(n) && (n < residual_norm_ || k == settings_.max_halvings))
                  {
                    if (!(n < residual_norm_))
                      {
                        std::ostringstream m;
                        m << "no damping of the Newton step reduced the residual " << residual_norm_ << " (last try "
                          << n << " at step fraction " << alpha << ")";
                        reason_ = m.str();
                        return not_a_number;
                      }
                    y_ = y_try;
                    set_value(std::move(v));
                    return alpha * dz.lpNorm<Eigen::Infinity>();
                  }
              }
            catch (const PeriodMapFailure &e)
              {
                reason_ = std::string("the period map failed on every damped step: ") + e.what();
              }
          }
        return not_a_number;
      }

      bool small(const double) const { return false; } // converged on the residual, in evaluate

      const Eigen::VectorXd &y() const { return y_; }
      const PeriodMapValue &value() const { return value_; }
      double residual_norm() const { return residual_norm_; }
      const Eigen::MatrixXd &monodromy() const { return monodromy_; }
      const std::string &reason() const { return reason_; }

    private:
      void set_value(PeriodMapValue v)
      {
        value_         = std::move(v);
        r_             = (value_.end - y_).cwiseQuotient(settings_.scale);
        residual_norm_ = r_.lpNorm<Eigen::Infinity>();
        have_value_    = true;
      }

      const PeriodMap &map_;
      const ShootingSettings &settings_;
      double lambda_;
      Eigen::VectorXd y_, r_;
      PeriodMapValue value_;
      bool have_value_      = false;
      double residual_norm_ = std::numeric_limits<double>::infinity();
      Eigen::MatrixXd monodromy_, A_;
      Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
      std::string reason_;
    };
  } // namespace

  Eigen::MatrixXd scaled_monodromy(const PeriodMap &map, const Eigen::VectorXd &y, const double lambda,
                                   const Eigen::VectorXd &phi_y, const Eigen::VectorXd &scale, const double h)
  {
    const Eigen::Index n = y.size();
    Eigen::MatrixXd M(n, n);
    for (Eigen::Index j = 0; j < n; ++j)
      {
        Eigen::VectorXd y_j = y;
        y_j[j] += h * scale[j];
        M.col(j) = (map(y_j, lambda).end - phi_y).cwiseQuotient(scale) / h;
      }
    return M;
  }

  Eigen::VectorXcd floquet_multipliers(const Eigen::MatrixXd &monodromy)
  {
    Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(monodromy, false).eigenvalues();
    std::sort(mu.data(), mu.data() + mu.size(),
              [](const std::complex<double> &a, const std::complex<double> &b) { return std::abs(a) > std::abs(b); });
    return mu;
  }

  ShootingOutcome shoot(const PeriodMap &map, const Eigen::VectorXd &y, const double lambda,
                        const ShootingSettings &settings)
  {
    if (settings.scale.size() != y.size() || !(settings.scale.array() > 0.).all())
      throw std::invalid_argument("shoot: the scale must have one positive entry per unknown");
    FixedPointProblem problem(map, y, lambda, settings);
    NewtonControl control;
    control.max_iterations = settings.max_iterations;
    ShootingOutcome out;
    NewtonOutcome newton;
    try
      {
        newton = solve_newton(problem, control);
      }
    catch (const PeriodMapFailure &e)
      {
        out.reason = std::string("the period map failed at the start: ") + e.what();
        return out;
      }
    out.point.lambda      = lambda;
    out.point.y           = problem.y();
    out.point.observables = problem.value().observables;
    out.point.residual    = problem.residual_norm();
    out.point.iterations  = newton.iterations;
    out.converged         = newton.converged();
    if (!out.converged)
      {
        std::ostringstream m;
        m << (newton.stop == NewtonStop::diverged ? problem.reason() : newton.reason()) << " after "
          << newton.iterations << " corrections, residual " << problem.residual_norm();
        out.reason = m.str();
        return out;
      }
    const Eigen::MatrixXd M =
      scaled_monodromy(map, out.point.y, lambda, problem.value().end, settings.scale, settings.difference_step);
    out.point.multipliers = floquet_multipliers(M);
    out.point.jacobian_change =
      jacobian_change(map, out.point.y, lambda, problem.value().end, settings.scale, settings.difference_step, M);
    return out;
  }

  unsigned int detect_period_count(const PeriodMap &map, Eigen::VectorXd &y, const double lambda,
                                   const Eigen::VectorXd &scale, const unsigned int transient,
                                   const unsigned int max_k, const double tolerance,
                                   std::vector<Eigen::VectorXd> *section)
  {
    for (unsigned int i = 0; i < transient; ++i)
      y = map(y, lambda).end;
    std::vector<Eigen::VectorXd> points{y};
    for (unsigned int k = 1; k <= max_k; ++k)
      points.push_back(map(points.back(), lambda).end);
    if (section)
      *section = points;
    for (unsigned int k = 1; k <= max_k; ++k)
      if ((points[k] - points[0]).cwiseQuotient(scale).lpNorm<Eigen::Infinity>() <= tolerance)
        return k;
    return 0;
  }

  double largest_lyapunov_exponent(const PeriodMap &map, Eigen::VectorXd y, const double lambda,
                                   const Eigen::VectorXd &scale, const unsigned int periods, const double separation,
                                   const unsigned int discard)
  {
    // The first separation along every scaled unknown alike.
    const double n       = static_cast<double>(y.size());
    Eigen::VectorXd near = y + scale * (separation / std::sqrt(n));
    double sum           = 0;
    for (unsigned int i = 0; i < discard + periods; ++i)
      {
        y                        = map(y, lambda).end;
        near                     = map(near, lambda).end;
        const double growth      = (near - y).cwiseQuotient(scale).norm() / separation;
        if (!(growth > 0.) || !std::isfinite(growth))
          return growth == 0. ? -std::numeric_limits<double>::infinity() : not_a_number;
        if (i >= discard)
          sum += std::log(growth);
        near = y + (near - y) / growth;
      }
    return sum / periods;
  }

  std::string to_string(const BranchEvent event)
  {
    switch (event)
      {
        case BranchEvent::turning_point:
          return "turning point";
        case BranchEvent::period_doubling:
          return "period doubling";
        case BranchEvent::torus:
          return "torus (Neimark-Sacker)";
      }
    return "";
  }
} // namespace beamslider
