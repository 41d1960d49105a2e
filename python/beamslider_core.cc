// The compiled part of the Python module `beamslider` (python/beamslider/
// __init__.py is the part users read). It runs beamslider's sub-commands in
// the Python process through the same command line as the executable
// (verification/cli/command_line.h), so that a study from Python is the same
// run, with the same checks, messages and files, as from the shell:
//
//   run(args, progress)  runs `beamslider args...` with the GIL released;
//                        returns (exit status, the error lines, the signal
//                        that stopped it or 0). Ctrl-C (SIGINT) and SIGTERM
//                        stop the run at its next step, as in the shell;
//                        Python's own handlers are back when it returns.
//                        progress(line) gets each progress line.
//   interrupt()          stops the running command from another thread.
//   scene_text(path, overrides)
//                        the scene after the overrides, in the scene-file
//                        format (bad values raise ValueError with the CLI's
//                        message).
//   scene_parameters(path, overrides)
//                        the same scene as {"Section/Name": text}, read by
//                        the one scene reader (meshes/scene_parameters.cc).
//   resolve_scene(name)  a scene name of meshes/ or a path, as the CLI
//                        resolves it.
//   Run(path, overrides, model)
//                        one free-slider run held in this process and
//                        stepped from Python (verification/studies/
//                        simulation.h): step(n) with the GIL released, the
//                        state, trace and periods as NumPy arrays, the
//                        verdict, checkpoint bytes (python/beamslider/
//                        __init__.py's Run is the part users read).
#include "io/interruption.h"
#include "meshes/scene.h"
#include "verification/cli/command_line.h"
#include "verification/cli/commands.h"
#include "verification/studies/simulation.h"
#include "io/checkpoint.h"
#include "io/console.h"

#include <deal.II/base/multithread_info.h>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <atomic>
#include <csignal>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace py = pybind11;

namespace
{
  // Python's handlers of the signals the run takes over, restored when the
  // run returns (also by an exception).
  class SignalHandlersOfTheRun
  {
  public:
    SignalHandlersOfTheRun()
    {
      for (std::size_t i = 0; i < signals.size(); ++i)
        sigaction(signals[i], nullptr, &saved[i]);
      beamslider::clear_interruption();
      beamslider::install_interruption_handlers();
    }
    ~SignalHandlersOfTheRun()
    {
      for (std::size_t i = 0; i < signals.size(); ++i)
        sigaction(signals[i], &saved[i], nullptr);
    }

  private:
    static constexpr std::array<int, 4> signals = {{SIGINT, SIGTERM, SIGXFSZ, SIGPIPE}};
    std::array<struct sigaction, 4> saved{};
  };

  // Progress lines to a Python callable; an exception it raises stops the
  // run and is raised again once the run has returned.
  class ProgressToPython
  {
  public:
    explicit ProgressToPython(py::object callback)
      : callback_(std::move(callback))
    {
      if (callback_.is_none())
        return;
      beamslider::set_console_sink([this](const std::string &line) {
        const std::lock_guard<std::mutex> lock(mutex_); // members may report from several threads
        py::gil_scoped_acquire gil;
        if (error_)
          return;
        try
          {
            callback_(line);
          }
        catch (py::error_already_set &e)
          {
            error_.emplace(std::move(e));
            beamslider::request_interruption(SIGINT);
          }
      });
    }
    ~ProgressToPython() { beamslider::set_console_sink({}); }

    void raise_if_failed()
    {
      if (error_)
        {
          py::error_already_set e = std::move(*error_);
          error_.reset();
          throw e;
        }
    }

  private:
    py::object callback_;
    std::mutex mutex_;
    std::optional<py::error_already_set> error_;
  };

  // One command at a time: the commands keep process-wide settings (the
  // console, the interruption flag, the recorded command line).
  std::mutex one_command_at_a_time;

