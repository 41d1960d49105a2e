// Prescribed-slider-position sweeps, see prescribed_position_sweep.h.
#include "runs/prescribed_position_sweep.h"
#include "numerics/elapsed.h"

#include "runs/batch_means.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <tuple>

namespace beamslider
{
  namespace
  {
    // Closest x_C/L to a support at which both window corners (±B/2 about
    // x_C) stay on the beam with a margin of 0.01 L.
    double outermost_position_over_L(const Scene &scene)
    {
      return 0.5 * scene.slider.window_width / scene.beam.length + 0.01;
    }

    double mean(const std::vector<double> &v)
    {
      double s = 0;
      for (const double x : v)
        s += x;
      return v.empty() ? 0. : s / v.size();
    }

    double standard_deviation(const std::vector<double> &v)
    {
      if (v.size() < 2)
        return 0.;
      const double m = mean(v);
      double s       = 0;
      for (const double x : v)
        s += (x - m) * (x - m);
      return std::sqrt(s / (v.size() - 1));
    }
  } // namespace

  std::vector<double> PcsSweepSettings::positions(const SweepDirection direction) const
  {
    // The grid low + k Δ (up) or high − k Δ (down); the far end is included
    // when the range is not a whole number of steps.
    std::vector<double> positions;
    const double span = high_over_L - low_over_L;
    const long n      = static_cast<long>(std::floor(span / step_over_L + 1e-9));
    for (long k = 0; k <= n; ++k)
      positions.push_back(direction == SweepDirection::up ? low_over_L + k * step_over_L : high_over_L - k * step_over_L);
    const double far_end = direction == SweepDirection::up ? high_over_L : low_over_L;
    if (std::abs(positions.back() - far_end) > 1e-9)
      positions.push_back(far_end);
    return positions;
  }

  std::string to_string(const SweepDirection direction) { return direction == SweepDirection::up ? "up" : "down"; }

  void validate_held_position_range(const Scene &scene, const double low_over_L, const double high_over_L,
                                    const std::string &who)
  {
    auto fail = [&](const std::string &name, const double value, const std::string &range) {
      std::ostringstream m;
      m << who << " parameter " << name << " = " << value << " is outside the allowed range " << range;
      throw InputError(m.str());
    };
    const double edge = outermost_position_over_L(scene);
    std::ostringstream range;
    range << "[" << edge << ", " << 1. - edge << "] (slider window corners at x_C ± B/2 must stay 0.01 L inside the beam)";
    if (!(low_over_L >= edge - 1e-12 && low_over_L <= 1. - edge + 1e-12))
      fail("low x_C/L", low_over_L, range.str());
    if (!(high_over_L >= edge - 1e-12 && high_over_L <= 1. - edge + 1e-12))
      fail("high x_C/L", high_over_L, range.str());
    if (!(high_over_L > low_over_L))
      fail("high x_C/L", high_over_L, "(low x_C/L = " + std::to_string(low_over_L) + ", inf)");
  }

  std::pair<double, double> default_held_position_range(const Scene &scene)
  {
    const double edge = std::max(0.05, outermost_position_over_L(scene));
    return scene.initial.slider_position_over_L <= 0.5 ? std::make_pair(edge, 0.5) : std::make_pair(0.5, 1. - edge);
  }

  void PcsSweepSettings::validate(const Scene &scene) const
  {
    auto fail = [](const std::string &name, const double value, const std::string &range) {
      std::ostringstream m;
      m << "sweep parameter " << name << " = " << value << " is outside the allowed range " << range;
      throw InputError(m.str());
    };
    validate_held_position_range(scene, low_over_L, high_over_L, "sweep");
    if (!(step_over_L > 0. && step_over_L <= high_over_L - low_over_L))
      fail("step dx_C/L", step_over_L, "(0, high − low]");
    if (!(settle_time >= 0.))
      fail("settle time [s]", settle_time, "[0, inf)");
    const double period = 1. / scene.excitation.frequency_hz;
    if (!(average_time >= period))
      fail("average time [s]", average_time, "[one excitation period = " + std::to_string(period) + " s, inf)");
  }

  PcsSweepSettings PcsSweepSettings::for_scene(const Scene &scene)
  {
    PcsSweepSettings s;
    std::tie(s.low_over_L, s.high_over_L) = default_held_position_range(scene);
    return s;
  }

