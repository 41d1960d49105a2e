// The harmonic balance residual of a conservative system by AFT, and the solve
// with the continuation's Newton matrix: the parts of compute_backbone that
// the continuation (backbone_continuation.h) builds on. Internal to the library.
#pragma once

#include "reduced/harmonic_balance.h"

#include <Eigen/Dense>

#include <utility>
#include <vector>

namespace beamslider
{
  namespace internal
  {
    // x = A⁻¹ b for the continuation's Newton matrix, sparse or dense
    // (harmonic_balance_residual.cc).
    Eigen::VectorXd solve_newton_matrix(const Eigen::MatrixXd &A, const Eigen::VectorXd &b);

    // The HB residual R(Q, ω) of the file header, its Jacobian ∂R/∂Q and
    // ∂R/∂ω, by AFT on N_t equispaced samples of one period.
    class HarmonicBalanceResidual
    {
    public:
      HarmonicBalanceResidual(const ConservativeSystem &system, std::vector<unsigned int> harmonics,
                              const unsigned int n_time_samples);

      unsigned int n_unknowns() const { return n_ * nb_; }

      // R; if J_X is non-null also ∂R/∂Q and ∂R/∂ω. Returns ‖KQ‖ + ‖F‖, the
      // scale against which ‖R‖ is judged.
      double evaluate(const Eigen::VectorXd &X, const double omega, Eigen::VectorXd &R, Eigen::MatrixXd *J_X,
                      Eigen::VectorXd *J_omega) const;

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
  } // namespace internal
} // namespace beamslider