  std::tuple<int, std::string, int> run(const std::vector<std::string> &args, py::object progress)
  {
    std::unique_lock<std::mutex> running(one_command_at_a_time, std::try_to_lock);
    if (!running.owns_lock())
      throw std::runtime_error("another beamslider command is running in this process; run one at a time (studies "
                               "spread over the cores themselves)");
    std::vector<std::string> words = {"beamslider"};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char *> argv;
    for (std::string &w : words)
      argv.push_back(w.data());
    argv.push_back(nullptr);
    const int argc = static_cast<int>(words.size());

    beamslider::record_command_line(argc, argv.data());
    ProgressToPython to_python(std::move(progress));
    std::ostringstream errors;
    int status = 0, signal = 0;
    {
      SignalHandlersOfTheRun handlers;
      py::gil_scoped_release no_gil;
      status = beamslider::run_beamslider(argc, argv.data(), errors);
      signal = beamslider::interruption_signal();
    }
    to_python.raise_if_failed();
    return {status, errors.str(), signal};
  }

  // Bad input as ValueError with the line the command line prints for it.
  template <typename F>
  auto as_value_error(F &&f)
  {
    try
      {
        return f();
      }
    catch (const beamslider::InputError &e)
      {
        const std::string what = e.what();
        throw py::value_error("error: " + what.substr(0, what.find('\n')));
      }
    catch (const std::invalid_argument &e)
      {
        const std::string what = e.what();
        throw py::value_error("error: " + what.substr(0, what.find('\n')));
      }
  }

  std::string scene_text(const std::string &path, const std::vector<std::string> &overrides)
  {
    return as_value_error([&] { return beamslider::scene_file_text(beamslider::read_scene(path, overrides)); });
  }

  std::map<std::string, std::string> scene_parameters(const std::string &path, const std::vector<std::string> &overrides)
  {
    return as_value_error(
      [&] { return beamslider::scene_parameter_values(beamslider::read_scene(path, overrides)); });
  }

  std::string resolve_scene(const std::string &scene)
  {
    return as_value_error([&] { return beamslider::resolve_scene_path(scene); });
  }

  // Columns of records as {name: float array}, one array per member.
  template <typename Record>
  py::dict columns(const std::vector<Record> &records, const std::vector<std::string> &names,
                   const std::vector<double (*)(const Record &)> &fields)
  {
    py::dict out;
    for (std::size_t c = 0; c < names.size(); ++c)
      {
        py::array_t<double> a(static_cast<py::ssize_t>(records.size()));
        auto view = a.mutable_unchecked<1>();
        for (std::size_t i = 0; i < records.size(); ++i)
          view(static_cast<py::ssize_t>(i)) = fields[c](records[i]);
        out[py::str(names[c])] = a;
      }
    return out;
  }

  // A run in this process (see the top). Steps go in pieces with the GIL
  // released; between pieces Python's signal handlers run, so Ctrl-C raises
  // KeyboardInterrupt with the run at the end of a whole piece, intact.
  class Run
  {
  public:
    Run(const std::string &path, const std::vector<std::string> &overrides, const std::string &model)
      : path_(path)
      , overrides_(overrides)
    {
      as_value_error([&] {
        const beamslider::Scene scene = beamslider::read_scene(path, overrides);
        simulation_ = std::make_unique<beamslider::Simulation>(scene, beamslider::scene_model(scene, model));
        return 0;
      });
    }

    Run(std::string path, std::vector<std::string> overrides, std::unique_ptr<beamslider::Simulation> simulation)
      : path_(std::move(path))
      , overrides_(std::move(overrides))
      , simulation_(std::move(simulation))
      , time_(simulation_->time())
    {}

    const std::string &scene_path() const { return path_; }
    const std::vector<std::string> &overrides() const { return overrides_; }

