// The free-slider ("self-adaptive") simulation of a scene on any BeamSystem,
// and the prescribed-position variant for the sweeps of seed §4.2–4.3
// (doc/physics.md §10): steps the MoreauStepper from the current state to an end
// time and reports, without ever holding the whole history in memory,
//   - trace rows, decimated to the scene's output rate (trace.csv columns
//     t_s, slider_x_over_L, slider_z_m, slider_beta_rad, w_center_m,
//     w_probe_m, amplitude_over_h);
//   - one record per excitation period: amplitude (peak-to-peak/2 of w(L/2)
//     over the period, divided by h), mean slider position, the
//     period-averaged horizontal contact force on the slider F̄_x, and the
//     energy balance (works of gravity, damping, base load, impacts,
//     friction, base-through-contacts, and the residual);
//   - progress.
// w is the beam's displacement relative to the moving base [m].
// A run that meets a support, a contact-solver failure, a non-finite or
// unphysical state, or an interruption (Ctrl-C, SIGTERM) stops cleanly after
// the last complete step with a status and a message that says when and
// where; rows and periods written before stay valid (writers flush regularly).
#pragma once

#include "contact/base_excitation.h"
#include "contact/beam_system.h"
#include "io/checkpoint.h"
#include "io/csv_writer.h"
#include "contact/moreau_stepper.h"
#include "scene/scene.h"

#include <array>
#include <functional>
#include <memory>
#include <vector>
#include <string>

namespace beamslider
{
  struct TraceRow
  {
    double t                = 0; // [s]
    double slider_x_over_L  = 0; // x_C / L [-]
    double slider_z         = 0; // z_C [m], absolute
    double slider_beta      = 0; // β [rad]
    double w_center         = 0; // w(L/2) relative to the base [m]
    double w_probe          = 0; // w(x_probe) relative to the base [m]
    // Amplitude of the last completed excitation period / h; during the first
    // period, of the part run so far [-].
    double amplitude_over_h = 0;
  };

  struct PeriodRecord
  {
    unsigned int index = 0;      // 0-based period number since the run's t = 0
    double t_start = 0, t_end = 0; // [s]
    double slider_x_over_L = 0;  // mean over the period [-]
    double amplitude_over_h = 0; // (max − min)/2 of w(L/2) / h [-]
    double mean_horizontal_contact_force = 0; // F̄_x on the slider, + toward x = L [N]
    double energy_start = 0, energy_end = 0;  // beam + slider kinetic [J]
    double work_gravity = 0, work_damping = 0, work_excitation = 0; // [J]
    double work_impact = 0, work_friction = 0, work_base_contact = 0; // [J]
    // (energy_end − energy_start) − Σ works: the discretisation error [J].
    double energy_residual = 0;
    unsigned int max_solver_iterations = 0;
    double contact_fraction = 0; // fraction of steps with ≥ 1 active corner [-]
  };

  // A period record in a checkpoint (checkpoint.h), bit for bit.
  void save_period(CheckpointWriter &out, const PeriodRecord &record);
  PeriodRecord load_period(CheckpointReader &in);

  // A trace row's values in trace_csv_columns()' order, and the row in a
  // checkpoint, bit for bit.
  std::array<double, 7> trace_row_values(const TraceRow &row);
  void save_trace_row(CheckpointWriter &out, const TraceRow &row);
  TraceRow load_trace_row(CheckpointReader &in);
  // A period record's values in period_csv_columns()' order (the counts as
  // doubles).
  std::array<double, 17> period_values(const PeriodRecord &record);

  struct RunProgress
  {
    double t = 0, end_time = 0;
    double slider_x_over_L = 0, amplitude_over_h = 0;
    double steps_per_second = 0; // wall-clock
  };

  enum class RunStatus
  {
    completed,
    slider_at_support,
    contact_solver_failure,
    non_finite_state,
    beam_solver_failure, // BeamSystem::free_velocity threw a std::runtime_error
    unphysical_state,    // the state left the physically possible set (UnphysicalState)
    interrupted          // SIGINT/SIGTERM arrived (interruption.h); the last step was finished
  };
  std::string to_string(RunStatus status);
  // Whether a run's end is a result of the scene: it completed, or the
  // slider reached a support (the run stops there by design). A failing
  // solver, a non-finite or unphysical state is not, and neither is an
  // interrupted run (partial).
  inline bool ends_in_a_result(const RunStatus status)
  {
    return status == RunStatus::completed || status == RunStatus::slider_at_support;
  }

  struct RunResult
  {
    RunStatus status = RunStatus::completed;
    std::string message;       // empty when completed
    double t_end = 0;          // time of the last accepted state [s]
    double slider_x_over_L = 0; // then
    unsigned long n_steps = 0;
    double wall_seconds = 0, steps_per_second = 0;
    unsigned int max_solver_iterations = 0;
    // Steps with an active contact (each one contact solve) and the contact
    // solver's iterations summed over them, for the benchmarks.
    unsigned long n_contact_steps = 0, solver_iterations = 0;
  };

