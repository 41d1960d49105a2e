// The stroboscopic map of the held-slider system (doc/physics.md §11), the
// map whose fixed points are the steady vibrations of seed §4.2: the slider's
// horizontal position x_C held (as in the sweeps, prescribed_position_sweep.h),
// its height z_C and tilt β free, the four corners' unilateral contact with
// friction, the beam excited at f_ex. One evaluation runs the Moreau stepper
// over k excitation periods from a state at phase zero, t = 0.
//
// The unknowns y = (q, u, ζ, ψ, ζ̇, ψ̇): the beam's coordinates and
// velocities (modal for the ROM, nodal for the FE) and the slider's free
// coordinates relative to the beam under x_C, ζ = z_C − w(x_C) and
// ψ = β − atan w'(x_C), with their rates; x_C is the continuation parameter
// λ, given as x_C/L. Relative coordinates stay within the clearance as x_C
// changes (absolute ones would put the slider through a beam vibrating at a
// few h), so the orbit is a smooth function of λ in them.
// So that k periods are a whole number of steps, the map steps at
// T k / ⌈T k / Δt⌉, the largest step not above the model's Δt.
//
// Observables of the k periods from y (PeriodMapValue::observables, in the
// order of held_slider_observable_names()): the amplitude (max − min)/2 of
// w(L/2) over the k periods over h, the mean horizontal contact force F̄_x on
// the slider [N, + toward x = L] (as in the sweeps), the fraction of steps
// with a closed corner, and the largest contact solver iteration count.
//
// Every evaluation starts the stepper afresh (set_state: no warm start from
// the evaluation before), so the map is a function of y alone. A step that
// fails (contact solver, support, unphysical or non-finite state, the beam's
// own solver) throws PeriodMapFailure with the stepper's message.
#pragma once

#include "contact/beam_system.h"
#include "contact/moreau_stepper.h"
#include "scene/scene.h"
#include "numerics/periodic_orbits.h"

#include <string>
#include <vector>

namespace beamslider
{
  std::vector<std::string> held_slider_observable_names();

  class HeldSliderMap
  {
  public:
    // The beam must outlive the map; `time_step` is the model's [s] (the
    // map's step is the largest not above it that fits k periods).
    HeldSliderMap(const Scene &scene, BeamSystem &beam, double time_step, unsigned int periods = 1,
                  ProxSolverSettings solver = {});

    unsigned int n_unknowns() const { return 2 * beam_.n_dofs() + 4; }
    unsigned int periods() const { return periods_; }
    double step() const { return stepper_.time_step(); } // [s]
    unsigned int steps_per_map() const { return steps_; }

    // y of a state (x_C and v_x dropped) and back at x_C/L.
    Eigen::VectorXd pack(const SystemState &state) const;
    SystemState unpack(const Eigen::VectorXd &y, double x_over_L) const;

    // The slider resting on the beam at rest at x_C/L, as y.
    Eigen::VectorXd resting(double x_over_L) const;

    // Φ(y; x_C/L) and the observables of its periods.
    PeriodMapValue operator()(const Eigen::VectorXd &y, double x_over_L);

    // Typical sizes of the unknowns around y, for ShootingSettings::scale:
    // each beam block (q, u) its largest entry, at least the coordinates
    // that deflect the centre by the clearance R − h (and Ω times that); the
    // slider's relative coordinates R − h and (R − h)/B, their rates Ω times.
    Eigen::VectorXd scale(const Eigen::VectorXd &y) const;

    // A PeriodMap that calls this object (which must outlive it).
    PeriodMap as_function();

    // The beam's share y.head(2 n) and the slider's y.tail(4).
    unsigned int n_beam_unknowns() const { return 2 * beam_.n_dofs(); }

  private:
    // w, atan w' and their rates under x_C [m] for coordinates q and velocities u.
    Eigen::Vector4d beam_under_slider(double x_C, const Eigen::VectorXd &q, const Eigen::VectorXd &u) const;

    BeamSystem &beam_;
    MoreauStepper stepper_;
    unsigned int periods_, steps_;
    double clearance_, window_width_, omega_;
    Eigen::VectorXd centre_grad_w_;
  };

  // What the held slider's motion settles to at one x_C, by the map alone:
  // the evidence for or against a periodic orbit to shoot for.
  struct HeldSliderAttractor
  {
    double x_over_L = 0;
    // The smallest k ≤ max_k with Φᵏ(y) = y to the tolerance; 0: none.
    unsigned int period_count = 0;
    // The Poincaré section's spread over the last max_k periods, scaled by
    // HeldSliderMap::scale (∞-norm of the largest difference from the
    // first point), for the beam's unknowns and for the slider's.
    double beam_spread = 0, slider_spread = 0;
    // Largest Lyapunov exponent [per period] (numerics/periodic_orbits.h).
    double lyapunov_per_period = 0;
    // Means over the section's periods: amplitude / h and F̄_x [N].
    double amplitude_over_h = 0, mean_fx = 0;
    Eigen::VectorXd state; // where the probe ended (a start for the next x_C)
  };

  // Runs `settle` periods from y, then max_k periods for the section and
  // `lyapunov_periods` for the exponent. Throws PeriodMapFailure if a step fails.
  HeldSliderAttractor probe_held_slider_attractor(HeldSliderMap &map, double x_over_L, Eigen::VectorXd y,
                                                  unsigned int settle, unsigned int max_k = 8,
                                                  unsigned int lyapunov_periods = 60, double tolerance = 1e-6);
} // namespace beamslider
