// beamslider.Branches' compiled part: the held slider's slow manifold
// (verification/studies/slow_manifold.h) computed in the Python process by
// the study itself, with the GIL released, and returned as NumPy columns.
// No command line in between: the study's settings are checked by the
// study (SlowManifoldSettings::validate), bad ones raise ValueError.
#include "python/bindings.h"
#include "verification/studies/slow_manifold.h"

#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace beamslider_python
{
  namespace
  {
    py::dict compute_branches(const std::string &path, const std::vector<std::string> &overrides, py::object low,
                              py::object high, const double probe_step, const unsigned int settle_periods)
    {
      beamslider::SlowManifold m;
      const beamslider::Scene scene = as_value_error([&] { return beamslider::read_scene(path, overrides); });
      beamslider::SlowManifoldSettings s = beamslider::SlowManifoldSettings::for_scene(scene);
      if (!low.is_none())
        s.low_over_L = low.cast<double>();
      if (!high.is_none())
        s.high_over_L = high.cast<double>();
      s.probe_step_over_L = probe_step;
      s.settle_periods    = settle_periods;
      as_value_error([&] {
        s.validate(scene);
        return 0;
      });
      {
        py::gil_scoped_release released;
        m = beamslider::compute_slow_manifold(scene, s);
      }
      py::dict out;
      out["model"]        = m.model;
      out["probe_stop"]   = m.probe_stop;
      out["end_reason"]   = m.attached.end_reason;
      out["wall_seconds"] = m.wall_seconds;
      const double f      = scene.excitation.frequency_hz;
      out["attractor"]    = columns(m.probes,
                                 {"x_over_L", "period_count", "beam_spread", "slider_spread", "lyapunov_per_period",
                                  "lyapunov_per_s", "amplitude_over_h", "mean_fx_N"},
                                 [f](const beamslider::HeldSliderAttractor &a) {
                                   return std::vector<double>{a.x_over_L, double(a.period_count), a.beam_spread,
                                                              a.slider_spread, a.lyapunov_per_period,
                                                              a.lyapunov_per_period * f, a.amplitude_over_h, a.mean_fx};
                                 });
      out["branches"] = columns(m.attached.points,
                                {"x_over_L", "amplitude_over_h", "mean_fx_N", "stable", "largest_multiplier"},
                                [](const beamslider::OrbitPoint &p) {
                                  return std::vector<double>{p.lambda, p.observables[0], p.observables[1],
                                                             p.stable() ? 1. : 0., p.largest_multiplier()};
                                });
      {
        py::array_t<double> growth(static_cast<py::ssize_t>(m.attached_growth.size()));
        for (std::size_t i = 0; i < m.attached_growth.size(); ++i)
          growth.mutable_at(static_cast<py::ssize_t>(i)) = m.attached_growth[i];
        out["branches"].cast<py::dict>()["integration_growth"] = growth;
      }
      py::list events;
      for (const auto &e : m.attached.events)
        events.append(py::make_tuple(beamslider::to_string(e.kind), e.lambda, e.observables[0], e.observables[1]));
      out["events"] = events;
      return out;
    }
  } // namespace

  void bind_branches(py::module_ &m)
  {
    m.def("compute_branches", &compute_branches, py::arg("path"), py::arg("overrides"), py::arg("low"),
          py::arg("high"), py::arg("probe_step"), py::arg("settle_periods"),
          "The held slider's slow manifold (the study of `beamslider branches`), as NumPy columns.");
  }
} // namespace beamslider_python
