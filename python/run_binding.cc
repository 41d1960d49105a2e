// beamslider.Run's compiled part: one free-slider run held in the Python
// process (verification/studies/simulation.h), stepped with the GIL
// released, its state, trace and periods as NumPy arrays, its verdict, and
// its checkpoint bytes.
#include "io/checkpoint.h"
#include "python/bindings.h"
#include "verification/studies/simulation.h"
#include "verification/studies/simulation_cases.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace beamslider_python
{
  namespace
  {
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
        if (!beamslider::ends_in_a_result(r.status) && r.status != beamslider::RunStatus::interrupted)
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
        // The last step's contact impulses per corner (rows: upper-left,
        // upper-right, lower-left, lower-right; columns: normal, tangential).
        Eigen::Matrix<double, beamslider::n_slider_corners, 2> impulses;
        std::vector<bool> in_contact;
        for (unsigned int k = 0; k < beamslider::n_slider_corners; ++k)
          {
            impulses.row(k) = simulation_->corner_impulses()[k].transpose();
            in_contact.push_back(impulses(k, 0) > 0);
          }
        d["contact_impulses"] = Eigen::MatrixXd(impulses);
        d["corners_in_contact"] = in_contact;
        return d;
      }

      py::dict trace() const
      {
        const auto held = hold();
        return columns(simulation_->trace(), beamslider::trace_csv_columns(), beamslider::trace_row_values);
      }

      py::dict periods() const
      {
        const auto held = hold();
        return columns(simulation_->periods(), beamslider::period_csv_columns(), beamslider::period_values);
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

  void bind_run(py::module_ &m)
  {
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
} // namespace beamslider_python
