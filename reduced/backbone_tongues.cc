// Extrapolation of a backbone across an internal-resonance tongue and the
// restart guesses; see backbone_tongues.h.
#include "reduced/backbone_tongues.h"

#include <algorithm>
#include <cmath>

namespace beamslider
{
  double BackboneFrequencyFit::omega(const double amplitude) const
  {
    double w2 = 0;
    for (Eigen::Index k = 0; k < coef.size(); ++k)
      w2 += coef[k] * std::pow(amplitude / a_ref, 2 * k);
    return w2 > 0 ? std::sqrt(w2) * omega_scale : 0.;
  }

  bool fit_backbone_frequency(const std::vector<BackbonePoint> &points, const double a_ref, const double omega_scale,
                              BackboneFrequencyFit &fit)
  {
    std::vector<std::size_t> ref;
    for (std::size_t i = 0; i < points.size(); ++i)
      if (!points[i].tongue && points[i].amplitude >= 0.4 * a_ref && points[i].amplitude <= 0.85 * a_ref)
        ref.push_back(i);
    if (ref.size() < 2)
      return false;
    // Scaled variables keep the least-squares problem well conditioned.
    const unsigned int n_terms = ref.size() >= 3 ? 3 : 2;
    Eigen::MatrixXd A(ref.size(), n_terms);
    Eigen::VectorXd y(ref.size());
    double a_best = 0;
    for (std::size_t r = 0; r < ref.size(); ++r)
      {
        const BackbonePoint &p = points[ref[r]];
        const double a         = p.amplitude / a_ref;
        for (unsigned int k = 0; k < n_terms; ++k)
          A(r, k) = std::pow(a, 2 * k);
        y[r] = std::pow(p.omega / omega_scale, 2);
        if (p.amplitude > a_best)
          {
            a_best        = p.amplitude;
            fit.reference = ref[r];
          }
      }
    fit.coef        = A.colPivHouseholderQr().solve(y);
    fit.a_ref       = a_ref;
    fit.omega_scale = omega_scale;
    return true;
  }

  Eigen::VectorXd tongue_restart_guess(const BackbonePoint &reference, const std::vector<unsigned int> &harmonics,
                                       const unsigned int n_dofs, const double a_target,
                                       const bool first_harmonic_only)
  {
    const double r    = a_target / reference.amplitude;
    Eigen::VectorXd X = reference.harmonics;
    for (unsigned int b = 0; b < harmonics.size(); ++b)
      {
        const unsigned int h = harmonics[b];
        const double scale   = (first_harmonic_only && h != 1) ? 0. : std::pow(r, h == 0 ? 2 : std::min(h, 3u));
        X.segment(b * n_dofs, n_dofs) *= scale;
      }
    return X;
  }
} // namespace beamslider