  struct RunOptions
  {
    double end_time    = 60.;   // [s]
    // The model's time step [s]: from_scene(scene) gives the ROM's ('Time
    // stepping/Time step'), from_scene(scene, Δt) a model's own (the FE's
    // 'FE time step'). The scene's value is never overwritten for it.
    double time_step = 0.;
    double output_rate = 1000.; // trace rows per second [1/s]; 0: every step
    double probe_position_over_L = 4. / 7.;
    bool prescribed_slider_position = false; // hold x_C (seed §4.2)
    // Stop at the process's stop request (Ctrl-C, SIGTERM: numerics/
    // stop_request.h). False for a caller that steps in pieces and checks
    // for its own interruptions between them (the Python module's Run),
    // so that a request left from an earlier command cannot stop it.
    bool stop_on_request = true;
    ProxSolverSettings solver;
    double progress_interval = 1.; // simulated seconds between progress reports [s]
    // Period of the bookkeeping when the scene has no excitation [s].
    double period_without_excitation = 0.01;

    static RunOptions from_scene(const Scene &scene);
    // The same for a model that runs at its own `time_step` [s].
    static RunOptions from_scene(const Scene &scene, double time_step);
  };

  class AdaptationRun
  {
  public:
    // The beam must outlive the run. The initial state is the beam at rest and
    // the slider resting on it at the scene's x_C/L, t = 0. Throws
    // std::invalid_argument for a time step above the beam's stability limit.
    AdaptationRun(const Scene &scene, BeamSystem &beam, RunOptions options);

    std::function<void(const TraceRow &)> on_trace_row;
    std::function<void(const PeriodRecord &)> on_period;
    std::function<void(const RunProgress &)> on_progress;

    // Runs from the current state to options.end_time and ends the trace
    // with the last state (finish_trace).
    RunResult run();
    // Runs from the current state to t_end. Trace rows follow the output
    // grid across calls (a run in pieces writes the same rows as one run);
    // a run that stops early (any status but `completed`) ends its trace
    // with the last good state at once, a completed piece does not.
    RunResult run_until(double t_end);
    // Writes the current state as the last trace row unless it was just written.
    void finish_trace();

    // The run's whole state (stepper, beam model, period accumulators,
    // output cursors) for bit-identical checkpoints (checkpoint.h).
    void save(CheckpointWriter &out) const;
    void load(CheckpointReader &in);

    // State access, for sweeps that continue from the previous state.
    const SystemState &state() const { return stepper_.state(); }
    void set_state(const SystemState &state);
    // Carry the slider along the beam to x_C (MoreauStepper::slider_moved_to:
    // its gaps kept, no corner through the beam), e.g. one step Δx_C of a
    // prescribed-position sweep.
    void set_slider_position(double x_C);
    void set_prescribed_slider_position(bool prescribed);

    MoreauStepper &stepper() { return stepper_; }
    const RunOptions &options() const { return options_; }
    double period() const { return period_; }

  private:
    void begin_period(double t);
    void close_period(double t);
    TraceRow make_row() const;
    // The stages of run_until: a trace row if one is due on the output
    // grid (or every step for a zero interval); the check for an
    // interruption; one step of the stepper, or the status and message of
    // its failure (null then); the step's counts and works, into the result
    // and the open period.
    void emit_row_if_due(double output_interval, double eps);
    bool stop_if_interrupted(RunResult &result) const;
    const StepReport *step_or_stop(RunResult &result);
    void record_step(const StepReport &report, RunResult &result);

    BeamSystem &beam_;
    RunOptions options_;
    double thickness_;
    MoreauStepper stepper_;
    double period_;

    // Running period.
    bool period_open_ = false;
    PeriodRecord current_;
    double w_min_ = 0, w_max_ = 0, x_sum_ = 0, impulse_x_ = 0;
    unsigned long period_steps_ = 0, contact_steps_ = 0;
    double last_amplitude_over_h_ = 0;
    bool have_amplitude_          = false;

    // Output cursors: next trace row and progress report [s]; whether the
    // last trace row shows the current state.
    double next_output_        = 0;
    double next_progress_      = 0;
    bool last_row_is_current_  = false;
    mutable BeamPointKinematics point_;
    Eigen::VectorXd centre_grad_w_; // ∂w(L/2)/∂q: the centre's deflection, tracked every step, is its dot with q
  };

  // trace.csv and periods.csv (written through CsvWriter): their columns
  // and one row of a TraceRow / PeriodRecord, 10 significant digits (a
  // resumed run's rows must equal those of an uninterrupted one).
  std::vector<std::string> trace_csv_columns();
  void write_trace_row(CsvWriter &csv, const TraceRow &row);
  std::vector<std::string> period_csv_columns();
  void write_period_row(CsvWriter &csv, const PeriodRecord &record);
} // namespace beamslider
