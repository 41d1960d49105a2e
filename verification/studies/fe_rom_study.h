// The FE-against-ROM study behind report section 5 and `simulate --model
// auto`: the same scene, the same contact code, run on beam models of
// different fidelity and cost, each compared with a reference run over the
// same time window.
//
// A setting is one model and its numerical parameters:
//   fe   the deal.II beam (fem/fe_beam_system) with n_elements and Δt,
//   rom  the reduced model on the FE modal basis with N modes, cubic
//        coefficients from `analytic | step-condensed | ice`, and Δt.
// Errors against the reference, per excitation period k. The rattling slider
// makes the period-to-period amplitude sensitive to every impact (two runs
// that differ in the last digit part after a few dozen periods), while the
// slow quantities the adaptation is about, the slider drift and the
// amplitude envelope, are robust. So we compare those:
//   drift error      max_k |x̄_k − x̄_k^ref| / |x̄_end^ref − x̄_0^ref|  (x̄ = period mean of x_C)
//   envelope error   ‖ā − ā_ref‖₂ / ‖ā_ref‖₂, ā = a averaged over the periods of the last 0.1 s
//                    (a = ŵ(L/2)/h per period)
//   position error   max_k |x̄_k − x̄_k^ref| / L
#pragma once

#include "contact/adaptation_run.h"
#include "contact/trace_analysis.h"
#include "meshes/scene.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace beamslider
{
  class BeamSystem;

  struct ModelSetting
  {
    std::string family = "rom"; // fe | rom
    unsigned int n_elements = 0; // fe: 0 = the scene's
    unsigned int n_modes = 5;    // rom
    std::string coefficients = "analytic"; // rom: analytic | step-condensed | ice
    // rom: explicit (the published midpoint step) | implicit (the FE's
    // implicit midpoint rule, reduced/rom_implicit_beam_system.h): the
    // ladder rung that changes only the integrator.
    std::string integrator = "explicit";
    double time_step = 2e-5;     // [s]
    // Added to the scene's start position x_C/L: a "round-off twin" of a run
    // (e.g. 1e-9) measures how far the rattling alone spreads two runs.
    double slider_offset_over_L = 0;

    std::string label() const;
  };

  // The beam model of a setting for `scene` (the scene's mesh, damping and
  // excitation; the setting's own parameters). Throws if it cannot be built.
  std::unique_ptr<BeamSystem> make_beam_model(const Scene &scene, const ModelSetting &setting);

  struct ModelRun
  {
    ModelSetting setting;
    std::vector<PeriodRecord> periods;
    RunResult result;
    bool ok = false;        // ran to the end of the window
    std::string message;    // why not
    double wall_seconds = 0; // model set-up + run
    // Against the reference (-1: not compared); see the file header.
    double drift_error = -1, envelope_error = -1, position_error = -1;
  };

  // Runs `setting` on `scene` from t = 0 to `window` seconds. Never throws
  // for a failing model: the failure is recorded in the result. `on_period`
  // (optional) sees every period as it closes, e.g. to stream it to a CSV.
  ModelRun run_setting(const Scene &scene, const ModelSetting &setting, double window,
                       const std::function<void(const PeriodRecord &)> &on_period = {});

  // The errors of `run` against `other` (compare_with_reference on a copy).
  struct RunDifference
  {
    double drift = -1, envelope = -1, position = -1;
  };
  RunDifference difference(const ModelRun &run, const ModelRun &other);

  // The outcome of a long adaptation run: the one trace analysis
  // (contact/trace_analysis.h) with the scene's thresholds.
  using TraceOutcome = TraceAnalysis;
  TraceOutcome trace_outcome(const ModelRun &run, const TraceThresholds &thresholds);

  // Fills amplitude_error and position_error of `run` against `reference`.
  void compare_with_reference(ModelRun &run, const ModelRun &reference);

  // Indices of the runs on the Pareto front of (wall time, drift error):
  // no other run is both faster and more accurate.
  std::vector<std::size_t> pareto_front(const std::vector<ModelRun> &runs);

  // The cost of simulating one second with a setting, in units of the
  // published ROM's step (N = 5): a stated model, not a clock reading, so
  // that a loaded machine cannot change a choice. Per step, a ROM costs
  // 1 + (N/5)² units (its cubic force and mass-matrix products grow like N²,
  // the contact part does not) and the FE 40 × elements/32 units (the
  // measured ratio on the default mesh, ~28 µs against ~0.7 µs per step,
  // README); times the steps per second, 1/Δt.
  double cost_per_simulated_second(const ModelSetting &setting, const Scene &scene);

  // `simulate --model auto`: runs the candidate settings (ROM N = 1, 3, 5, 7
  // at the scene's Δt and 2Δt, the FE model) over a short window against the
  // FE reference at Δt/2, and returns the cheapest setting by
  // cost_per_simulated_second whose drift error is within `tolerance`, or
  // the FE model at the scene's Δt if none is. The reasoning (errors, costs,
  // wall times for information, what was picked and why) goes to `why`.
  ModelSetting choose_model(const Scene &scene, double tolerance, std::string &why, double window = 0.5);
} // namespace beamslider
