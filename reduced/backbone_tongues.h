// Internal-resonance tongues on a backbone: the heuristics by which
// compute_backbone (harmonic_balance.h) sees that the branch has left the
// backbone and finds the backbone again beyond the tongue.
//
// Where k ω of the backbone meets another mode's frequency, the continuation
// turns into a narrow tongue in which that mode's k-th harmonic grows. Two
// signs, either of which is enough:
//   - the first-harmonic amplitude falls below a fraction of the largest
//     reached (BackboneSettings::tongue_exit_fraction);
//   - ω departs from the backbone extrapolated from below by more than
//     BackboneSettings::tongue_frequency_deviation (a tongue can be left at
//     almost constant amplitude).
// The extrapolation is ω² = α + β a² (+ γ a⁴) fitted to the regular points
// with amplitudes in [0.4, 0.85] a_ref, away from the tongue near a_ref.
// A restart tries amplitude-controlled Newton solves at a = (1 + δ) a_last
// from the extrapolated ω and a guess scaled from the fit's largest point,
// and accepts a solution within tongue_restart_tolerance of the prediction.
#pragma once

#include "reduced/harmonic_balance.h"

#include <Eigen/Dense>

#include <array>
#include <cstddef>
#include <vector>

namespace beamslider
{
  // ω(a) of the backbone extrapolated from below.
  struct BackboneFrequencyFit
  {
    Eigen::VectorXd coef;       // of ω²/s_ω² in powers (a/a_ref)^{2k}
    double a_ref = 1;           // [m]
    double omega_scale = 1;     // s_ω [rad/s]
    std::size_t reference = 0;  // index of the fitted point of largest amplitude
    double omega(double amplitude) const; // [rad/s]; 0 where ω² ≤ 0
  };

  // Fits ω² through the points that are not on a tongue with amplitudes in
  // [0.4, 0.85] a_ref (any segment). False if fewer than two such points.
  bool fit_backbone_frequency(const std::vector<BackbonePoint> &points, double a_ref, double omega_scale,
                              BackboneFrequencyFit &fit);

  // Relative steps δ beyond the last regular amplitude at which a restart is
  // tried, in this order.
  inline constexpr std::array<double, 6> tongue_restart_offsets{0.02, 0.05, 0.1, 0.2, 0.3, 0.5};
  // A restarted point is the backbone's continuation if its ω is within this
  // fraction of the extrapolated one.
  inline constexpr double tongue_restart_tolerance = 0.03;

  // Initial guess for the harmonics (stacked as in Backbone::harmonics, n_dofs
  // per harmonic) at amplitude a_target: the reference point's harmonic h
  // scaled like (a_target/a_ref)^min(h,3) (the mean like a²), or, with
  // first_harmonic_only, its first harmonic alone (the component resonating
  // in the tongue changes sign across it, so dropping it can be the better
  // guess).
  Eigen::VectorXd tongue_restart_guess(const BackbonePoint &reference, const std::vector<unsigned int> &harmonics,
                                       unsigned int n_dofs, double a_target, bool first_harmonic_only);
} // namespace beamslider
