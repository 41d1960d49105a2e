// Harmonic balance backbones with AFT and pseudo-arclength continuation; see
// harmonic_balance.h for the equations, the choice of harmonics and samples.
// This file checks the settings and runs the continuation
// (backbone_continuation.h); the residual is in harmonic_balance_residual.cc.
#include "reduced/harmonic_balance.h"
#include "numerics/elapsed.h"

#include "reduced/backbone_continuation.h"

#include "numerics/stop_request.h"

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  namespace
  {
    using internal::BackboneContinuation;
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
