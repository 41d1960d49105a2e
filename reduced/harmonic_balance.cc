// Harmonic balance backbones with AFT and pseudo-arclength continuation; see
// harmonic_balance.h for the equations, the choice of harmonics and samples.
#include "reduced/harmonic_balance.h"
#include "numerics/elapsed.h"

#include "reduced/backbone_tongues.h"

#include "numerics/stop_request.h"
#include "numerics/newton.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <chrono>
#include <limits>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace beamslider
{
  namespace
  {
    // x = A⁻¹ b for the continuation's Newton matrix. An FE system's matrix
    // is sparse: each (harmonic, harmonic) block is the FE tangent's band
    // (the default beam: 129 DoFs × 11 harmonics, half of them active, ~700
    // unknowns, a row coupling each DoF's band in ~6 harmonics), and a
    // sparse LU with a fill-reducing ordering costs a fraction of a dense
    // one. A modal system's matrix is dense, and there the dense LU is
    // faster; the choice is by the fraction of nonzeros. Both pivot partially
    // (SparseLU's default threshold 1); a singular matrix gives a
    // non-finite x, which the callers reject.
    Eigen::VectorXd solve_newton_matrix(const Eigen::MatrixXd &A, const Eigen::VectorXd &b)
    {
      const double nonzero_fraction = double((A.array() != 0.).count()) / double(A.size());
      if (nonzero_fraction > 0.25)
        return A.partialPivLu().solve(b);
      const Eigen::SparseMatrix<double> S = A.sparseView();
      Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
      lu.compute(S);
      if (lu.info() != Eigen::Success)
        return Eigen::VectorXd::Constant(b.size(), std::numeric_limits<double>::quiet_NaN());
      return lu.solve(b);
    }

    // The HB residual R(Q, ω) of the file header, its Jacobian ∂R/∂Q and
    // ∂R/∂ω, by AFT on N_t equispaced samples of one period.
    class HarmonicBalanceResidual
    {
    public:
      HarmonicBalanceResidual(const ConservativeSystem &system, std::vector<unsigned int> harmonics,
                              const unsigned int n_time_samples)
        : system_(system)
        , harmonics_(std::move(harmonics))
        , n_(system.n_dofs())
        , nb_(harmonics_.size())
        , cos_(nb_, n_time_samples)
        , weighted_cos_(nb_, n_time_samples)
      {
        const double pi = std::acos(-1.);
        for (unsigned int b = 0; b < nb_; ++b)
          for (unsigned int i = 0; i < n_time_samples; ++i)
            {
              cos_(b, i)          = std::cos(harmonics_[b] * 2. * pi * i / n_time_samples);
              weighted_cos_(b, i) = weight(b) / n_time_samples * cos_(b, i);
            }
        // ∂F_b/∂Q_c = w_b Σ_i cos(h_b τ_i) cos(h_c τ_i) T_i / N_t, and ∂F_c/∂Q_b
        // the same sum times w_c (w = 1 for h = 0, else 2): one sum per pair b ≤ c.
        for (unsigned int b = 0; b < nb_; ++b)
          for (unsigned int c = b; c < nb_; ++c)
            pairs_.emplace_back(b, c);
        sample_weights_.resize(n_time_samples, pairs_.size());
        for (unsigned int p = 0; p < pairs_.size(); ++p)
          sample_weights_.col(p) =
            (cos_.row(pairs_[p].first).array() * cos_.row(pairs_[p].second).array()).matrix().transpose() /
            double(n_time_samples);
      }

      unsigned int n_unknowns() const { return n_ * nb_; }

      // R; if J_X is non-null also ∂R/∂Q and ∂R/∂ω. Returns ‖KQ‖ + ‖F‖, the
      // scale against which ‖R‖ is judged.
      double evaluate(const Eigen::VectorXd &X, const double omega, Eigen::VectorXd &R, Eigen::MatrixXd *J_X,
                      Eigen::VectorXd *J_omega) const
      {
        const Eigen::Map<const Eigen::MatrixXd> Q(X.data(), n_, nb_);
        const Eigen::MatrixXd q_t = Q * cos_; // q(τ_i), n × N_t
        Eigen::MatrixXd f_t(n_, cos_.cols());
        for (Eigen::Index i = 0; i < cos_.cols(); ++i)
          {
            f_t.col(i) = system_.force(q_t.col(i));
            if (!f_t.col(i).allFinite())
              throw std::runtime_error("harmonic balance: the force callback returned non-finite values");
          }
        const Eigen::MatrixXd F  = f_t * weighted_cos_.transpose(); // n × nb
        const Eigen::MatrixXd KQ = system_.stiffness * Q;
        const Eigen::MatrixXd MQ = system_.mass * Q;
        R.resize(n_unknowns());
        Eigen::Map<Eigen::MatrixXd> Rm(R.data(), n_, nb_);
        for (unsigned int b = 0; b < nb_; ++b)
          {
            const double hw = harmonics_[b] * omega;
            Rm.col(b)       = KQ.col(b) - hw * hw * MQ.col(b) + F.col(b);
          }
        if (J_X != nullptr)
          {
            J_X->setZero(n_unknowns(), n_unknowns());
            for (unsigned int b = 0; b < nb_; ++b)
              {
                const double hw = harmonics_[b] * omega;
                J_X->block(b * n_, b * n_, n_, n_) = system_.stiffness - hw * hw * system_.mass;
              }
            // ∂F_b/∂Q_c = Σ_i w_b cos(h_b τ_i) cos(h_c τ_i) T(q(τ_i)), as one
            // product over the pairs b ≤ c (the constructor):
            // [vec T_1 … vec T_Nt] · S(:, pair), then times w_b and w_c.
            // Only the entries of T that are nonzero at some sample take part:
            // all of a modal tangent's, about a tenth of an FE tangent's
            // (its band, on the default beam).
            Eigen::MatrixXd T_all(n_ * n_, cos_.cols());
            Eigen::Array<bool, Eigen::Dynamic, 1> used = Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(n_ * n_, false);
            for (Eigen::Index i = 0; i < cos_.cols(); ++i)
              {
                const Eigen::MatrixXd T = system_.tangent(q_t.col(i));
                T_all.col(i)            = Eigen::Map<const Eigen::VectorXd>(T.data(), n_ * n_);
                used                    = used || (T_all.col(i).array() != 0.);
              }
            std::vector<Eigen::Index> entries; // k = i + n j of T_ij
            entries.reserve(used.count());
            for (Eigen::Index k = 0; k < used.size(); ++k)
              if (used[k])
                entries.push_back(k);
            const Eigen::MatrixXd sums = T_all(entries, Eigen::placeholders::all) * sample_weights_; // entries × pairs
            for (unsigned int p = 0; p < pairs_.size(); ++p)
              {
                const auto [b, c] = pairs_[p];
                const double w_b = weight(b), w_c = weight(c);
                for (std::size_t e = 0; e < entries.size(); ++e)
                  {
                    const Eigen::Index i = entries[e] % n_, j = entries[e] / n_;
                    (*J_X)(b * n_ + i, c * n_ + j) += w_b * sums(e, p);
                    if (c != b)
                      (*J_X)(c * n_ + i, b * n_ + j) += w_c * sums(e, p);
                  }
              }
            J_omega->resize(n_unknowns());
            Eigen::Map<Eigen::MatrixXd> Jw(J_omega->data(), n_, nb_);
            for (unsigned int b = 0; b < nb_; ++b)
              Jw.col(b) = -2. * harmonics_[b] * harmonics_[b] * omega * MQ.col(b);
          }
        return KQ.norm() + F.norm();
      }

    private:
      // w_b of the Fourier coefficient of harmonic h_b: 1 for h = 0, else 2.
      double weight(const unsigned int b) const { return harmonics_[b] == 0 ? 1. : 2.; }

      const ConservativeSystem &system_;
      std::vector<unsigned int> harmonics_;
      unsigned int n_, nb_;
      Eigen::MatrixXd cos_, weighted_cos_;
      std::vector<std::pair<unsigned int, unsigned int>> pairs_; // (b, c), b ≤ c
      Eigen::MatrixXd sample_weights_; // N_t × pairs: cos(h_b τ_i) cos(h_c τ_i) / N_t
    };

    // Continuation state in scaled unknowns z = (Q / s_x, ω / s_ω).
    class BackboneContinuation
    {
    public:
      BackboneContinuation(const ConservativeSystem &system, const BackboneSettings &settings, Backbone &result)
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

      void run()
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

    private:
      double amplitude_of(const Eigen::VectorXd &z) const { return amplitude_row_.dot(z); }

      // Full harmonic vector X (n·|𝓗|, inactive entries 0) from the scaled
      // unknowns z (m + 1, the last one ω/s_ω), and back (z with ω = 0).
      Eigen::VectorXd expand(const Eigen::VectorXd &z) const
      {
        Eigen::VectorXd X = Eigen::VectorXd::Zero(residual_.n_unknowns());
        X(active_)        = z.head(m_) * s_x_;
        return X;
      }
      Eigen::VectorXd restrict_to_active(const Eigen::VectorXd &X_scaled) const
      {
        Eigen::VectorXd z = Eigen::VectorXd::Zero(m_ + 1);
        z.head(m_)        = X_scaled(active_);
        return z;
      }

      // The Newton matrix [∂R/∂z; rowᵀ] on the active unknowns, and R.
      void linearise(const Eigen::VectorXd &z, const Eigen::VectorXd &row, Eigen::VectorXd &R, Eigen::MatrixXd &A)
      {
        Eigen::VectorXd Jw;
        Eigen::MatrixXd JX;
        residual_.evaluate(expand(z), z[m_] * s_w_, R, &JX, &Jw);
        A.resize(m_ + 1, m_ + 1);
        A.topLeftCorner(m_, m_) = JX(active_, active_) * s_x_;
        A.topRightCorner(m_, 1) = Jw(active_) * s_w_;
        A.row(m_)               = row.transpose();
      }

      double relative_residual(const Eigen::VectorXd &z)
      {
        Eigen::VectorXd R;
        const double ref = residual_.evaluate(expand(z), z[m_] * s_w_, R, nullptr, nullptr);
        return R.norm() / std::max(ref, std::numeric_limits<double>::min());
      }

      // Newton on R(z) = 0 plus one closing equation rowᵀ z = rhs
      // (numerics/newton.h: full Newton, converged on the correction).
      bool correct(Eigen::VectorXd &z, const Eigen::VectorXd &row, const double rhs, BackbonePoint &p)
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

      bool correct_at_amplitude(Eigen::VectorXd &z, const double amplitude, BackbonePoint &p)
      {
        return correct(z, amplitude_row_, amplitude, p);
      }

      // Unit tangent of the solution curve: [∂R/∂z; rowᵀ] t = [0; 1].
      Eigen::VectorXd tangent(const Eigen::VectorXd &z, const Eigen::VectorXd &row)
      {
        Eigen::VectorXd R;
        Eigen::MatrixXd A;
        linearise(z, row, R, A);
        Eigen::VectorXd rhs     = Eigen::VectorXd::Zero(m_ + 1);
        rhs[m_]                 = 1.;
        const Eigen::VectorXd t = solve_newton_matrix(A, rhs);
        return t / t.norm();
      }

      void store(const Eigen::VectorXd &z, BackbonePoint &p)
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

      std::string where(const Eigen::VectorXd &z, const BackbonePoint &p) const
      {
        std::ostringstream s;
        s << "amplitude " << amplitude_of(z) << " m, ω " << z[m_] * s_w_ << " rad/s (last converged: amplitude "
          << result_.points.back().amplitude << " m, ω " << result_.points.back().omega
          << " rad/s), relative residual " << p.relative_residual;
        return s.str();
      }

      // Pseudo-arclength: predictor z + Δs t, corrector on tᵀ(z − z_pred) = 0.
      void run_arclength(Eigen::VectorXd z)
      {
        Eigen::VectorXd t = tangent(z, amplitude_row_);
        double ds         = settings_.initial_step;
        double a_max      = amplitude_of(z);
        std::size_t last_regular = result_.points.size() - 1; // last point on the rising backbone
        while (true)
          {
            if (result_.points.size() >= settings_.max_points)
              {
                result_.message = "stopped after max_points = " + std::to_string(settings_.max_points) +
                                  " points at amplitude " + std::to_string(result_.points.back().amplitude) + " m";
                return;
              }
            const Eigen::VectorXd z_pred = z + ds * t;
            Eigen::VectorXd z_new        = z_pred;
            BackbonePoint p;
            bool ok = correct(z_new, t, t.dot(z_pred), p);
            Eigen::VectorXd t_new;
            if (ok)
              {
                t_new = tangent(z_new, t);
                // A turn of more than ~25° in one step: the step jumped (to
                // another branch, or across a sharp fold); retry smaller.
                ok = t_new.dot(t) > 0.9;
              }
            if (!ok)
              {
                ds *= 0.5;
                if (ds < settings_.min_step)
                  {
                    result_.message = "continuation failed: no convergence (or a sharp turn) with step " +
                                      std::to_string(ds) + " < min_step near " + where(z_pred, p);
                    return;
                  }
                continue;
              }
            const double a_new = amplitude_of(z_new);
            land_on_listed_amplitudes(z, z_new);
            if (a_new >= settings_.end_amplitude)
              {
                finish_at_end_amplitude(z, z_new, p);
                return;
              }
            // The zero solution Q = 0 solves R = 0 for every ω: a step that
            // lands near it has left the backbone.
            if (z_new.head(m_).norm() < 0.5 * start_norm_)
              {
                result_.message = "continuation stopped: the step fell back onto the trivial solution Q = 0 near " +
                                  where(z_new, p);
                return;
              }
            store(z_new, p);
            // An internal resonance (k ω ≈ ω_j of another mode) opens a tongue:
            // the branch turns, the other mode's harmonic takes over, ω runs
            // away from the backbone and the first harmonic of the output
            // shrinks. Detected by either sign; a loop that comes back within
            // both is followed.
            const bool rising = a_new >= a_max;
            a_max             = std::max(a_max, a_new);
            double deviation  = 0;
            BackboneFrequencyFit fit;
            if (settings_.tongue_frequency_deviation > 0 && fit_backbone_frequency(result_.points, a_max, s_w_, fit))
              deviation = std::abs(z_new[m_] * s_w_ / fit.omega(a_new) - 1.);
            const bool off_backbone = settings_.tongue_frequency_deviation > 0 &&
                                      deviation > settings_.tongue_frequency_deviation;
            if (rising && !off_backbone)
              last_regular = result_.points.size() - 1;
            if (off_backbone || a_new < settings_.tongue_exit_fraction * a_max)
              {
                const BackbonePoint &last = result_.points[last_regular];
                std::ostringstream s;
                s << "left the backbone along an internal-resonance tongue after amplitude " << last.amplitude
                  << " m (ω " << last.omega << " rad/s): ";
                if (off_backbone)
                  s << "ω = " << z_new[m_] * s_w_ << " rad/s at amplitude " << a_new << " m is " << deviation
                    << " off the backbone extrapolated from below (tongue_frequency_deviation = "
                    << settings_.tongue_frequency_deviation << ")";
                else
                  s << "the first-harmonic amplitude fell to " << a_new << " m after a maximum of " << a_max
                    << " m, at ω " << z_new[m_] * s_w_ << " rad/s (set tongue_exit_fraction = 0 to follow it)";
                mark_tongue(last_regular);
                if (settings_.restart_past_tongues && result_.gaps.size() < settings_.max_restarts)
                  {
                    Eigen::VectorXd z_restart;
                    const double a_last = last.amplitude;
                    if (restart_past_tongue(last_regular, z_restart))
                      {
                        z            = z_restart;
                        t            = tangent(z, amplitude_row_); // towards larger amplitude
                        ds           = settings_.initial_step;
                        a_max        = amplitude_of(z);
                        last_regular = result_.points.size() - 1;
                        continue;
                      }
                    s << "; no restart beyond it converged to the extrapolated backbone (tried up to 1.5 × " << a_last
                      << " m)";
                  }
                result_.message = s.str();
                return;
              }
            z = z_new;
            t = t_new;
            if (p.newton_iterations <= 3)
              ds = std::min(1.5 * ds, settings_.max_step);
            else if (p.newton_iterations >= 7)
              ds *= 0.6;
          }
      }

      // Flag the points of the current segment after point `last`.
      void mark_tongue(const std::size_t last)
      {
        for (std::size_t i = last + 1; i < result_.points.size(); ++i)
          if (result_.points[i].segment == segment_)
            result_.points[i].tongue = true;
      }

      // The branch left along a tongue after the point `last` (the last
      // regular one): look for the backbone beyond it (see
      // BackboneSettings::restart_past_tongues). On success, stores the first
      // point of a new segment and returns it in z.
      bool restart_past_tongue(const std::size_t last, Eigen::VectorXd &z)
      {
        const BackbonePoint last_point = result_.points[last];
        const double a_last = last_point.amplitude;
        BackboneFrequencyFit fit;
        if (!fit_backbone_frequency(result_.points, a_last, s_w_, fit))
          return false;
        const BackbonePoint reference = result_.points[fit.reference];

        for (const double delta : tongue_restart_offsets)
          {
            const double a_target = std::min((1. + delta) * a_last, settings_.end_amplitude);
            if (a_target <= a_last)
              break;
            const double omega_pred = fit.omega(a_target);
            if (!(omega_pred > 0))
              continue;
            for (const bool first_only : {false, true})
              {
                const Eigen::VectorXd X = tongue_restart_guess(reference, result_.harmonics, n_, a_target, first_only);
                Eigen::VectorXd z_try = restrict_to_active(X / s_x_);
                z_try[m_]             = omega_pred / s_w_;
                BackbonePoint p;
                if (!correct_at_amplitude(z_try, a_target, p))
                  continue;
                const double omega = z_try[m_] * s_w_;
                if (std::abs(omega / omega_pred - 1.) > tongue_restart_tolerance)
                  continue;
                BackboneGap gap;
                gap.last_amplitude    = a_last;
                gap.last_omega        = last_point.omega;
                gap.restart_amplitude = a_target;
                gap.restart_omega     = omega;
                gap.predicted_omega   = omega_pred;
                result_.gaps.push_back(gap);
                ++segment_;
                store(z_try, p);
                z = z_try;
                return true;
              }
          }
        return false;
      }

      // Natural continuation in the amplitude a (fails at folds in a).
      void run_amplitude(Eigen::VectorXd z)
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

      // Store extra points exactly at the listed amplitudes that the step
      // z → z_new crossed upwards (BackboneSettings::landing_amplitudes).
      void land_on_listed_amplitudes(const Eigen::VectorXd &z, const Eigen::VectorXd &z_new)
      {
        const double a = amplitude_of(z), a_new = amplitude_of(z_new);
        for (const double target : settings_.landing_amplitudes)
          if (a < target && target <= a_new && target < settings_.end_amplitude)
            {
              Eigen::VectorXd z_land = z + (target - a) / (a_new - a) * (z_new - z);
              BackbonePoint p;
              if (correct_at_amplitude(z_land, target, p))
                store(z_land, p);
            }
      }

      // The last arclength step crossed end_amplitude: land exactly on it.
      void finish_at_end_amplitude(const Eigen::VectorXd &z, const Eigen::VectorXd &z_new, BackbonePoint p_new)
      {
        const double a = amplitude_of(z), a_new = amplitude_of(z_new);
        Eigen::VectorXd z_end = z + (settings_.end_amplitude - a) / (a_new - a) * (z_new - z);
        BackbonePoint p;
        result_.completed = true;
        if (correct_at_amplitude(z_end, settings_.end_amplitude, p))
          {
            store(z_end, p);
            result_.message = "reached end_amplitude";
          }
        else
          {
            store(z_new, p_new);
            result_.message = "reached end_amplitude (last point slightly beyond it: the landing solve failed)";
          }
      }

      const ConservativeSystem &system_;
      const BackboneSettings &settings_;
      Backbone &result_;
      HarmonicBalanceResidual residual_;
      unsigned int n_, m_ = 0;
      std::vector<Eigen::Index> active_; // indices into X of the unknowns solved for
      unsigned int segment_ = 0;
      double s_x_, s_w_ = 1;
      double start_norm_ = 0; // ‖Q/s_x‖ at the first point
      Eigen::VectorXd amplitude_row_, mode_shape_;
    };
  } // namespace

  Backbone compute_backbone(const ConservativeSystem &system, const BackboneSettings &settings)
  {
    const auto t0       = std::chrono::steady_clock::now();
    const unsigned int n = system.n_dofs();
    auto fail = [](const std::string &what) { throw std::invalid_argument("compute_backbone: " + what); };
    if (n == 0 || system.stiffness.cols() != n || system.mass.rows() != n || system.mass.cols() != n)
      fail("mass and stiffness must be square and of the same size (got K " + std::to_string(system.stiffness.rows()) +
           "×" + std::to_string(system.stiffness.cols()) + ", M " + std::to_string(system.mass.rows()) + "×" +
           std::to_string(system.mass.cols()) + ")");
    if (!system.force || !system.tangent)
      fail("force and tangent callbacks must be set");
    if (settings.output.size() != n)
      fail("output has " + std::to_string(settings.output.size()) + " entries; must have n_dofs = " +
           std::to_string(n));
    if (settings.mode >= n)
      fail("mode = " + std::to_string(settings.mode) + "; must be < n_dofs = " + std::to_string(n));
    if (settings.hb.n_harmonics < 1 || settings.hb.n_harmonics > 200)
      fail("n_harmonics = " + std::to_string(settings.hb.n_harmonics) + "; allowed 1 … 200");
    if (!(settings.start_amplitude > 0) || !(settings.end_amplitude > settings.start_amplitude))
      fail("need 0 < start_amplitude < end_amplitude (got " + std::to_string(settings.start_amplitude) + " m, " +
           std::to_string(settings.end_amplitude) + " m)");
    if (!(settings.min_step > 0) || !(settings.initial_step >= settings.min_step) ||
        !(settings.max_step >= settings.initial_step))
      fail("need 0 < min_step ≤ initial_step ≤ max_step (got " + std::to_string(settings.min_step) + ", " +
           std::to_string(settings.initial_step) + ", " + std::to_string(settings.max_step) + ")");

    Backbone result;
    for (unsigned int h = settings.hb.odd_harmonics_only ? 1 : 0; h <= settings.hb.n_harmonics;
         h += settings.hb.odd_harmonics_only ? 2 : 1)
      result.harmonics.push_back(h);
    const unsigned int exact_samples = 4 * settings.hb.n_harmonics + 1;
    result.n_time_samples = settings.hb.n_time_samples == 0 ? exact_samples : settings.hb.n_time_samples;
    if (!settings.hb.even_harmonic_dofs.empty())
      {
        if (settings.hb.even_harmonic_dofs.size() != n)
          fail("even_harmonic_dofs has " + std::to_string(settings.hb.even_harmonic_dofs.size()) +
               " entries; must be empty or have n_dofs = " + std::to_string(n));
        if (settings.hb.odd_harmonics_only)
          fail("even_harmonic_dofs and odd_harmonics_only cannot be combined (set all entries false instead)");
      }
    if (result.n_time_samples < 2 * settings.hb.n_harmonics + 1)
      fail("n_time_samples = " + std::to_string(result.n_time_samples) + "; must be ≥ 2H+1 = " +
           std::to_string(2 * settings.hb.n_harmonics + 1) + " (≥ 4H+1 for exact cubic terms)");

    BackboneContinuation continuation(system, settings, result);
    try
      {
        continuation.run();
      }
    catch (const Interrupted &e)
      {
        // Stopped between Newton iterations: the converged points stay (none
        // converged: nothing to keep, the caller stops).
        if (result.points.empty() || !settings.keep_points_when_interrupted)
          throw;
        result.interrupted = true;
        result.completed   = false;
        std::ostringstream s;
        s << e.what() << " after " << result.points.size() << " converged points (last at amplitude "
          << result.points.back().amplitude << " m, ω " << result.points.back().omega << " rad/s)";
        result.message = s.str();
      }
    result.seconds = elapsed_seconds(t0);
    return result;
  }

  Eigen::VectorXd output_time_history(const Backbone &backbone, const BackbonePoint &point,
                                      const Eigen::VectorXd &output, const unsigned int n_samples)
  {
    const unsigned int n  = output.size();
    const unsigned int nb = backbone.harmonics.size();
    if (point.harmonics.size() != n * nb)
      throw std::invalid_argument("output_time_history: point has " + std::to_string(point.harmonics.size()) +
                                  " harmonic coefficients; expected n·|H| = " + std::to_string(n * nb));
    const Eigen::Map<const Eigen::MatrixXd> Q(point.harmonics.data(), n, nb);
    const Eigen::VectorXd yh = Q.transpose() * output; // y's harmonic coefficients
    const double pi          = std::acos(-1.);
    Eigen::VectorXd y        = Eigen::VectorXd::Zero(n_samples);
    for (unsigned int i = 0; i < n_samples; ++i)
      for (unsigned int b = 0; b < nb; ++b)
        y[i] += yh[b] * std::cos(backbone.harmonics[b] * 2. * pi * i / n_samples);
    return y;
  }

  unsigned int count_amplitude_folds(const Backbone &backbone, const bool include_tongues)
  {
    std::vector<const BackbonePoint *> kept;
    for (const BackbonePoint &p : backbone.points)
      if (include_tongues || !p.tongue)
        kept.push_back(&p);
    unsigned int folds = 0;
    for (std::size_t i = 2; i < kept.size(); ++i)
      {
        const BackbonePoint &before = *kept[i - 2], &a = *kept[i - 1], &b = *kept[i];
        if (before.segment != b.segment || a.segment != b.segment)
          continue;
        if ((a.amplitude - before.amplitude) * (b.amplitude - a.amplitude) < 0)
          ++folds;
      }
    return folds;
  }
} // namespace beamslider
