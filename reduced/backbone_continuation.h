// The continuation of a backbone in (Q, ω) from the linear mode: the state
// and steps of compute_backbone (backbone_continuation.cc, the arclength
// steps and tongue restarts in backbone_arclength.cc). Internal to the library.
#pragma once

#include "reduced/harmonic_balance.h"
#include "reduced/harmonic_balance_residual.h"

#include <Eigen/Dense>

#include <cstddef>
#include <string>
#include <vector>

namespace beamslider
{
  namespace internal
  {
    // Continuation state in scaled unknowns z = (Q / s_x, ω / s_ω).
    class BackboneContinuation
    {
    public:
      BackboneContinuation(const ConservativeSystem &system, const BackboneSettings &settings, Backbone &result);
      void run();

    private:
      double amplitude_of(const Eigen::VectorXd &z) const { return amplitude_row_.dot(z); }

      // Full harmonic vector X (n·|𝓗|, inactive entries 0) from the scaled
      // unknowns z (m + 1, the last one ω/s_ω), and back (z with ω = 0).
      Eigen::VectorXd expand(const Eigen::VectorXd &z) const;
      Eigen::VectorXd restrict_to_active(const Eigen::VectorXd &X_scaled) const;

      // The Newton matrix [∂R/∂z; rowᵀ] on the active unknowns, and R.
      void linearise(const Eigen::VectorXd &z, const Eigen::VectorXd &row, Eigen::VectorXd &R, Eigen::MatrixXd &A);

      double relative_residual(const Eigen::VectorXd &z);

      // Newton on R(z) = 0 plus one closing equation rowᵀ z = rhs
      // (numerics/newton.h: full Newton, converged on the correction).
      bool correct(Eigen::VectorXd &z, const Eigen::VectorXd &row, const double rhs, BackbonePoint &p);

      bool correct_at_amplitude(Eigen::VectorXd &z, const double amplitude, BackbonePoint &p);

      // Unit tangent of the solution curve: [∂R/∂z; rowᵀ] t = [0; 1].
      Eigen::VectorXd tangent(const Eigen::VectorXd &z, const Eigen::VectorXd &row);

      void store(const Eigen::VectorXd &z, BackbonePoint &p);

      std::string where(const Eigen::VectorXd &z, const BackbonePoint &p) const;

      // Pseudo-arclength: predictor z + Δs t, corrector on tᵀ(z − z_pred) = 0.
      void run_arclength(Eigen::VectorXd z);

      // Flag the points of the current segment after point `last`.
      void mark_tongue(const std::size_t last);

      // The branch left along a tongue after the point `last` (the last
      // regular one): look for the backbone beyond it (see
      // BackboneSettings::restart_past_tongues). On success, stores the first
      // point of a new segment and returns it in z.
      bool restart_past_tongue(const std::size_t last, Eigen::VectorXd &z);

      // Natural continuation in the amplitude a (fails at folds in a).
      void run_amplitude(Eigen::VectorXd z);

      // Store extra points exactly at the listed amplitudes that the step
      // z → z_new crossed upwards (BackboneSettings::landing_amplitudes).
      void land_on_listed_amplitudes(const Eigen::VectorXd &z, const Eigen::VectorXd &z_new);

      // The last arclength step crossed end_amplitude: land exactly on it.
      void finish_at_end_amplitude(const Eigen::VectorXd &z, const Eigen::VectorXd &z_new, BackbonePoint p_new);

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
  } // namespace internal
} // namespace beamslider
