// The pseudo-arclength continuation of a backbone: its steps, the landings on
// given amplitudes, and the internal-resonance tongues it detects and restarts
// past.
#include "reduced/backbone_continuation.h"

#include "reduced/backbone_tongues.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace beamslider
{
  namespace internal
  {
    void BackboneContinuation::run_arclength(Eigen::VectorXd z)
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

    void BackboneContinuation::mark_tongue(const std::size_t last)
    {
      for (std::size_t i = last + 1; i < result_.points.size(); ++i)
        if (result_.points[i].segment == segment_)
          result_.points[i].tongue = true;
    }

    bool BackboneContinuation::restart_past_tongue(const std::size_t last, Eigen::VectorXd &z)
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

    void BackboneContinuation::land_on_listed_amplitudes(const Eigen::VectorXd &z, const Eigen::VectorXd &z_new)
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

    void BackboneContinuation::finish_at_end_amplitude(const Eigen::VectorXd &z, const Eigen::VectorXd &z_new,
                                                       BackbonePoint p_new)
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
  } // namespace internal
} // namespace beamslider