  PcsBranch run_pcs_branch(const Scene &scene, BeamSystem &beam, const PcsSweepSettings &settings, const double time_step,
                           const SweepDirection direction, const std::function<void(const PcsPoint &)> &on_point)
  {
    settings.validate(scene);
    const auto start = std::chrono::steady_clock::now();
    const double L   = beam.length();

    const std::vector<double> positions = settings.positions(direction);

    Scene start_scene                          = scene;
    start_scene.initial.slider_position_over_L = positions.front();
    RunOptions options                         = RunOptions::from_scene(scene, time_step);
    options.prescribed_slider_position         = true;
    options.output_rate                        = 1.; // no trace rows needed
    options.progress_interval                  = 1e300;
    AdaptationRun run(start_scene, beam, options);

    // Collect the periods that close inside the averaging window.
    double average_from = 0;
    std::vector<double> amplitudes, forces;
    run.on_period = [&](const PeriodRecord &r) {
      if (r.t_start >= average_from - 1e-9)
        {
          amplitudes.push_back(r.amplitude_over_h);
          forces.push_back(r.mean_horizontal_contact_force);
        }
    };

    PcsBranch branch;
    branch.direction = direction;
    for (std::size_t i = 0; i < positions.size(); ++i)
      {
        if (i > 0)
          run.set_slider_position(positions[i] * L);
        amplitudes.clear();
        forces.clear();
        const double t0 = run.state().t;
        average_from    = t0 + settings.settle_time;
        branch.last_run = run.run_until(average_from + settings.average_time);
        if (branch.last_run.status != RunStatus::completed)
          break;

        PcsPoint p;
        p.x_over_L             = positions[i];
        p.direction            = direction;
        p.amplitude_over_h     = mean(amplitudes);
        p.amplitude_std_over_h = standard_deviation(amplitudes);
        p.mean_fx              = mean(forces);
        p.mean_fx_std          = standard_deviation(forces);
        p.mean_fx_ci95         = batch_means_interval(forces).half_width;
        p.n_periods            = amplitudes.size();
        p.t_end                = run.state().t;
        branch.points.push_back(p);
        if (on_point)
          on_point(p);
      }
    branch.wall_seconds = elapsed_seconds(start);
    return branch;
  }

  std::vector<ForceZeroCrossing> force_zero_crossings(const std::vector<PcsPoint> &branch)
  {
    // Sort by position so that up and down branches read the same way.
    std::vector<PcsPoint> p = branch;
    std::sort(p.begin(), p.end(), [](const PcsPoint &a, const PcsPoint &b) { return a.x_over_L < b.x_over_L; });
    // Walk the samples with F̄_x ≠ 0; a sign change between two of them is a
    // crossing, placed at the zero sample(s) between them if there are any
    // (their midpoint), else by linear interpolation.
    std::vector<ForceZeroCrossing> crossings;
    std::size_t previous = p.size(); // last sample with F̄_x ≠ 0
    for (std::size_t i = 0; i < p.size(); ++i)
      {
        const double f1 = p[i].mean_fx;
        if (f1 == 0.)
          continue;
        if (previous < p.size() && (p[previous].mean_fx > 0.) != (f1 > 0.))
          {
            const double f0 = p[previous].mean_fx;
            ForceZeroCrossing c;
            if (i - previous > 1)
              c.x_over_L = 0.5 * (p[previous + 1].x_over_L + p[i - 1].x_over_L);
            else
              c.x_over_L = p[previous].x_over_L + f0 / (f0 - f1) * (p[i].x_over_L - p[previous].x_over_L);
            c.stable = f1 < f0; // F̄_x decreasing in x: a displaced slider is pushed back
            // The interval: where each band F̄_x ± ci95 crosses zero between
            // the two positions, or the bracket's edge if it does not.
            const double x0 = p[previous].x_over_L, x1 = p[i].x_over_L;
            auto band_zero  = [&](const double sign) {
              const double b0 = f0 + sign * p[previous].mean_fx_ci95, b1 = f1 + sign * p[i].mean_fx_ci95;
              if ((b0 > 0.) == (b1 > 0.) || b0 == b1)
                // No sign change: the band stays on one side over the whole
                // bracket; the crossing can lie anywhere toward that side.
                return (b0 > 0.) == (f0 > 0.) ? x1 : x0;
              return x0 + b0 / (b0 - b1) * (x1 - x0);
            };
            const double xa = band_zero(+1.), xb = band_zero(-1.);
            c.x_low_over_L  = std::min({xa, xb, c.x_over_L});
            c.x_high_over_L = std::max({xa, xb, c.x_over_L});
            // Resolved when both neighbours' 95 % intervals (batch means: the
            // periods of a rattling slider are correlated) exclude zero.
            c.resolved = std::abs(f0) > p[previous].mean_fx_ci95 && std::abs(f1) > p[i].mean_fx_ci95;
            crossings.push_back(c);
          }
        previous = i;
      }
    return crossings;
  }

  std::optional<AmplitudeJump> largest_amplitude_jump(const std::vector<PcsPoint> &branch, const double min_ratio)
  {
    std::optional<AmplitudeJump> best;
    double best_ratio = min_ratio;
    for (std::size_t i = 1; i < branch.size(); ++i)
      {
        const double a0 = branch[i - 1].amplitude_over_h, a1 = branch[i].amplitude_over_h;
        const double lo = std::min(a0, a1), hi = std::max(a0, a1);
        const double ratio = lo > 0. ? hi / lo : (hi > 0. ? INFINITY : 1.);
        if (ratio > best_ratio)
          {
            best_ratio = ratio;
            best = AmplitudeJump{branch[i - 1].x_over_L, branch[i].x_over_L, a0, a1};
          }
      }
    return best;
  }
} // namespace beamslider
