// The harmonic balance residual R(Q, ω) and its Jacobian by alternating
// frequency/time evaluation, and the Newton matrix's sparse or dense solve.
#include "reduced/harmonic_balance_residual.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

namespace beamslider
{
  namespace internal
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

    HarmonicBalanceResidual::HarmonicBalanceResidual(const ConservativeSystem &system,
                                                     std::vector<unsigned int> harmonics,
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

    double HarmonicBalanceResidual::evaluate(const Eigen::VectorXd &X, const double omega, Eigen::VectorXd &R,
                                             Eigen::MatrixXd *J_X, Eigen::VectorXd *J_omega) const
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
  } // namespace internal
} // namespace beamslider
