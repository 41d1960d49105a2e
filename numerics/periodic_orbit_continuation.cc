// Pseudo-arclength continuation of periodic orbits, see periodic_orbits.h.
//
// Unknowns w = (z, ℓ): the scaled state z = y / s and ℓ = λ / lambda_scale.
// The metric ⟨a, b⟩ = a_zᵀ b_z / n + a_ℓ b_ℓ weighs the state's n components
// together like the one parameter. At each accepted point the Jacobian
// J = [M̃ − I, ∂r/∂ℓ] (n + 1 more periods) gives the multipliers and the
// tangent; the corrector of the next point uses it as its chord matrix,
// bordered by the arclength condition.
#include "numerics/newton.h"
#include "numerics/periodic_orbits.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // The linearisation at an accepted point.
    struct PointJacobian
    {
      Eigen::MatrixXd monodromy; // M̃ (scaled)
      Eigen::VectorXd d_lambda;  // ∂r/∂ℓ (scaled)
    };

    PointJacobian linearise(const PeriodMap &map, const OrbitPoint &p, const Eigen::VectorXd &phi,
                            const ContinuationSettings &s)
    {
      const double h = s.shooting.difference_step;
      PointJacobian J;
      J.monodromy = scaled_monodromy(map, p.y, p.lambda, phi, s.shooting.scale, h);
      J.d_lambda  = (map(p.y, p.lambda + h * s.lambda_scale).end - phi).cwiseQuotient(s.shooting.scale) / h;
      return J;
    }

    double inner(const Eigen::VectorXd &a, const Eigen::VectorXd &b)
    {
      const Eigen::Index n = a.size() - 1;
      return a.head(n).dot(b.head(n)) / static_cast<double>(n) + a[n] * b[n];
    }

    // [M̃ − I, ∂r/∂ℓ; metric row of t] — the bordered matrix of both the
    // tangent and the corrector.
    Eigen::MatrixXd bordered(const PointJacobian &J, const Eigen::VectorXd &t)
    {
      const Eigen::Index n = J.monodromy.rows();
      Eigen::MatrixXd B(n + 1, n + 1);
      B.topLeftCorner(n, n)  = J.monodromy - Eigen::MatrixXd::Identity(n, n);
      B.topRightCorner(n, 1) = J.d_lambda;
      B.bottomLeftCorner(1, n) = t.head(n).transpose() / static_cast<double>(n);
      B(n, n)                = t[n];
      return B;
    }

    // The unit tangent (in the metric) continuing the direction of t_old.
    Eigen::VectorXd tangent(const PointJacobian &J, const Eigen::VectorXd &t_old)
    {
      const Eigen::Index n = J.monodromy.rows();
      Eigen::VectorXd rhs  = Eigen::VectorXd::Zero(n + 1);
      rhs[n]               = 1.;
      Eigen::VectorXd t    = bordered(J, t_old).fullPivLu().solve(rhs);
      return t / std::sqrt(inner(t, t));
    }

    // The corrector: chord Newton on r(w) = 0 and ⟨t, w − w_p⟩ = 0.
    class ArclengthCorrector
    {
    public:
      ArclengthCorrector(const PeriodMap &map, const ContinuationSettings &s, const PointJacobian &J,
                         const Eigen::VectorXd &t, const Eigen::VectorXd &w_predicted)
        : map_(map)
        , s_(s)
        , J_(J)
        , t_(t)
        , w_p_(w_predicted)
        , w_(w_predicted)
      {}

      NewtonState evaluate(const bool refresh)
      {
        const Eigen::Index n = w_.size() - 1;
        value_               = map_(y(), lambda());
        R_.resize(n + 1);
        R_.head(n)     = (value_.end - y()).cwiseQuotient(s_.shooting.scale);
        R_[n]          = inner(t_, w_ - w_p_);
        residual_norm_ = R_.head(n).lpNorm<Eigen::Infinity>();
        if (!std::isfinite(R_.lpNorm<Eigen::Infinity>()))
          return NewtonState::diverged;
        if (residual_norm_ <= s_.shooting.tolerance && std::abs(R_[n]) <= s_.shooting.tolerance)
          return NewtonState::converged;
        if (refresh)
          B_ = bordered(J_, t_);
        return NewtonState::go_on;
      }
      void factorise() { lu_.compute(B_); }
      double correct()
      {
        const Eigen::VectorXd dw = lu_.solve(-R_);
        w_ += dw;
        return dw.lpNorm<Eigen::Infinity>();
      }
      bool small(const double) const { return false; }

      Eigen::VectorXd y() const
      {
        const Eigen::Index n = w_.size() - 1;
        return w_.head(n).cwiseProduct(s_.shooting.scale);
      }
      double lambda() const { return w_[w_.size() - 1] * s_.lambda_scale; }
      const Eigen::VectorXd &w() const { return w_; }
      const PeriodMapValue &value() const { return value_; }
      double residual_norm() const { return residual_norm_; }

    private:
      const PeriodMap &map_;
      const ContinuationSettings &s_;
      const PointJacobian &J_;
      const Eigen::VectorXd &t_;
      Eigen::VectorXd w_p_, w_, R_;
      PeriodMapValue value_;
      double residual_norm_ = std::numeric_limits<double>::infinity();
      Eigen::MatrixXd B_;
      Eigen::FullPivLU<Eigen::MatrixXd> lu_;
    };

    Eigen::VectorXd unknowns(const OrbitPoint &p, const ContinuationSettings &s)
    {
      const Eigen::Index n = p.y.size();
      Eigen::VectorXd w(n + 1);
      w.head(n) = p.y.cwiseQuotient(s.shooting.scale);
      w[n]      = p.lambda / s.lambda_scale;
      return w;
    }

    // How many multipliers lie outside the unit circle: real and > 1, real
    // and < −1, and in complex pairs.
    struct OutsideCount
    {
      int positive = 0, negative = 0, complex = 0;
    };
    OutsideCount outside(const Eigen::VectorXcd &mu)
    {
      OutsideCount c;
      for (const auto &m : mu)
        if (std::abs(m) > 1.)
          {
            if (std::abs(m.imag()) > 1e-9 * std::abs(m))
              ++c.complex;
            else if (m.real() > 0.)
              ++c.positive;
            else
              ++c.negative;
          }
      return c;
    }

    // Events between accepted points a and b, with their tangents' λ
    // components ta, tb and the arclength Δ between them.
    void record_events(const OrbitPoint &a, const OrbitPoint &b, const double ta, const double tb, const double delta,
                       const ContinuationSettings &s, const std::size_t after, Branch &branch)
    {
      auto interpolated = [&](const double f) { return ((1. - f) * a.observables + f * b.observables).eval(); };
      if ((ta > 0.) != (tb > 0.))
        {
          // λ'(σ) linear from ta to tb over [0, Δ]: the extremum at its zero.
          const double sigma = ta / (ta - tb) * delta;
          BranchEventRecord e;
          e.kind        = BranchEvent::turning_point;
          e.after_point = after;
          e.lambda      = a.lambda + s.lambda_scale * (ta * sigma + 0.5 * (tb - ta) * sigma * sigma / delta);
          e.observables = interpolated(sigma / delta);
          branch.events.push_back(e);
        }
      const OutsideCount ca = outside(a.multipliers), cb = outside(b.multipliers);
      auto crossing = [&](const BranchEvent kind) {
        BranchEventRecord e;
        e.kind        = kind;
        e.after_point = after;
        e.lambda      = 0.5 * (a.lambda + b.lambda);
        e.observables = interpolated(0.5);
        branch.events.push_back(e);
      };
      if (ca.negative != cb.negative)
        crossing(BranchEvent::period_doubling);
      if (ca.complex != cb.complex)
        crossing(BranchEvent::torus);
    }
  } // namespace

  Branch continue_branch(const PeriodMap &map, const OrbitPoint &start, const ContinuationSettings &settings)
  {
    ContinuationSettings s = settings; // its scale follows the branch (rescale)
    if (s.shooting.scale.size() != start.y.size() || !(s.lambda_scale > 0.) || !(s.min_step > 0.) ||
        !(s.initial_step >= s.min_step) || !(s.max_step >= s.initial_step))
      throw std::invalid_argument("continue_branch: scale of the wrong length, or steps not 0 < min <= initial <= max");
    const Eigen::Index n = start.y.size();
    Branch branch;

    OrbitPoint current = start;
    PeriodMapValue phi = map(current.y, current.lambda);
    current.observables = phi.observables;
    PointJacobian J     = linearise(map, current, phi.end, s);
    current.multipliers = floquet_multipliers(J.monodromy);
    Eigen::VectorXd t_seed = Eigen::VectorXd::Zero(n + 1);
    t_seed[n]              = s.direction >= 0 ? 1. : -1.;
    Eigen::VectorXd t      = tangent(J, t_seed);
    branch.points.push_back(current);
    if (s.on_point)
      s.on_point(current);

    double step = s.initial_step;
    NewtonControl control;
    control.modified       = true;
    control.max_iterations = s.max_corrector_iterations;
    while (branch.points.size() < s.max_points)
      {
        if (s.stop_requested && s.stop_requested())
          {
            branch.end_reason = "interrupted";
            return branch;
          }
        const Eigen::VectorXd w = unknowns(current, s);
        ArclengthCorrector corrector(map, s, J, t, w + step * t);
        NewtonOutcome out;
        std::string failure;
        try
          {
            out = solve_newton(corrector, control);
          }
        catch (const PeriodMapFailure &e)
          {
            failure = e.what();
          }
        OrbitPoint next;
        PointJacobian J_next;
        Eigen::VectorXd t_next;
        bool accepted = failure.empty() && out.converged();
        if (accepted)
          {
            next.lambda      = corrector.lambda();
            next.y           = corrector.y();
            next.observables = corrector.value().observables;
            next.residual    = corrector.residual_norm();
            next.iterations  = out.iterations;
            next.jacobian_change = std::numeric_limits<double>::quiet_NaN(); // not checked along a branch
            try
              {
                J_next = linearise(map, next, corrector.value().end, s);
                t_next = tangent(J_next, t);
              }
            catch (const PeriodMapFailure &e)
              {
                failure  = e.what();
                accepted = false;
              }
            // A tangent that turned by more than 60° in one step has likely
            // jumped to another branch: take a shorter step.
            accepted = accepted && inner(t_next, t) > 0.5;
          }
        if (!accepted)
          {
            step *= 0.5;
            if (step < s.min_step)
              {
                std::ostringstream m;
                m << "the corrector failed at lambda = " << current.lambda << " with the smallest step " << s.min_step
                  << ": " << (failure.empty() ? out.reason() + ", residual " + std::to_string(corrector.residual_norm())
                                              : failure);
                branch.end_reason = m.str();
                return branch;
              }
            continue;
          }
        next.multipliers = floquet_multipliers(J_next.monodromy);
        const double delta = std::sqrt(inner(unknowns(next, s) - w, unknowns(next, s) - w));
        record_events(current, next, t[n], t_next[n], delta, s, branch.points.size() - 1, branch);
        branch.points.push_back(next);
        if (s.on_point)
          s.on_point(next);
        current = next;
        J       = std::move(J_next);
        t       = t_next;
        if (s.rescale)
          {
            // The same tangent and Jacobian in the new scale: z = y / s.
            const Eigen::VectorXd old_scale = s.shooting.scale;
            s.shooting.scale                = s.rescale(current.y);
            const Eigen::VectorXd ratio     = old_scale.cwiseQuotient(s.shooting.scale);
            t.head(n)                       = t.head(n).cwiseProduct(ratio);
            t /= std::sqrt(inner(t, t));
            J.monodromy = ratio.asDiagonal() * J.monodromy * ratio.cwiseInverse().asDiagonal();
            J.d_lambda  = J.d_lambda.cwiseProduct(ratio);
          }
        if (2 * out.iterations <= s.max_corrector_iterations)
          step = std::min(1.5 * step, s.max_step);
        if (current.lambda < s.lambda_min || current.lambda > s.lambda_max)
          {
            branch.end_reason = "left the parameter range";
            return branch;
          }
      }
    branch.end_reason = "point limit reached";
    return branch;
  }
} // namespace beamslider
