// The files of the held slider's slow manifold, see slow_manifold_files.h.
#include "verification/report/slow_manifold_files.h"

#include "io/console.h"
#include "io/csv_writer.h"

#include <cmath>
#include <sstream>

namespace beamslider
{
  SlowManifold run_slow_manifold_into(const Scene &scene, const SlowManifoldSettings &settings, const std::string &dir)
  {
    CsvWriter attractor(dir + "/attractor.csv",
                        {"x_over_L", "period_count", "beam_spread", "slider_spread", "lyapunov_per_period",
                         "lyapunov_per_s", "amplitude_over_h", "mean_fx_N"});
    CsvWriter branches(dir + "/branches.csv", {"x_over_L", "amplitude_over_h", "mean_fx_N", "stable",
                                               "largest_multiplier", "integration_growth", "period_count", "branch", "model"});
    const double f = scene.excitation.frequency_hz;
    SlowManifoldObserver observer;
    observer.on_probe = [&](const HeldSliderAttractor &a) {
      attractor.row({CsvWriter::cell(a.x_over_L), std::to_string(a.period_count), CsvWriter::cell(a.beam_spread),
                     CsvWriter::cell(a.slider_spread), CsvWriter::cell(a.lyapunov_per_period),
                     CsvWriter::cell(a.lyapunov_per_period * f), CsvWriter::cell(a.amplitude_over_h),
                     CsvWriter::cell(a.mean_fx)});
      attractor.flush();
      console() << "  probe x_C/L = " << a.x_over_L << ": period " << (a.period_count ? std::to_string(a.period_count) : "none")
                << ", Lyapunov " << a.lyapunov_per_period << " per period, amplitude " << a.amplitude_over_h << " h"
                << std::endl;
    };
    unsigned long n_orbits = 0;
    observer.on_orbit = [&](const OrbitPoint &p, const double growth) {
      branches.row({CsvWriter::cell(p.lambda), CsvWriter::cell(p.observables[0]), CsvWriter::cell(p.observables[1]),
                    p.stable() ? "1" : "0", CsvWriter::cell(p.largest_multiplier()),
                    std::isnan(growth) ? "" : CsvWriter::cell(growth), "1", "attached", "attached ROM"});
      if (++n_orbits % 200 == 0)
        {
          branches.flush();
          console() << "  attached model: " << n_orbits << " orbits, at x_C/L = " << p.lambda << std::endl;
        }
    };
    observer.on_progress = [](const std::string &line) { console() << "  " << line << std::endl; };
    const SlowManifold result = compute_slow_manifold(scene, settings, observer);
    attractor.close();
    branches.close();
    {
      CsvWriter events(dir + "/branch_events.csv", {"kind", "x_over_L", "amplitude_over_h", "mean_fx_N"});
      for (const auto &e : result.attached.events)
        events.row({to_string(e.kind), CsvWriter::cell(e.lambda), CsvWriter::cell(e.observables[0]),
                    CsvWriter::cell(e.observables[1])});
      events.close();
    }
    return result;
  }

  std::string describe_slow_manifold(const SlowManifold &m, const Scene &scene, const std::string &heading)
  {
    std::ostringstream s;
    const double f = scene.excitation.frequency_hz;
    unsigned int periodic = 0, chaotic = 0;
    for (const auto &p : m.probes)
      {
        periodic += p.period_count > 0;
        chaotic += p.period_count == 0 && p.lyapunov_per_period > 0.;
      }
    s << heading << " The rattling held slider (" << m.model << ")\n\n"
      << m.probes.size() << " probes; a periodic orbit (period ≤ 8 excitation periods) at " << periodic
      << "; no period and a positive largest Lyapunov exponent at " << chaotic
      << ": there the held slider's motion is chaotic and has no periodic orbit to shoot for (attractor.csv).\n\n"
      << "| x_C/L | period | section spread beam / slider | Lyapunov [1/period] | [1/s] | amplitude [h] | F̄_x [N] |\n"
      << "|---|---|---|---|---|---|---|\n";
    for (const auto &p : m.probes)
      s << "| " << p.x_over_L << " | " << (p.period_count ? std::to_string(p.period_count) : "none") << " | "
        << p.beam_spread << " / " << p.slider_spread << " | " << p.lyapunov_per_period << " | "
        << p.lyapunov_per_period * f << " | " << p.amplitude_over_h << " | " << p.mean_fx << " |\n";
    if (!m.probe_stop.empty())
      s << "\nThe probes stopped " << m.probe_stop << ".\n";

    s << "\n" << heading << " The attached-slider model (" << m.model << ", slider moving with the beam)\n\n";
    const Branch &b = m.attached;
    unsigned int stable = 0;
    double a_max = 0, x_at_max = 0;
    for (const auto &p : b.points)
      {
        stable += p.stable();
        if (p.observables[0] > a_max)
          {
            a_max    = p.observables[0];
            x_at_max = p.lambda;
          }
      }
    unsigned int checked = 0, agreeing = 0;
    for (std::size_t i = 0; i < b.points.size() && i < m.attached_growth.size(); ++i)
      if (!std::isnan(m.attached_growth[i]) && std::abs(b.points[i].largest_multiplier() - 1.) > 0.01)
        {
          ++checked;
          agreeing += (m.attached_growth[i] < 1.) == b.points[i].stable();
        }
    s << b.points.size() << " periodic orbits by shooting and arclength continuation (" << stable
      << " stable); largest amplitude " << a_max << " h at x_C/L = " << x_at_max << "; the continuation ended: "
      << b.end_reason << ". Stability by time integration started on the orbit (a small separation's growth per "
      << "period, integration_growth in branches.csv) agrees with the Floquet multipliers at " << agreeing << " of "
      << checked << " orbits checked (every 50th, those with |μ₁ − 1| > 0.01).\n\n";
    if (b.events.empty())
      s << "No turning point, period doubling or torus on the branch: one orbit at each x_C, no bistability in "
           "this model.\n";
    for (const auto &e : b.events)
      s << "- " << to_string(e.kind) << " at x_C/L = " << e.lambda << ", amplitude " << e.observables[0] << " h\n";
    s << "\nThe attached model's F̄_x is the frictionless share of the force that carries the slider (a sticking "
         "slider can hold itself by friction); compare its amplitudes with the rattling ones, not its forces.\n";
    return s.str();
  }
} // namespace beamslider
