// One reading of an adaptation run: from its per-period records (contact/
// adaptation_run.h) to the envelope, the jump, the turn-around, the end state
// and the outcome class. Every command, study and report uses this one set
// of rules, so that "jump" or "signature move" means the same everywhere.
//
// Rules (thresholds in TraceThresholds, all relative to the run's own levels
// or to the scene's backbone, none tuned to one case):
//   envelope e_k   trailing mean of the per-period amplitude a = ŵ(L/2)/h
//                  over `envelope_window` (0.1 s: a few dozen periods, long
//                  against the rattling, short against the adaptation);
//   jump           at period k after the build-up from rest (`build_up_time`,
//                  ≈ 2/(D ω₁)): e_k exceeds `jump_ratio` × b, b the smallest
//                  envelope of the preceding `lookback`; the rise e_k − b is
//                  at least `jump_share` of the run's largest envelope; e stays
//                  above `jump_ratio` × b for `hold_time`; and e_k reaches
//                  `high_level_over_h`, the amplitude at which the scene's
//                  mode-1 backbone (seed Eq. 4) lies 5 % above ω₁: a jump is
//                  a landing on the stiffened upper branch of the resonance,
//                  not a bump of the rattling near the linear level. Further
//                  such rises after e has stayed below the middle between b
//                  and the level jumped to for `hold_time` count as
//                  recurrent jumps (the beating while the slider settles
//                  after a jump does not);
//   initial direction  change of x̄ over the first `direction_window` (or up
//                  to the jump): away from the centre by more than
//                  `direction_threshold` = toward the clamp, toward the
//                  centre by more = toward the centre, else stays;
//   turn           the period mean x̄ farthest from the centre, if it lies
//                  `direction_threshold` farther out than the start and the
//                  end state is `turn_margin` back toward the centre from it;
//   end state      x̄ and a averaged over the last `final_window` (or the last
//                  tenth of a shorter run);
//   adaptation time  the end of the last period whose x̄ lies more than
//                  `settle_tolerance` from the end state's: from then on the
//                  slider stays at its end position (a value near the run's
//                  end says it has not settled);
//   class          failed / reached a support (by the run's status); else
//                  relaxation oscillation (≥ 2 jumps); signature move (toward
//                  the clamp, jump, turn, and the end on the upper branch:
//                  end amplitude ≥ `high_end_share` of the largest envelope
//                  and ≥ `high_level_over_h`);
//                  self-damping (end amplitude below `damped_share` of the
//                  largest envelope); trivial adaption (no jump, toward the
//                  centre, the end on the upper branch as above);
//                  else no adaptation.
#pragma once

#include "runs/adaptation_run.h"

#include <string>
#include <vector>

namespace beamslider
{
  struct TraceThresholds
  {
    double envelope_window     = 0.1;   // [s]
    double build_up_time       = 2.0;   // [s]
    double jump_ratio          = 2.0;   // [-]
    double lookback            = 1.0;   // [s]
    double jump_share          = 0.2;   // of the largest envelope [-]
    double hold_time           = 1.0;   // [s]
    double high_level_over_h   = 0.;    // [h]; 0: no level condition
    double direction_window    = 5.0;   // [s]
    double direction_threshold = 0.005; // [x/L]
    double turn_margin         = 0.02;  // [x/L]
    double final_window        = 1.0;   // [s]
    double settle_tolerance    = 0.01;  // [x/L]
    double high_end_share      = 0.5;   // [-]
    double damped_share        = 0.2;   // [-]

    // The thresholds for a scene whose mode-1 backbone is (ω/ω₁)² = 1 + c (ŵ/h)²
    // (seed Eq. 4): the upper-branch level is where ω/ω₁ = 1.05. c = 0 (a
    // linear beam) leaves no level at which a jump could land.
    static TraceThresholds for_backbone(double c);
  };

  enum class AdaptationClass
  {
    signature_move,
    trivial_adaption,
    relaxation_oscillation,
    self_damping,
    no_adaptation,
    reached_support,
    failed,
    too_short
  };
  std::string to_string(AdaptationClass c);

  struct TraceAnalysis
  {
    bool valid = false; // enough periods (≥ 20) to judge jumps and turns
    double end_time = 0; // [s]
    std::vector<double> envelope; // e_k per period [h]
    double max_envelope = 0;      // [h]

    std::string initial_direction = "stays"; // "toward the clamp" | "toward the centre" | "stays"
    double initial_drift_over_L   = 0;
    double direction_until        = 0; // end of the window judged [s]

    bool jumped = false;
    double jump_time = -1;           // [s], -1 without a jump
    double level_before_jump = 0;    // b of the first jump [h]
    unsigned int n_upward_jumps = 0; // the first and the recurrent ones

    bool turned = false;
    double turn_position = 0, turn_time = 0; // x_C/L, [s]

    double final_position = 0, final_amplitude = 0; // x_C/L, [h]
    double adaptation_time = 0;                     // [s]
    bool crosses_centre = false;

    AdaptationClass outcome = AdaptationClass::too_short;
    std::string line; // one line in words
  };

  TraceAnalysis analyse_trace(const std::vector<PeriodRecord> &periods, RunStatus status,
                              const TraceThresholds &thresholds);
} // namespace beamslider
