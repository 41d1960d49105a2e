// One free-slider run held in memory and stepped by its caller: the model
// of a setting on a scene, the run from rest at t = 0, and the trace rows
// and period records it has produced so far. It is the run `beamslider
// simulate` makes (the same model, options and steps; simulate streams the
// rows to trace.csv and periods.csv instead of keeping them), so a
// Simulation advanced to T holds the rows `simulate` writes for End time T.
// The Python module's Run is this object.
#pragma once

#include "numerics/state_bytes.h"
#include "runs/adaptation_run.h"
#include "runs/trace_analysis.h"
#include "verification/studies/fe_rom_study.h"

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace beamslider
{
  // The first line in which two texts (a scene's, a run's identity) differ,
  // now's and then's, "(end)" for a text that ended first; none if equal.
  // How a checkpoint of another run says what changed.
  std::optional<std::pair<std::string, std::string>> first_differing_lines(const std::string &now,
                                                                           const std::string &then);

  class Simulation
  {
  public:
    // Builds the setting's model for the scene (InputError for a time step
    // above its stability limit) and puts the slider at rest on the beam
    // at the scene's start position, t = 0.
    Simulation(const Scene &scene, const ModelSetting &setting);
    ~Simulation();

    const Scene &scene() const { return scene_; }
    const ModelSetting &setting() const { return setting_; }
    double time() const { return run_->state().t; }
    double time_step() const { return setting_.time_step; }
    const SystemState &state() const { return run_->state(); }
    // The contact impulses (P_N, P_T) [N s] of each slider corner in the
    // last step, zero at a corner not in contact; corners in the order
    // upper-left, upper-right, lower-left, lower-right (contact/slider_contact.h).
    const std::array<Eigen::Vector2d, n_slider_corners> &corner_impulses() const
    {
      return run_->stepper().corner_impulses();
    }
    const BeamSystem &model() const { return *beam_; }

    // Takes n steps, fewer if the run stops (a support reached, a solver
    // failure: the result's status and message say which and when). A
    // stopped run takes no more steps: the result is the stopping one.
    // The process's stop request does not stop it: a caller that wants to
    // be interruptible steps in pieces and checks between them.
    RunResult step(unsigned long n);
    // Whether a step failed or the slider reached a support.
    bool stopped() const { return stopped_; }
    // The result of the last call to step.
    const RunResult &last_result() const { return last_; }

    // Trace rows at the scene's output rate, the state at t = 0 first, and
    // the closed excitation periods (runs/adaptation_run.h).
    const std::vector<TraceRow> &trace() const { return rows_; }
    const std::vector<PeriodRecord> &periods() const { return periods_; }

    // The run so far read as `simulate` reads it (runs/trace_analysis.h),
    // with the scene's thresholds.
    TraceAnalysis analyse() const;

    // The whole run (its setting, the scene as scene_file_text writes it,
    // the model's and the run's state, the rows and periods) for a
    // checkpoint, and back: load refuses (InputError) a checkpoint of
    // another scene, naming the first parameter line that differs.
    void save(CheckpointWriter &out) const;
    static std::unique_ptr<Simulation> load(CheckpointReader &in, const Scene &scene);

  private:
    Scene scene_;
    ModelSetting setting_;
    std::unique_ptr<BeamSystem> beam_;
    std::unique_ptr<AdaptationRun> run_;
    std::vector<TraceRow> rows_;
    std::vector<PeriodRecord> periods_;
    RunResult last_;
    bool stopped_ = false;
  };
} // namespace beamslider