    // n steps; returns the run's status. A failed step raises RuntimeError
    // with the solver's message (the run keeps its last good state).
    std::string step(unsigned long n)
    {
      const auto held = hold();
      // About a millisecond of the published ROM, 30 ms of the FE beam.
      constexpr unsigned long piece = 1024;
      while (n > 0 && !simulation_->stopped())
        {
          const unsigned long k = std::min(n, piece);
          {
            py::gil_scoped_release no_gil;
            simulation_->step(k);
          }
          time_ = simulation_->time();
          n -= k;
          if (PyErr_CheckSignals() != 0)
            throw py::error_already_set();
        }
      const beamslider::RunResult &r = simulation_->last_result();
      if (r.status != beamslider::RunStatus::completed && r.status != beamslider::RunStatus::slider_at_support &&
          r.status != beamslider::RunStatus::interrupted)
        throw std::runtime_error(beamslider::to_string(r.status) + ": " + r.message);
      return beamslider::to_string(r.status);
    }

    std::string status() const
    {
      const auto held = hold();
      return beamslider::to_string(simulation_->last_result().status);
    }
    std::string message() const
    {
      const auto held = hold();
      return simulation_->last_result().message;
    }
    // The time at the end of the last whole piece: readable while another
    // thread steps (a progress bar's).
    double time() const { return time_; }
    double time_step() const { return simulation_->time_step(); }
    std::string model() const { return simulation_->setting().label(); }

    py::dict state() const
    {
      const auto held                  = hold();
      const beamslider::SystemState &s = simulation_->state();
      const double L                   = simulation_->scene().beam.length;
      py::dict d;
      d["t"]               = s.t;
      d["q"]               = Eigen::VectorXd(s.q);
      d["u"]               = Eigen::VectorXd(s.u);
      d["slider_x_over_L"] = s.s[0] / L;
      d["slider_x"]        = s.s[0];
      d["slider_z"]        = s.s[1];
      d["slider_beta"]     = s.s[2];
      d["slider_velocity"] = Eigen::Vector3d(s.v);
      return d;
    }

    py::dict trace() const
    {
      using R         = beamslider::TraceRow;
      const auto held = hold();
      return columns<R>(simulation_->trace(), beamslider::trace_csv_columns(),
                        {[](const R &r) { return r.t; }, [](const R &r) { return r.slider_x_over_L; },
                         [](const R &r) { return r.slider_z; }, [](const R &r) { return r.slider_beta; },
                         [](const R &r) { return r.w_center; }, [](const R &r) { return r.w_probe; },
                         [](const R &r) { return r.amplitude_over_h; }});
    }

    py::dict periods() const
    {
      using P         = beamslider::PeriodRecord;
      const auto held = hold();
      return columns<P>(
        simulation_->periods(), beamslider::period_csv_columns(),
        {[](const P &p) { return double(p.index); }, [](const P &p) { return p.t_start; },
         [](const P &p) { return p.t_end; }, [](const P &p) { return p.slider_x_over_L; },
         [](const P &p) { return p.amplitude_over_h; }, [](const P &p) { return p.mean_horizontal_contact_force; },
         [](const P &p) { return p.energy_start; }, [](const P &p) { return p.energy_end; },
         [](const P &p) { return p.work_gravity; }, [](const P &p) { return p.work_damping; },
         [](const P &p) { return p.work_excitation; }, [](const P &p) { return p.work_impact; },
         [](const P &p) { return p.work_friction; }, [](const P &p) { return p.work_base_contact; },
         [](const P &p) { return p.energy_residual; }, [](const P &p) { return double(p.max_solver_iterations); },
         [](const P &p) { return p.contact_fraction; }});
    }

    py::dict analyse() const
    {
      const auto held                   = hold();
      const beamslider::TraceAnalysis a = simulation_->analyse();
      py::dict d;
      d["verdict"]           = a.line;
      d["outcome"]           = beamslider::to_string(a.outcome);
      d["valid"]             = a.valid;
      d["initial_direction"] = a.initial_direction;
      d["jumped"]            = a.jumped;
      d["jump_time"]         = a.jump_time;
      d["turned"]            = a.turned;
      d["final_position"]    = a.final_position;
      d["final_amplitude"]   = a.final_amplitude;
      d["adaptation_time"]   = a.adaptation_time;
      return d;
    }

