// The one reading of an adaptation run, see trace_analysis.h.
#include "runs/trace_analysis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace beamslider
{
  TraceThresholds TraceThresholds::for_backbone(const double c)
  {
    TraceThresholds t;
    t.high_level_over_h = c > 0. ? std::sqrt((1.05 * 1.05 - 1.) / c) : std::numeric_limits<double>::infinity();
    return t;
  }

  std::string to_string(const AdaptationClass c)
  {
    switch (c)
      {
        case AdaptationClass::signature_move:
          return "signature move";
        case AdaptationClass::trivial_adaption:
          return "trivial adaption";
        case AdaptationClass::relaxation_oscillation:
          return "relaxation oscillation";
        case AdaptationClass::self_damping:
          return "self-damping";
        case AdaptationClass::no_adaptation:
          return "no adaptation";
        case AdaptationClass::reached_support:
          return "reached a support";
        case AdaptationClass::failed:
          return "failed";
        case AdaptationClass::too_short:
          return "too short to judge";
      }
    return "unknown";
  }

  namespace
  {
    // Number of periods in a time span (at least one).
    std::size_t periods_in(const double seconds, const double period)
    {
      return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(seconds / period)));
    }

    // Envelope: trailing mean of the amplitude over the envelope window.
    void compute_envelope(const std::vector<PeriodRecord> &periods, const std::size_t w, TraceAnalysis &a)
    {
      const std::size_t n = periods.size();
      a.envelope.resize(n);
      double sum = 0;
      for (std::size_t k = 0; k < n; ++k)
        {
          sum += periods[k].amplitude_over_h;
          if (k >= w)
            sum -= periods[k - w].amplitude_over_h;
          a.envelope[k] = sum / std::min(k + 1, w);
        }
      a.max_envelope = *std::max_element(a.envelope.begin(), a.envelope.end());
    }

    // Jumps: sudden, large, lasting, and landing on the upper branch.
    // After a jump the envelope first rises through the middle level (the
    // trailing mean needs its window to fill); it may beat around it while
    // the slider settles. Only a fall below the middle that lasts
    // `hold_time` re-arms the detector for a recurrent jump.
    void detect_jumps(const std::vector<PeriodRecord> &periods, const TraceThresholds &th, const double period,
                      TraceAnalysis &a)
    {
      const std::size_t n = periods.size();
      const auto &e       = a.envelope;
      const std::size_t look = periods_in(th.lookback, period), hold = periods_in(th.hold_time, period);
      bool high = false, risen = false;
      double fall_level = 0;
      for (std::size_t k = 0; k < n; ++k)
        {
          if (high)
            {
              risen = risen || e[k] >= fall_level;
              if (risen && e[k] < fall_level && k + hold <= n &&
                  std::all_of(e.begin() + k, e.begin() + k + hold, [&](const double x) { return x < fall_level; }))
                high = false;
              continue;
            }
          if (periods[k].t_end < th.build_up_time)
            continue;
          const double b = *std::min_element(e.begin() + (k > look ? k - look : 0), e.begin() + k + 1);
          if (!(e[k] > th.jump_ratio * b && e[k] - b > th.jump_share * a.max_envelope))
            continue;
          const std::size_t k_end = std::min(n, k + hold);
          if (k + hold > n) // cannot tell whether it lasts
            continue;
          bool lasts = true;
          double landed = e[k];
          for (std::size_t j = k; j < k_end && lasts; ++j)
            {
              lasts  = e[j] >= th.jump_ratio * b;
              landed = std::max(landed, e[j]);
            }
          if (!lasts || !(landed >= th.high_level_over_h))
            continue;
          high       = true;
          risen      = false;
          fall_level = 0.5 * (b + landed);
          if (++a.n_upward_jumps == 1)
            {
              a.jumped            = true;
              a.jump_time         = periods[k].t_end;
              a.level_before_jump = b;
            }
        }
    }

    // Initial direction, and whether the slider crosses the centre; returns
    // x̄/L at the end of the window judged.
    double judge_initial_direction(const std::vector<PeriodRecord> &periods, const TraceThresholds &th,
                                   TraceAnalysis &a)
    {
      const std::size_t n = periods.size();
      const double x0     = periods.front().slider_x_over_L;
      a.direction_until   = a.jumped ? std::min(th.direction_window, a.jump_time) : th.direction_window;
      std::size_t k_dir   = 0;
      while (k_dir + 1 < n && periods[k_dir + 1].t_end <= a.direction_until)
        ++k_dir;
      a.direction_until      = periods[k_dir].t_end;
      const double x1        = periods[k_dir].slider_x_over_L;
      a.initial_drift_over_L = x1 - x0;
      const double outward   = std::abs(x1 - 0.5) - std::abs(x0 - 0.5);
      a.initial_direction    = outward > th.direction_threshold    ? "toward the clamp"
                               : outward < -th.direction_threshold ? "toward the centre"
                                                                   : "stays";
      for (const PeriodRecord &p : periods)
        if ((p.slider_x_over_L - 0.5) * (x0 - 0.5) < 0.)
          a.crosses_centre = true;
      return x1;
    }

    // End state, adaptation time and turn-around.
    void judge_end_and_turn(const std::vector<PeriodRecord> &periods, const TraceThresholds &th, const double period,
                            TraceAnalysis &a)
    {
      const std::size_t n = periods.size();
      // End state.
      const std::size_t tail = std::max<std::size_t>(1, std::min(periods_in(th.final_window, period), n / 10));
      for (std::size_t k = n - tail; k < n; ++k)
        {
          a.final_position += periods[k].slider_x_over_L / tail;
          a.final_amplitude += periods[k].amplitude_over_h / tail;
        }

      // Adaptation time: from when on every period mean x̄ stays within
      // `settle_tolerance` of the end state (the end of the last period
      // outside it; 0 if none is).
      a.adaptation_time = 0.;
      for (std::size_t k = n; k-- > 0;)
        if (std::abs(periods[k].slider_x_over_L - a.final_position) > th.settle_tolerance)
          {
            a.adaptation_time = periods[k].t_end;
            break;
          }

      // Turn-around.
      const double x0    = periods.front().slider_x_over_L;
      std::size_t k_turn = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (std::abs(periods[k].slider_x_over_L - 0.5) > std::abs(periods[k_turn].slider_x_over_L - 0.5))
          k_turn = k;
      a.turn_position = periods[k_turn].slider_x_over_L;
      a.turn_time     = 0.5 * (periods[k_turn].t_start + periods[k_turn].t_end);
      a.turned        = std::abs(a.turn_position - 0.5) > std::abs(x0 - 0.5) + th.direction_threshold &&
                 std::abs(a.final_position - 0.5) <= std::abs(a.turn_position - 0.5) - th.turn_margin;
    }

    // The reading in words, up to the class; x0, x1: x̄/L at the start and
    // at the end of the direction window.
    std::string describe(const TraceAnalysis &a, const double x0, const double x1)
    {
      std::ostringstream line;
      line << std::setprecision(3);
      line << a.initial_direction << " (x_C/L " << x0 << " → " << x1 << " by t = " << a.direction_until << " s); ";
      if (a.jumped)
        line << "jump at t = " << a.jump_time << " s from " << a.level_before_jump << " h (envelope up to "
             << a.max_envelope << " h)";
      else
        line << "no jump (envelope ≤ " << a.max_envelope << " h)";
      if (a.turned)
        line << "; turned at x_C/L = " << a.turn_position << " (t = " << a.turn_time << " s)";
      else
        line << "; no turn-around";
      line << "; ends at x_C/L = " << a.final_position << " with " << a.final_amplitude << " h";
      if (a.n_upward_jumps > 1)
        line << "; " << a.n_upward_jumps << " upward jumps";
      if (a.crosses_centre)
        line << "; crosses the centre";
      return line.str();
    }

    AdaptationClass classify(const TraceAnalysis &a, const RunStatus status, const TraceThresholds &th)
    {
      // The run ends on the upper branch: near its own largest envelope and in
      // the stiffened regime of the scene's backbone.
      const bool on_upper_end = a.final_amplitude >= th.high_end_share * a.max_envelope &&
                                a.final_amplitude >= th.high_level_over_h;
      if (status == RunStatus::slider_at_support)
        return AdaptationClass::reached_support;
      if (status != RunStatus::completed && status != RunStatus::interrupted)
        return AdaptationClass::failed;
      if (!a.valid)
        return AdaptationClass::too_short;
      if (a.n_upward_jumps >= 2)
        return AdaptationClass::relaxation_oscillation;
      if (a.initial_direction == "toward the clamp" && a.jumped && a.turned && on_upper_end)
        return AdaptationClass::signature_move;
      if (a.final_amplitude < th.damped_share * a.max_envelope)
        return AdaptationClass::self_damping;
      if (!a.jumped && a.initial_direction == "toward the centre" && on_upper_end)
        return AdaptationClass::trivial_adaption;
      return AdaptationClass::no_adaptation;
    }
  } // namespace

  TraceAnalysis analyse_trace(const std::vector<PeriodRecord> &periods, const RunStatus status,
                              const TraceThresholds &th)
  {
    TraceAnalysis a;
    const std::size_t n = periods.size();
    if (n == 0)
      {
        a.outcome = status == RunStatus::slider_at_support ? AdaptationClass::reached_support
                    : status == RunStatus::completed || status == RunStatus::interrupted ? AdaptationClass::too_short
                                                                                          : AdaptationClass::failed;
        a.line = "no complete excitation period";
        return a;
      }
    a.end_time          = periods.back().t_end;
    const double period = periods[0].t_end - periods[0].t_start;

    compute_envelope(periods, periods_in(th.envelope_window, period), a);
    detect_jumps(periods, th, period, a);
    const double x1 = judge_initial_direction(periods, th, a);
    judge_end_and_turn(periods, th, period, a);
    a.valid   = n >= 20;
    a.outcome = classify(a, status, th);
    a.line    = describe(a, periods.front().slider_x_over_L, x1) + ": " + to_string(a.outcome);
    return a;
  }
} // namespace beamslider
