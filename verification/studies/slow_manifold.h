// The held slider's slow manifold by its periodic orbits (issue 73, doc/
// physics.md §12): what `beamslider branches` computes.
//
// Two parts, because the rattling system has no periodic orbit to continue:
//   - the attractor probes: the held slider of the scene's reduced model
//     (runs/held_slider_map.h) at a grid of x_C, each started from the state
//     the previous one ended in (as the sweep's up branch): period count,
//     Poincaré section spread, largest Lyapunov exponent, and the amplitude
//     and F̄_x reached. The evidence for or against a periodic orbit.
//   - the branch of the attached-slider model (reduced/attached_slider_model.h),
//     the smooth description whose orbits, unstable ones included, shooting
//     and arclength continuation follow through their turning points in x_C
//     (numerics/periodic_orbits.h), with Floquet multipliers.
// The study writes and prints nothing; the observer sees each result.
#pragma once

#include "scene/scene.h"
#include "numerics/periodic_orbits.h"
#include "runs/held_slider_map.h"

#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  struct SlowManifoldSettings
  {
    double low_over_L = 0.1, high_over_L = 0.5; // x_C/L range of both parts
    double probe_step_over_L = 0.02;            // between attractor probes
    unsigned int settle_periods = 120;          // per probe before its section
    unsigned int section_periods = 8;           // the section (and largest period count looked for)
    unsigned int lyapunov_periods = 60;
    double max_step_over_L = 0.003;             // the continuation's largest step in x_C/L

    // InputError naming the parameter if a value is out of range for the scene.
    void validate(const Scene &scene) const;
    static SlowManifoldSettings for_scene(const Scene &scene); // the sweep's range
  };

  struct SlowManifold
  {
    std::string model;                          // e.g. "ROM N = 5"
    std::vector<HeldSliderAttractor> probes;
    std::string probe_stop;                     // why the probes stopped early ("" if they did not)
    Branch attached;                            // x_C/L is λ; observables: amplitude/h, F̄_x [N]
    // The stability verdict by time integration, at every 50th orbit: the
    // growth per period of a small separation started on the orbit (40
    // periods after 20), |μ₁| if the multipliers are right; NaN elsewhere.
    std::vector<double> attached_growth;
    double wall_seconds = 0;
  };

  struct SlowManifoldObserver
  {
    std::function<void(const HeldSliderAttractor &)> on_probe;
    std::function<void(const OrbitPoint &, double growth)> on_orbit; // growth: see attached_growth
    std::function<void(const std::string &)> on_progress; // a line without '\n'
  };

  // The scene's own reduced model (its N modes and coefficients).
  SlowManifold compute_slow_manifold(const Scene &scene, const SlowManifoldSettings &settings,
                                     const SlowManifoldObserver &observer = {});
} // namespace beamslider
