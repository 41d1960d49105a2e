// The held slider's slow manifold, see slow_manifold.h.
#include "verification/studies/slow_manifold.h"

#include "numerics/elapsed.h"
#include "numerics/stop_request.h"
#include "reduced/attached_slider_model.h"
#include "reduced/rom_beam_system.h"
#include "runs/prescribed_position_sweep.h"
#include "verification/studies/fe_rom_study.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

namespace beamslider
{
  namespace
  {
    // The attached model's branch from the low end of the range upward,
    // started on the linear steady state there.
    Branch continue_attached(const Scene &scene, const ReducedOrderModel &rom, const SlowManifoldSettings &s,
                             const SlowManifoldObserver &observer, std::vector<double> &growth)
    {
      const AttachedSliderModel model(rom, scene.slider_mass(), scene.slider_inertia(), scene.contact.gravity,
                                      BaseExcitation::from_scene(scene.excitation), scene.beam.thickness);
      const Eigen::VectorXd y0 = model.linear_response(s.low_over_L);
      ShootingSettings shooting;
      shooting.scale             = model.scale(y0);
      shooting.tolerance         = 1e-8;
      const ShootingOutcome out  = shoot(model, y0, s.low_over_L, shooting);
      if (!out.converged)
        {
          Branch failed;
          failed.end_reason = "no periodic orbit of the attached model at x_C/L = " + std::to_string(s.low_over_L) +
                              " to start from: " + out.reason;
          return failed;
        }
      ContinuationSettings c;
      c.shooting       = shooting;
      c.shooting.scale = model.scale(out.point.y);
      c.rescale        = [&model](const Eigen::VectorXd &y) { return model.scale(y); };
      // A unit step in the scaled unknowns weighs like 0.01 L.
      c.lambda_scale   = 0.01;
      c.lambda_min     = s.low_over_L;
      c.lambda_max     = s.high_over_L;
      c.initial_step   = 0.05;
      c.max_step       = s.max_step_over_L / c.lambda_scale;
      c.max_points     = 20000;
      c.on_point       = [&](const OrbitPoint &p) {
        double g = std::numeric_limits<double>::quiet_NaN();
        if (growth.size() % 50 == 0)
          g = std::exp(largest_lyapunov_exponent(model, p.y, p.lambda, model.scale(p.y), 40, 1e-7, 20));
        growth.push_back(g);
        if (observer.on_orbit)
          observer.on_orbit(p, g);
      };
      c.stop_requested = [] { return interruption_requested(); };
      return continue_branch(model, out.point, c);
    }
  } // namespace

  void SlowManifoldSettings::validate(const Scene &scene) const
  {
    auto fail = [](const std::string &name, const double value, const std::string &range) {
      std::ostringstream m;
      m << "branches parameter " << name << " = " << value << " is outside the allowed range " << range;
      throw InputError(m.str());
    };
    validate_held_position_range(scene, low_over_L, high_over_L, "branches");
    if (!(probe_step_over_L > 0. && probe_step_over_L <= high_over_L - low_over_L + 1e-12))
      fail("probe step dx_C/L", probe_step_over_L, "(0, high - low]");
    if (!(max_step_over_L > 0. && max_step_over_L <= 0.05))
      fail("continuation step dx_C/L", max_step_over_L, "(0, 0.05]");
    if (section_periods < 1 || section_periods > 64)
      fail("section periods", section_periods, "[1, 64]");
    if (lyapunov_periods < 1 || lyapunov_periods > 10000)
      fail("Lyapunov periods", lyapunov_periods, "[1, 10000]");
    if (settle_periods > 100000)
      fail("settle periods", settle_periods, "[0, 100000]");
    if (!(scene.excitation.frequency_hz > 0.))
      fail("Excitation/Frequency [Hz]", scene.excitation.frequency_hz, "(0, inf) (the orbits are periodic in the excitation)");
  }

  SlowManifoldSettings SlowManifoldSettings::for_scene(const Scene &scene)
  {
    SlowManifoldSettings s;
    std::tie(s.low_over_L, s.high_over_L) = default_held_position_range(scene);
    return s;
  }

  SlowManifold compute_slow_manifold(const Scene &scene, const SlowManifoldSettings &settings,
                                     const SlowManifoldObserver &observer)
  {
    settings.validate(scene);
    const auto start                = std::chrono::steady_clock::now();
    const ModelSetting setting      = scene_model(scene, "rom");
    const ReducedOrderModel rom     = make_reduced_model(scene, setting);
    SlowManifold result;
    result.model = "ROM N = " + std::to_string(rom.n_modes());
    auto progress = [&](const std::string &line) {
      if (observer.on_progress)
        observer.on_progress(line);
    };

    // The rattling held slider: probes up the range, each from the last state.
    RomBeamSystem beam(rom, scene.beam.thickness_profile(), BaseExcitation::from_scene(scene.excitation));
    require_stable_time_step(setting, beam);
    HeldSliderMap map(scene, beam, setting.time_step);
    Eigen::VectorXd y = map.resting(settings.low_over_L);
    const long n_probes =
      static_cast<long>(std::floor((settings.high_over_L - settings.low_over_L) / settings.probe_step_over_L + 1e-9));
    for (long i = 0; i <= n_probes && result.probe_stop.empty(); ++i)
      {
        if (interruption_requested())
          {
            result.probe_stop = "interrupted";
            break;
          }
        const double x = settings.low_over_L + i * settings.probe_step_over_L;
        try
          {
            // y from the probe before: its slider unknowns are relative to
            // the beam, so at the new x_C the slider is carried along.
            HeldSliderAttractor a = probe_held_slider_attractor(map, x, y, settings.settle_periods,
                                                                settings.section_periods, settings.lyapunov_periods);
            y                     = a.state;
            result.probes.push_back(a);
            if (observer.on_probe)
              observer.on_probe(a);
          }
        catch (const PeriodMapFailure &e)
          {
            result.probe_stop = "at x_C/L = " + std::to_string(x) + ": " + e.what();
          }
      }
    progress("attractor probes done (" + std::to_string(result.probes.size()) + "); continuing the attached model");

    result.attached     = continue_attached(scene, rom, settings, observer, result.attached_growth);
    result.wall_seconds = elapsed_seconds(start);
    return result;
  }
} // namespace beamslider
