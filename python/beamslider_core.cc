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
//                        the one scene reader (scene/scene_parameters_read.cc).
//   resolve_scene(name)  a scene name of meshes/ or a path, as the CLI
//                        resolves it.
//   Run, FEBeam, ReducedModel
//                        objects on the library itself (python/
//                        run_binding.cc, model_bindings.cc); __init__.py's
//                        classes of the same names are the part users read.
#include "io/interruption.h"
#include "scene/scene.h"
#include "verification/cli/command_line.h"
#include "verification/cli/commands.h"
#include "io/console.h"

#include <deal.II/base/multithread_info.h>

#include "python/bindings.h"

#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
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
  using beamslider_python::as_value_error;

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

  // Whether a command runs, under its own lock: interrupt() requests a stop
  // only then, and a command's end clears the request, so that no request
  // outlives its command (the solvers of the objects poll the same flag).
  std::mutex command_state;
  bool command_running = false;

  void interrupt_running_command()
  {
    const std::lock_guard<std::mutex> lock(command_state);
    if (command_running)
      beamslider::request_interruption(SIGINT);
  }

  void set_command_running(const bool running)
  {
    const std::lock_guard<std::mutex> lock(command_state);
    command_running = running;
    if (!running)
      beamslider::clear_interruption();
  }

} // namespace

std::tuple<int, std::string, int> beamslider_python::run_command(const std::vector<std::string> &args,
                                                                 py::object progress,
                                                                 beamslider::StudyHandover *handover)
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
    set_command_running(true);
    status = beamslider::run_beamslider(argc, argv.data(), errors, handover);
    signal = beamslider::interruption_signal();
    set_command_running(false);
  }
  to_python.raise_if_failed();
  return {status, errors.str(), signal};
}

namespace
{
  std::tuple<int, std::string, int> run(const std::vector<std::string> &args, py::object progress)
  {
    return beamslider_python::run_command(args, std::move(progress));
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

} // namespace

PYBIND11_MODULE(_core, m)
{
  m.doc() = "beamslider's command line in the Python process (use the package `beamslider`, not this module)";
  // As in the executable: deal.II's task parallelism on one thread; runs
  // parallelise over members and cells themselves.
  dealii::MultithreadInfo::set_thread_limit(1);
  m.def("run", &run, py::arg("args"), py::arg("progress") = py::none(),
        "Runs `beamslider ARGS...`; returns (exit status, error text, signal or 0).");
  m.def("interrupt", &interrupt_running_command,
        "Stops the running command at its next step, as Ctrl-C does; nothing when none runs.");
  m.def("scene_text", &scene_text, py::arg("path"), py::arg("overrides"),
        "The scene file's text after the overrides (\"Section/Name=value\").");
  m.def("scene_parameters", &scene_parameters, py::arg("path"), py::arg("overrides"),
        "Every parameter of the scene after the overrides, as {\"Section/Name\": text}.");
  m.def("resolve_scene", &resolve_scene, py::arg("scene"),
        "The path of a scene given by name (meshes/NAME.prm) or path.");
  beamslider_python::bind_run(m);
  beamslider_python::bind_models(m);
  beamslider_python::bind_solid(m);
  beamslider_python::bind_studies(m);
  beamslider_python::bind_branches(m);
}
