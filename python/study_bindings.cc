// beamslider's studies as objects (beamslider.Ensemble, Ladder, Sweep and Map): the
// command computes its study in this process and hands it over instead of
// writing it (verification/cli/commands.h, StudyHandover); the object holds
// it, gives its tables as NumPy arrays, and writes the command's folder only
// when asked (save), through the command itself, so that the files are those
// the command writes.
#include "python/bindings.h"
#include "verification/cli/commands.h"
#include "verification/cli/study_results.h"
#include "verification/report/map_files.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace beamslider_python
{
  namespace
  {
    using beamslider::EnsembleMember;

    constexpr double nan = std::numeric_limits<double>::quiet_NaN();

    // {name: array} from per-row values; an array of str where `text` says so.
    class Columns
    {
    public:
      void number(const std::string &name, const double x) { numbers_[name].push_back(x); order(name); }
      void text(const std::string &name, const std::string &x) { texts_[name].push_back(x); order(name); }
      py::dict dict() const
      {
        py::dict d;
        for (const std::string &name : names_)
          if (const auto n = numbers_.find(name); n != numbers_.end())
            d[py::str(name)] = py::array_t<double>(static_cast<py::ssize_t>(n->second.size()), n->second.data());
          else
            d[py::str(name)] = py::module_::import("numpy").attr("array")(texts_.at(name), "str");
        return d;
      }

    private:
      void order(const std::string &name)
      {
        if (std::find(names_.begin(), names_.end(), name) == names_.end())
          names_.push_back(name);
      }
      std::vector<std::string> names_;
      std::map<std::string, std::vector<double>> numbers_;
      std::map<std::string, std::vector<std::string>> texts_;
    };

    double or_nan(const bool happened, const double x) { return happened ? x : nan; }

    // The outcomes in members.csv's order, with their names.
    std::vector<std::pair<std::string, const std::vector<double> *>>
    named_outcomes(const beamslider::OutcomeSamples &s)
    {
      return {{"jump_time_s", &s.jump_time},
              {"turn_x_over_L", &s.turn_position},
              {"final_x_over_L", &s.final_position},
              {"final_amplitude_over_h", &s.final_amplitude}};
    }

    // A convergence check (convergence_check.h): whether it converged, its
    // verdict, and its trials (some of convergence.csv's columns).
    py::dict check_dict(const beamslider::ConvergenceCheck &check)
    {
      py::dict d;
      d["converged"] = check.converged;
      d["verdict"]   = check.verdict();
      Columns trials;
      for (const beamslider::ConvergenceTrial &t : check.trials)
        {
          trials.text("model", t.model.label());
          trials.number("time_step_s", t.model.time_step);
          trials.number("n_modes", t.model.n_modes);
          trials.number("members", t.members.size());
          trials.number("final_x_median", t.final_position.median);
          trials.number("wall_s_per_member", t.wall_seconds_per_member);
        }
      d["trials"] = trials.dict();
      return d;
    }

    // A study the command computed and handed over (see the top).
    class Study
    {
    public:
      Study(std::string command, std::shared_ptr<beamslider::StudyHandover> kept)
        : command_(std::move(command))
        , kept_(std::move(kept))
      {}

      const std::string &command() const { return command_; }

      // Writes the kept study through the command: `args` are those it was
      // computed with, and --output.
      std::tuple<int, std::string, int> save(const std::vector<std::string> &args, py::object progress)
      {
        beamslider::StudyHandover write;
        write.mode   = beamslider::StudyHandover::Mode::write;
        write.result = kept_->result;
        return run_command(args, std::move(progress), &write);
      }

      // --- ensemble ---
      py::dict members() const
      {
        Columns c;
        for (const EnsembleMember &m : ensemble().members)
          {
            const beamslider::TraceAnalysis &a = m.analysis;
            c.number("member", m.index);
            c.number("perturbation", m.perturbation);
            c.text("status", beamslider::to_string(m.result.status));
            c.number("jump_time_s", or_nan(a.jumped, a.jump_time));
            c.number("turn_x_over_L", or_nan(a.turned, a.turn_position));
            c.number("final_x_over_L", or_nan(a.valid, a.final_position));
            c.number("final_amplitude_over_h", or_nan(a.valid, a.final_amplitude));
            c.number("wall_s", m.wall_seconds);
            c.text("outcome", beamslider::to_string(a.outcome));
          }
        return c.dict();
      }

      py::dict member_periods() const
      {
        Columns c;
        for (const EnsembleMember &m : ensemble().members)
          for (const beamslider::PeriodRecord &p : m.periods)
            {
              c.number("member", m.index);
              c.number("t_s", p.t_end);
              c.number("x_over_L", p.slider_x_over_L);
              c.number("amplitude_over_h", p.amplitude_over_h);
            }
        return c.dict();
      }

      py::dict statistics() const
      {
        Columns c;
        const beamslider::OutcomeSamples samples = beamslider::outcome_samples(ensemble().members);
        for (const auto &[name, sample] : named_outcomes(samples))
          {
            const beamslider::OutcomeStatistics s = beamslider::statistics(name, *sample);
            c.text("outcome", name);
            c.number("n", s.n);
            for (const auto &[column, x] : {std::pair("median", s.median), std::pair("q1", s.q1), std::pair("q3", s.q3),
                                            std::pair("min", s.min), std::pair("max", s.max)})
              c.number(column, or_nan(s.n > 0, x));
          }
        return c.dict();
      }

      // Each outcome of this ensemble against `other`'s (compare_samples).
      py::dict compare_with(const beamslider::OutcomeSamples &other) const
      {
        const beamslider::OutcomeSamples mine = beamslider::outcome_samples(ensemble().members);
        const auto theirs                     = named_outcomes(other);
        const auto ours                       = named_outcomes(mine);
        std::vector<beamslider::SampleComparison> comparisons;
        {
          py::gil_scoped_release no_gil; // the bootstrap takes a moment
          for (std::size_t i = 0; i < ours.size(); ++i)
            comparisons.push_back(beamslider::compare_samples(*ours[i].second, *theirs[i].second));
        }
        Columns c;
        for (std::size_t i = 0; i < ours.size(); ++i)
          {
            const beamslider::SampleComparison &s = comparisons[i];
            c.text("outcome", ours[i].first);
            c.number("n_this", s.n_a);
            c.number("n_other", s.n_b);
            c.number("median_shift", s.shift);
            c.number("wasserstein", s.wasserstein);
            c.number("wasserstein_low", s.interval_low);
            c.number("wasserstein_high", s.interval_high);
            c.number("ks", s.ks);
            c.number("own_spread", s.spread);
            c.number("distinguishable", s.distinguishable ? 1 : 0);
          }
        return c.dict();
      }
      py::object comparison() const
      {
        const auto &against = ensemble().against;
        return against ? py::object(compare_with(*against)) : py::object(py::none());
      }
      py::dict compare(const Study &other) const
      {
        return compare_with(beamslider::outcome_samples(other.ensemble().members));
      }

      py::object convergence() const
      {
        const auto &check = ensemble().check;
        return check ? py::object(check_dict(*check)) : py::object(py::none());
      }
      std::string model() const { return ensemble().settings.model.label(); }
      double wall_seconds() const { return ensemble().wall_seconds; }

      // --- ladder: ladder.csv's, ladder_members.csv's, ladder_steps.csv's and
      // convergence.csv's columns ---
      py::dict ladder_rungs() const
      {
        Columns c;
        const beamslider::LadderStudy &study = ladder().study;
        for (std::size_t i = 0; i < study.rungs.size(); ++i)
          {
            const beamslider::LadderRungResult &r = study.rungs[i];
            const beamslider::ModelSetting &m     = r.rung.model;
            c.number("index", i);
            c.text("rung", r.rung.name);
            c.text("family", m.family);
            c.number("n_modes", m.family == "rom" ? m.n_modes : 0);
            c.number("n_elements", m.family == "fe" ? m.n_elements : 0);
            c.text("integrator", m.family == "rom" ? m.integrator : "implicit");
            c.number("time_step_s", m.time_step);
            c.number("damped_modes", m.damped_modes);
            c.number("reference", i == study.reference);
            c.number("members", r.members.size());
            c.number("failed", r.n_failed);
            c.number("wall_s_per_member", r.wall_seconds_per_member);
            c.number("cost_units", r.cost_units);
            for (const auto &[prefix, s, unit] : {std::tuple("final_x", &r.final_position, ""),
                                                  std::tuple("final_amplitude", &r.final_amplitude, ""),
                                                  std::tuple("jump", &r.jump_time, "_s")})
              {
                const std::string stem = std::string(prefix) == "jump" ? "jump_time" : prefix;
                c.number(std::string(prefix) + "_n", s->n);
                c.number(stem + "_median" + unit, or_nan(s->n > 0, s->median));
                c.number(stem + "_min" + unit, or_nan(s->n > 0, s->min));
                c.number(stem + "_max" + unit, or_nan(s->n > 0, s->max));
              }
            const beamslider::SampleComparison &d = r.position_to_reference;
            const bool compared                   = d.n_a > 0 && !std::isnan(d.wasserstein);
            c.number("w1_to_reference", or_nan(compared, d.wasserstein));
            c.number("w1_low", or_nan(compared, d.interval_low));
            c.number("w1_high", or_nan(compared, d.interval_high));
            c.number("spread", or_nan(compared, d.spread));
            c.number("distinguishable", or_nan(compared, d.distinguishable));
          }
        return c.dict();
      }
      py::dict ladder_members() const
      {
        Columns c;
        for (const beamslider::LadderRungResult &r : ladder().study.rungs)
          for (const EnsembleMember &m : r.members)
            {
              const beamslider::TraceAnalysis &a = m.analysis;
              c.text("rung", r.rung.name);
              c.number("member", m.index);
              c.number("perturbation", m.perturbation);
              c.text("status", beamslider::to_string(m.result.status));
              c.number("jump_time_s", or_nan(a.valid && a.jumped, a.jump_time));
              c.number("final_x_over_L", or_nan(a.valid, a.final_position));
              c.number("final_amplitude_over_h", or_nan(a.valid, a.final_amplitude));
              c.number("wall_s", m.wall_seconds);
              c.text("outcome", a.valid ? beamslider::to_string(a.outcome) : "");
            }
        return c.dict();
      }
      py::dict ladder_steps() const
      {
        Columns c;
        const beamslider::LadderStudy &study = ladder().study;
        for (std::size_t i = 1; i < study.rungs.size(); ++i)
          {
            const beamslider::SampleComparison &d = study.steps[i];
            if (d.n_a == 0)
              continue;
            c.text("from", study.rungs[i - 1].rung.name);
            c.text("to", study.rungs[i].rung.name);
            c.number("median_shift", study.rungs[i].final_position.median - study.rungs[i - 1].final_position.median);
            c.number("w1", d.wasserstein);
            c.number("w1_low", d.interval_low);
            c.number("w1_high", d.interval_high);
            c.number("spread", d.spread);
            c.number("distinguishable", d.distinguishable);
          }
        return c.dict();
      }
      py::dict ladder_checks() const
      {
        py::dict d;
        const beamslider::LadderStudy &study = ladder().study;
        for (std::size_t c = 0; c < study.checks.size(); ++c)
          {
            py::dict check = check_dict(study.checks[c]);
            check["claim"] = study.is_claim(c);
            d[py::str(study.checks[c].name)] = check;
          }
        return d;
      }
      // The rungs on the speed–accuracy front, in ascending cost.
      py::list ladder_front() const
      {
        py::list names;
        const beamslider::LadderStudy &study = ladder().study;
        for (const std::size_t i : beamslider::speed_accuracy_front(study))
          names.append(study.rungs[i].rung.name);
        return names;
      }

      // --- sweep ---
      py::dict pcs() const
      {
        Columns c;
        const beamslider::PcsStudy &s = sweep().study;
        for (const beamslider::PcsBranch *branch : {&s.up, &s.down})
          for (const beamslider::PcsPoint &p : branch->points)
            {
              c.number("x_over_L", p.x_over_L);
              c.text("direction", beamslider::to_string(p.direction));
              c.number("amplitude_over_h", p.amplitude_over_h);
              c.number("mean_fx_N", p.mean_fx);
              c.number("amplitude_std_over_h", p.amplitude_std_over_h);
              c.number("mean_fx_std_N", p.mean_fx_std);
              c.number("n_periods", p.n_periods);
              c.number("t_end_s", p.t_end);
              c.number("mean_fx_ci95_N", p.mean_fx_ci95);
            }
        return c.dict();
      }
      py::dict resonance() const
      {
        Columns c;
        for (const beamslider::ResonancePoint &r : sweep().study.resonance)
          {
            c.number("x_over_L", r.x_over_L);
            c.number("amplitude_over_h", std::isfinite(r.amplitude_over_h) ? r.amplitude_over_h : nan);
          }
        return c.dict();
      }
      py::dict free_periods() const
      {
        Columns c;
        const std::vector<std::string> names = beamslider::period_csv_columns();
        for (const beamslider::PeriodRecord &p : sweep().study.free_periods)
          {
            const auto values = beamslider::period_values(p);
            for (std::size_t i = 0; i < names.size(); ++i)
              c.number(names[i], values[i]);
          }
        return c.dict();
      }
      py::dict runs() const
      {
        Columns c;
        const beamslider::PcsStudy &s = sweep().study;
        for (const beamslider::PcsBranch *branch : {&s.up, &s.down})
          {
            c.text("run", beamslider::to_string(branch->direction));
            c.text("status", beamslider::to_string(branch->last_run.status));
            c.number("positions", branch->points.size());
            c.number("positions_planned", s.positions_planned);
            c.number("t_end_s", branch->last_run.t_end);
          }
        if (s.with_free_run)
          {
            c.text("run", "free");
            c.text("status", beamslider::to_string(s.free_run.status));
            c.number("positions", nan);
            c.number("positions_planned", nan);
            c.number("t_end_s", s.free_run.t_end);
          }
        return c.dict();
      }

      // --- map: map.csv's header and each computed cell's lines ---
      std::vector<std::string> map_columns() const { return beamslider::map_csv_columns(map().grid); }
      std::string map_rows() const
      {
        std::string all;
        for (const std::string &rows : map().rows)
          all += rows;
        return all;
      }
      std::size_t map_cells_done() const
      {
        std::size_t n = 0;
        for (const std::string &rows : map().rows)
          n += !rows.empty();
        return n;
      }
      std::size_t map_cells() const { return map().grid.n_cells(); }

    private:
      template <typename T>
      const T &kept(const char *kind) const
      {
        if (const T *t = std::any_cast<T>(&kept_->result))
          return *t;
        throw std::logic_error(std::string("this study is not ") + kind);
      }
      const beamslider::EnsembleRun &ensemble() const { return kept<beamslider::EnsembleRun>("an ensemble"); }
      const beamslider::SweepRun &sweep() const { return kept<beamslider::SweepRun>("a sweep"); }
      const beamslider::MapCells &map() const { return kept<beamslider::MapCells>("a map"); }
      const beamslider::LadderRun &ladder() const { return kept<beamslider::LadderRun>("a ladder"); }

      std::string command_;
      std::shared_ptr<beamslider::StudyHandover> kept_;
    };

    // Runs the command to compute its study; returns (status, error text,
    // signal, the study or None).
    std::tuple<int, std::string, int, py::object> compute(const std::vector<std::string> &args, py::object progress)
    {
      auto kept = std::make_shared<beamslider::StudyHandover>();
      const auto [status, errors, signal] = run_command(args, std::move(progress), kept.get());
      py::object study = py::none();
      if (kept->result.has_value())
        study = py::cast(Study(args.front(), kept));
      return {status, errors, signal, study};
    }
  } // namespace

  void bind_studies(py::module_ &m)
  {
    m.def("compute", &compute, py::arg("args"), py::arg("progress") = py::none(),
          "Runs `beamslider ARGS...` (ensemble, ladder, sweep or map) keeping its result in memory; returns (exit status, "
          "error text, signal or 0, the study or None).");
    py::class_<Study>(m, "Study", "A study computed in this process (use beamslider.Ensemble, Sweep, Map)")
      .def_property_readonly("command", &Study::command)
      .def("save", &Study::save, py::arg("args"), py::arg("progress") = py::none())
      .def("members", &Study::members)
      .def("member_periods", &Study::member_periods)
      .def("statistics", &Study::statistics)
      .def("comparison", &Study::comparison)
      .def("compare", &Study::compare, py::arg("other"))
      .def("convergence", &Study::convergence)
      .def("model", &Study::model)
      .def("wall_seconds", &Study::wall_seconds)
      .def("ladder_rungs", &Study::ladder_rungs)
      .def("ladder_members", &Study::ladder_members)
      .def("ladder_steps", &Study::ladder_steps)
      .def("ladder_checks", &Study::ladder_checks)
      .def("ladder_front", &Study::ladder_front)
      .def("pcs", &Study::pcs)
      .def("resonance", &Study::resonance)
      .def("free_periods", &Study::free_periods)
      .def("runs", &Study::runs)
      .def("map_columns", &Study::map_columns)
      .def("map_rows", &Study::map_rows)
      .def("map_cells_done", &Study::map_cells_done)
      .def("map_cells", &Study::map_cells);
  }
} // namespace beamslider_python
