// Prescribed-slider-position (PCS) sweeps, seed §4.2–4.3 and doc/physics.md §10.
//
// The slider's horizontal position x_C is held (its height z_C and tilt β stay
// free, the four corner contacts stay active) and stepped along the beam by
// Δx_C, each step starting from the state the previous one ended in: a
// sequential continuation of the stable periodic states with x_C as the
// control parameter. Because the slider drifts seconds-slowly while the beam
// vibrates at ~100 Hz, these states are the "slow manifold" the free slider
// follows (seed Fig. 10b).
//
// At each position we run `settle_time` and then average over the whole
// excitation periods of the next `average_time`:
//   - the amplitude, (max − min)/2 of w(L/2) per period, over h;
//   - F̄_x, the period-averaged horizontal contact force on the slider
//     [N, + toward x = L]: the force that would move a free slider. Its zero
//     crossings are equilibria of the free slider, stable where ∂F̄_x/∂x < 0.
// The spread (standard deviation over the averaged periods) is kept with each
// mean: a rattling slider does not settle to an exactly periodic state.
//
// Written once for any BeamSystem (ROM or FE), like the rest of contact/.
#pragma once

#include "runs/adaptation_run.h"
#include "contact/beam_system.h"
#include "scene/scene.h"

#include <functional>
#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace beamslider
{
  // Direction of a branch: x_C increasing ("up") or decreasing ("down").
  enum class SweepDirection
  {
    up,
    down
  };
  std::string to_string(SweepDirection direction);

  // The range of positions x_C/L a held slider may take on a scene, both
  // window corners (x_C ± B/2) 0.01 L inside the beam: throws InputError
  // "<who> parameter low x_C/L = … is outside the allowed range …" (or
  // high), and for high ≤ low. Shared by the sweeps and `branches`.
  void validate_held_position_range(const Scene &scene, double low_over_L, double high_over_L, const std::string &who);
  // The default range: the half of the beam holding the scene's initial
  // slider position, from the centre to 0.05 L (0.95 L) or as close to the
  // support as the slider's window allows.
  std::pair<double, double> default_held_position_range(const Scene &scene);

  struct PcsSweepSettings
  {
    double low_over_L   = 0.05;  // smallest x_C/L of both branches [-]
    double high_over_L  = 0.5;   // largest x_C/L [-]
    double step_over_L  = 0.003; // Δx_C/L between positions (seed) [-]
    double settle_time  = 0.5;   // simulated time before averaging, per position [s]
    double average_time = 0.2;   // simulated time averaged, per position [s]

    // Throws InputError naming the parameter if a value is out of range for
    // this scene (slider corners must stay on the beam).
    void validate(const Scene &scene) const;
    // The default range for a scene: the half of the beam holding the
    // scene's initial slider position, from the centre to 0.05 L (0.95 L) or
    // as close to the support as the slider's window allows.
    static PcsSweepSettings for_scene(const Scene &scene);
    // The positions x_C/L of one branch, in the order it visits them.
    std::vector<double> positions(SweepDirection direction) const;
  };

  struct PcsPoint
  {
    double x_over_L = 0;
    SweepDirection direction = SweepDirection::up;
    double amplitude_over_h = 0, amplitude_std_over_h = 0; // [-]
    double mean_fx = 0, mean_fx_std = 0;                   // F̄_x and its spread over periods [N]
    double mean_fx_ci95 = 0; // half width of F̄_x's 95 % interval by batch means (runs/batch_means.h) [N]
    unsigned int n_periods = 0;                            // periods averaged
    double t_end = 0;                                      // simulated time at the end of this position [s]
  };

  struct PcsBranch
  {
    SweepDirection direction = SweepDirection::up;
    std::vector<PcsPoint> points;
    RunResult last_run;     // status of the last run (completed unless the branch stopped early)
    double wall_seconds = 0;
  };

  // One branch: starts with the beam at rest and the slider resting at the
  // first position of the branch (low for up, high for down), then steps.
  // `on_point` is called after every position (for writing and progress).
  // A contact-solver failure or a non-finite state stops the branch: the
  // points reached are kept and last_run says when, where and why.
  // `time_step` is the model's [s].
  PcsBranch run_pcs_branch(const Scene &scene, BeamSystem &beam, const PcsSweepSettings &settings, double time_step,
                           SweepDirection direction,
                           const std::function<void(const PcsPoint &)> &on_point = {});

  // A zero crossing of F̄_x along one branch (linear interpolation between
  // neighbouring positions): an equilibrium of the free slider.
  struct ForceZeroCrossing
  {
    double x_over_L = 0;
    // Where the crossing may lie given F̄_x's 95 % intervals at the two
    // bracketing positions: the zero crossings of the bands F̄_x ± ci95,
    // each linearly interpolated like the mean; a band that does not change
    // sign between the two positions leaves that end at the bracket's edge
    // (and the crossing unresolved).
    double x_low_over_L = 0, x_high_over_L = 0;
    bool stable     = false; // ∂F̄_x/∂x < 0
    // Both neighbouring means lie outside zero by more than their 95 %
    // batch-means interval (runs/batch_means.h): a crossing of the mean,
    // not of the rattling noise.
    bool resolved = true;
  };
  std::vector<ForceZeroCrossing> force_zero_crossings(const std::vector<PcsPoint> &branch);

  // The largest jump of the amplitude between neighbouring positions of a
  // branch, if its ratio (larger/smaller) exceeds `min_ratio`: the turning
  // point of the low (or high) branch, where the continuation falls onto the
  // other one.
  struct AmplitudeJump
  {
    double x_before_over_L = 0, x_after_over_L = 0;
    double amplitude_before_over_h = 0, amplitude_after_over_h = 0;
  };
  std::optional<AmplitudeJump> largest_amplitude_jump(const std::vector<PcsPoint> &branch, double min_ratio = 1.5);
} // namespace beamslider