    // The run's checkpoint file (io/checkpoint.h) with the scene's source
    // in front, and back.
    py::bytes checkpoint() const
    {
      const auto held = hold();
      beamslider::CheckpointWriter out;
      out.put(std::string("beamslider Run"));
      out.put(path_);
      out.put(std::uint64_t(overrides_.size()));
      for (const std::string &o : overrides_)
        out.put(o);
      simulation_->save(out);
      return py::bytes(beamslider::checkpoint_file_bytes(out.bytes()));
    }

    static std::unique_ptr<Run> resume(const std::string &file)
    {
      return as_value_error([&] {
        try
          {
            beamslider::CheckpointReader in(beamslider::read_checkpoint_file(file));
            if (in.get_string() != "beamslider Run")
              throw beamslider::InputError("'" + file + "' is not the checkpoint of a Python Run");
            const std::string path = in.get_string();
            std::vector<std::string> overrides(in.get_count(sizeof(std::uint64_t)));
            for (std::string &o : overrides)
              o = in.get_string();
            const beamslider::Scene scene = beamslider::read_scene(path, overrides);
            return std::make_unique<Run>(path, overrides, beamslider::Simulation::load(in, scene));
          }
        catch (const beamslider::CheckpointError &e)
          {
            throw beamslider::InputError(std::string("'") + file + "': " + e.what());
          }
      });
    }

  private:
    // The run for this call: refused while another thread steps it (that
    // thread has released the GIL; waiting here with the GIL would
    // deadlock).
    std::unique_lock<std::mutex> hold() const
    {
      std::unique_lock<std::mutex> lock(busy_, std::try_to_lock);
      if (!lock.owns_lock())
        throw std::runtime_error("this Run is being stepped by another thread; read it when the step returns");
      return lock;
    }

    std::string path_;
    std::vector<std::string> overrides_;
    std::unique_ptr<beamslider::Simulation> simulation_;
    std::atomic<double> time_{0.};
    mutable std::mutex busy_;
  };
} // namespace

PYBIND11_MODULE(_core, m)
{
  m.doc() = "beamslider's command line in the Python process (use the package `beamslider`, not this module)";
  // As in the executable: deal.II's task parallelism on one thread; runs
  // parallelise over members and cells themselves.
  dealii::MultithreadInfo::set_thread_limit(1);
  m.def("run", &run, py::arg("args"), py::arg("progress") = py::none(),
        "Runs `beamslider ARGS...`; returns (exit status, error text, signal or 0).");
  m.def("interrupt", [] { beamslider::request_interruption(SIGINT); },
        "Stops the running command at its next step, as Ctrl-C does.");
  m.def("scene_text", &scene_text, py::arg("path"), py::arg("overrides"),
        "The scene file's text after the overrides (\"Section/Name=value\").");
  m.def("scene_parameters", &scene_parameters, py::arg("path"), py::arg("overrides"),
        "Every parameter of the scene after the overrides, as {\"Section/Name\": text}.");
  m.def("resolve_scene", &resolve_scene, py::arg("scene"),
        "The path of a scene given by name (meshes/NAME.prm) or path.");
  py::class_<Run>(m, "Run", "One free-slider run in this process (use beamslider.Run)")
    .def(py::init<const std::string &, const std::vector<std::string> &, const std::string &>(), py::arg("path"),
         py::arg("overrides"), py::arg("model"))
    .def("step", &Run::step, py::arg("n"))
    .def_property_readonly("status", &Run::status)
    .def_property_readonly("message", &Run::message)
    .def_property_readonly("t", &Run::time)
    .def_property_readonly("time_step", &Run::time_step)
    .def_property_readonly("model", &Run::model)
    .def_property_readonly("state", &Run::state)
    .def_property_readonly("trace", &Run::trace)
    .def_property_readonly("periods", &Run::periods)
    .def("analyse", &Run::analyse)
    .def_property_readonly("scene_path", &Run::scene_path)
    .def_property_readonly("overrides", &Run::overrides)
    .def("checkpoint_bytes", &Run::checkpoint)
    .def_static("resume", &Run::resume, py::arg("file"));
}
