#include "verification/studies/fe_rom_study.h"

#include "contact/beam_system.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "reduced/rom_beam_system.h"
#include "reduced/rom_implicit_beam_system.h"
#include "verification/studies/coefficient_methods.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace beamslider
{
  std::string ModelSetting::label() const
  {
    std::ostringstream s;
    if (family == "fe")
      s << "FE " << n_elements << " el.";
    else
      s << "ROM N=" << n_modes << " " << coefficients << (integrator == "implicit" ? " implicit" : "");
    s << " dt=" << time_step; // no comma: labels go into CSV cells
    if (slider_offset_over_L != 0)
      s << " x0+" << slider_offset_over_L;
    return s.str();
  }

  std::unique_ptr<BeamSystem> make_beam_model(const Scene &scene_in, const ModelSetting &setting)
  {
    Scene scene                     = scene_in;
    scene.time_stepping.time_step   = setting.time_step;
    if (setting.family == "fe")
      {
        if (setting.n_elements)
          scene.discretisation.n_elements = setting.n_elements;
        return make_fe_beam_system(scene);
      }
    if (setting.family != "rom")
      throw InputError("model family '" + setting.family + "' is not one of fe, rom");

    const FEBeam beam(scene);
    const FEModes modes = compute_bending_modes(beam, setting.n_modes);
    ModalBasis basis    = make_modal_basis(beam, modes, setting.n_modes);
    ReducedOrderModel rom(basis, scene.damping_ratio, scene.discretisation.geometric_nonlinearity);
    if (setting.coefficients != "analytic")
      {
        // STEP amplitude one thickness; ICE at 0.03 h (report section 2.4).
        const double level = setting.coefficients == "ice" ? 0.03 : 1.0;
        rom.set_cubic_terms(compute_coefficients(beam, modes, basis, setting.coefficients, level).fit.cubic);
      }
    if (setting.integrator == "implicit")
      return std::make_unique<RomImplicitBeamSystem>(std::move(rom), scene.beam.thickness,
                                                     BaseExcitation::from_scene(scene.excitation));
    if (setting.integrator != "explicit")
      throw InputError("ROM integrator '" + setting.integrator + "' is not one of explicit, implicit");
    return std::make_unique<RomBeamSystem>(std::move(rom), scene.beam.thickness,
                                           BaseExcitation::from_scene(scene.excitation));
  }

  ModelRun run_setting(const Scene &scene_in, const ModelSetting &setting, const double window,
                       const std::function<void(const PeriodRecord &)> &on_period)
  {
    ModelRun run;
    run.setting      = setting;
    const auto start = std::chrono::steady_clock::now();
    try
      {
        Scene scene                   = scene_in;
        scene.time_stepping.time_step = setting.time_step;
        scene.initial.slider_position_over_L += setting.slider_offset_over_L;
        if (setting.family == "fe" && setting.n_elements)
          scene.discretisation.n_elements = setting.n_elements;
        auto beam          = make_beam_model(scene, setting);
        RunOptions options = RunOptions::from_scene(scene);
        options.end_time   = window;
        options.progress_interval = 1e9;
        AdaptationRun adaptation(scene, *beam, options);
        adaptation.on_period = [&run, &on_period](const PeriodRecord &p) {
          run.periods.push_back(p);
          if (on_period)
            on_period(p);
        };
        run.result = adaptation.run();
        run.ok     = run.result.status == RunStatus::completed;
        run.message = run.result.message;
      }
    catch (const std::exception &e)
      {
        run.ok      = false;
        run.message = e.what();
      }
    run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
  }

  namespace
  {
    // Trailing mean of the per-period amplitude over `span` periods.
    std::vector<double> envelope(const std::vector<PeriodRecord> &periods, const std::size_t n, const std::size_t span)
    {
      std::vector<double> e(n);
      double sum = 0;
      for (std::size_t k = 0; k < n; ++k)
        {
          sum += periods[k].amplitude_over_h;
          if (k >= span)
            sum -= periods[k - span].amplitude_over_h;
          e[k] = sum / std::min(k + 1, span);
        }
      return e;
    }
  } // namespace

  void compare_with_reference(ModelRun &run, const ModelRun &reference)
  {
    const std::size_t n = std::min(run.periods.size(), reference.periods.size());
    if (!run.ok || !reference.ok || n == 0)
      return;
    const double period    = reference.periods[0].t_end - reference.periods[0].t_start;
    const std::size_t span = std::max<std::size_t>(1, std::lround(0.1 / period));
    const auto a = envelope(run.periods, n, span), a_ref = envelope(reference.periods, n, span);
    double diff2 = 0, ref2 = 0, dx = 0;
    for (std::size_t k = 0; k < n; ++k)
      {
        diff2 += (a[k] - a_ref[k]) * (a[k] - a_ref[k]);
        ref2 += a_ref[k] * a_ref[k];
        dx = std::max(dx, std::abs(run.periods[k].slider_x_over_L - reference.periods[k].slider_x_over_L));
      }
    const double drift = std::abs(reference.periods[n - 1].slider_x_over_L - reference.periods[0].slider_x_over_L);
    run.envelope_error = std::sqrt(diff2 / std::max(ref2, 1e-300));
    run.position_error = dx;
    run.drift_error    = dx / std::max(drift, 1e-9);
  }

  RunDifference difference(const ModelRun &run, const ModelRun &other)
  {
    ModelRun copy = run;
    compare_with_reference(copy, other);
    return {copy.drift_error, copy.envelope_error, copy.position_error};
  }

  TraceOutcome trace_outcome(const ModelRun &run, const TraceThresholds &thresholds)
  {
    return analyse_trace(run.periods, run.result.status, thresholds);
  }

  std::vector<std::size_t> pareto_front(const std::vector<ModelRun> &runs)
  {
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < runs.size(); ++i)
      {
        if (runs[i].drift_error < 0)
          continue;
        bool dominated = false;
        for (std::size_t j = 0; j < runs.size() && !dominated; ++j)
          dominated = j != i && runs[j].drift_error >= 0 && runs[j].wall_seconds <= runs[i].wall_seconds &&
                      runs[j].drift_error <= runs[i].drift_error &&
                      (runs[j].wall_seconds < runs[i].wall_seconds || runs[j].drift_error < runs[i].drift_error);
        if (!dominated)
          front.push_back(i);
      }
    return front;
  }

  double cost_per_simulated_second(const ModelSetting &setting, const Scene &scene)
  {
    const double per_step =
      setting.family == "fe"
        ? 40. * (setting.n_elements ? setting.n_elements : scene.discretisation.n_elements) / 32.
        : 1. + (setting.n_modes / 5.) * (setting.n_modes / 5.);
    return per_step / setting.time_step;
  }

  ModelSetting choose_model(const Scene &scene, const double tolerance, std::string &why, const double window)
  {
    const double dt = scene.time_stepping.time_step;
    ModelSetting reference_setting;
    reference_setting.family     = "fe";
    reference_setting.n_elements = scene.discretisation.n_elements;
    reference_setting.time_step  = dt / 2;
    const ModelRun reference = run_setting(scene, reference_setting, window);
    std::ostringstream log;
    if (!reference.ok)
      throw std::runtime_error("--model auto needs the FE reference, which failed: " + reference.message);

    std::vector<ModelSetting> candidates;
    for (const unsigned int N : {1u, 3u, 5u, 7u})
      for (const double step : {2 * dt, dt})
        {
          ModelSetting s;
          s.n_modes = N, s.time_step = step;
          candidates.push_back(s);
        }
    ModelSetting fe = reference_setting;
    fe.time_step    = dt;
    candidates.push_back(fe);

    log << "model selection over " << window << " s against " << reference_setting.label() << " (tolerance " << tolerance
        << " on the slider drift error; cost by a stated model, a unit = one step of the ROM N=5, not by wall time):\n";
    std::vector<ModelRun> runs;
    for (const auto &c : candidates)
      {
        runs.push_back(run_setting(scene, c, window));
        compare_with_reference(runs.back(), reference);
        const auto &r = runs.back();
        log << "  " << c.label() << ": " << (r.ok ? "drift error " + std::to_string(r.drift_error) : "failed (" + r.message + ")")
            << ", cost " << cost_per_simulated_second(c, scene) << " units per simulated second (wall "
            << r.wall_seconds << " s, for information)\n";
      }
    const ModelRun *best = nullptr;
    for (const auto &r : runs)
      if (r.ok && r.drift_error >= 0 && r.drift_error <= tolerance &&
          (!best || cost_per_simulated_second(r.setting, scene) < cost_per_simulated_second(best->setting, scene)))
        best = &r;
    ModelSetting chosen = best ? best->setting : fe;
    log << "picked " << chosen.label() << ": "
        << (best ? "the cheapest model (by the cost model) within the tolerance" : "no cheaper model met the tolerance, so the FE model") << "\n";
    why = log.str();
    return chosen;
  }
} // namespace beamslider
