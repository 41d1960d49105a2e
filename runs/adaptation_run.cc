// Free-slider and prescribed-position runs, see adaptation_run.h.
#include "runs/adaptation_run.h"
#include "numerics/elapsed.h"
#include "io/interruption.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  std::string to_string(const RunStatus status)
  {
    switch (status)
      {
        case RunStatus::completed:
          return "completed";
        case RunStatus::slider_at_support:
          return "slider_at_support";
        case RunStatus::contact_solver_failure:
          return "contact_solver_failure";
        case RunStatus::non_finite_state:
          return "non_finite_state";
        case RunStatus::beam_solver_failure:
          return "beam_solver_failure";
        case RunStatus::unphysical_state:
          return "unphysical_state";
        case RunStatus::interrupted:
          return "interrupted";
      }
    return "unknown";
  }

  // The scene's Solvers defaults (scene/scene.h) are the solver's own.
  static_assert(SolverData{}.contact_tolerance == ProxSolverSettings{}.tolerance &&
                  SolverData{}.contact_sweeps == ProxSolverSettings{}.max_iterations,
                "the default scene's contact-solver settings differ from ProxSolverSettings' defaults");

  RunOptions RunOptions::from_scene(const Scene &scene)
  {
    RunOptions o;
    o.end_time    = scene.time_stepping.end_time;
    o.time_step   = scene.time_stepping.time_step;
    o.output_rate = scene.time_stepping.output_rate;
    o.solver.method = scene.contact.solver == "exact-local" ? ProxSolverSettings::Method::exact_local
                                                            : ProxSolverSettings::Method::projected;
    o.solver.tolerance      = scene.solvers.contact_tolerance;
    o.solver.max_iterations = scene.solvers.contact_sweeps;
    return o;
  }

  RunOptions RunOptions::from_scene(const Scene &scene, const double time_step)
  {
    RunOptions o = from_scene(scene);
    o.time_step  = time_step;
    return o;
  }

  AdaptationRun::AdaptationRun(const Scene &scene, BeamSystem &beam, RunOptions options)
    : beam_(beam)
    , options_(options)
    , thickness_(beam.thickness())
    , stepper_(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene),
               BaseExcitation::from_scene(scene.excitation), options.time_step, options.solver)
  {
    const BaseExcitation base = BaseExcitation::from_scene(scene.excitation);
    period_ = std::isfinite(base.period()) ? base.period() : options_.period_without_excitation;
    if (!(options_.probe_position_over_L >= 0. && options_.probe_position_over_L <= 1.))
      {
        std::ostringstream m;
        m << "probe position x/L = " << options_.probe_position_over_L << " is outside [0, 1]";
        throw std::invalid_argument(m.str());
      }
    if (!(options_.output_rate >= 0.))
      {
        std::ostringstream m;
        m << "output rate = " << options_.output_rate << " 1/s is outside [0, inf)";
        throw std::invalid_argument(m.str());
      }
    const double x_C = scene.initial.slider_position_over_L * beam.length();
    beam.evaluate(0.5 * beam.length(), Eigen::VectorXd::Zero(beam.n_dofs()), point_);
    centre_grad_w_ = point_.grad_w;
    set_state(stepper_.resting_state(x_C, 0.));
    stepper_.set_prescribed_horizontal_position(options_.prescribed_slider_position);
  }

  void AdaptationRun::set_state(const SystemState &state)
  {
    stepper_.set_state(state);
    period_open_         = false;
    next_output_         = state.t;
    next_progress_       = state.t + options_.progress_interval;
    last_row_is_current_ = false;
  }

  void save_period(CheckpointWriter &out, const PeriodRecord &p)
  {
    out.put(std::uint64_t(p.index));
    for (const double x : {p.t_start, p.t_end, p.slider_x_over_L, p.amplitude_over_h, p.mean_horizontal_contact_force,
                           p.energy_start, p.energy_end, p.work_gravity, p.work_damping, p.work_excitation,
                           p.work_impact, p.work_friction, p.work_base_contact, p.energy_residual, p.contact_fraction})
      out.put(x);
    out.put(std::uint64_t(p.max_solver_iterations));
  }

  PeriodRecord load_period(CheckpointReader &in)
  {
    PeriodRecord p;
    p.index = in.get_uint();
    for (double *x : {&p.t_start, &p.t_end, &p.slider_x_over_L, &p.amplitude_over_h, &p.mean_horizontal_contact_force,
                      &p.energy_start, &p.energy_end, &p.work_gravity, &p.work_damping, &p.work_excitation,
                      &p.work_impact, &p.work_friction, &p.work_base_contact, &p.energy_residual, &p.contact_fraction})
      *x = in.get_double();
    p.max_solver_iterations = in.get_uint();
    return p;
  }
  std::array<double, 7> trace_row_values(const TraceRow &r)
  {
    return {{r.t, r.slider_x_over_L, r.slider_z, r.slider_beta, r.w_center, r.w_probe, r.amplitude_over_h}};
  }

  void save_trace_row(CheckpointWriter &out, const TraceRow &r)
  {
    for (const double x : trace_row_values(r))
      out.put(x);
  }

  TraceRow load_trace_row(CheckpointReader &in)
  {
    TraceRow r;
    for (double *x : {&r.t, &r.slider_x_over_L, &r.slider_z, &r.slider_beta, &r.w_center, &r.w_probe, &r.amplitude_over_h})
      *x = in.get_double();
    return r;
  }

  std::array<double, 17> period_values(const PeriodRecord &p)
  {
    return {{double(p.index), p.t_start, p.t_end, p.slider_x_over_L, p.amplitude_over_h,
             p.mean_horizontal_contact_force, p.energy_start, p.energy_end, p.work_gravity, p.work_damping,
             p.work_excitation, p.work_impact, p.work_friction, p.work_base_contact, p.energy_residual,
             double(p.max_solver_iterations), p.contact_fraction}};
  }


  void AdaptationRun::save(CheckpointWriter &out) const
  {
    stepper_.save(out);
    out.put(period_open_);
    save_period(out, current_);
    for (const double x : {w_min_, w_max_, x_sum_, impulse_x_, last_amplitude_over_h_, next_output_, next_progress_})
      out.put(x);
    out.put(std::uint64_t(period_steps_));
    out.put(std::uint64_t(contact_steps_));
    out.put(have_amplitude_);
    out.put(last_row_is_current_);
  }

  void AdaptationRun::load(CheckpointReader &in)
  {
    stepper_.load(in);
    period_open_ = in.get_bool();
    current_     = load_period(in);
    for (double *x : {&w_min_, &w_max_, &x_sum_, &impulse_x_, &last_amplitude_over_h_, &next_output_, &next_progress_})
      *x = in.get_double();
    period_steps_        = in.get_uint();
    contact_steps_       = in.get_uint();
    have_amplitude_      = in.get_bool();
    last_row_is_current_ = in.get_bool();
  }

  void AdaptationRun::set_slider_position(const double x_C)
  {
    set_state(stepper_.slider_moved_to(x_C));
  }

  void AdaptationRun::set_prescribed_slider_position(const bool prescribed)
  {
    options_.prescribed_slider_position = prescribed;
    stepper_.set_prescribed_horizontal_position(prescribed);
    period_open_ = false;
  }

  TraceRow AdaptationRun::make_row() const
  {
    const SystemState &s = stepper_.state();
    const double L       = beam_.length();
    TraceRow row;
    row.t               = s.t;
    row.slider_x_over_L = s.s[0] / L;
    row.slider_z        = s.s[1];
    row.slider_beta     = s.s[2];
    beam_.evaluate(0.5 * L, s.q, point_);
    row.w_center = point_.w;
    beam_.evaluate(options_.probe_position_over_L * L, s.q, point_);
    row.w_probe = point_.w;
    if (have_amplitude_)
      row.amplitude_over_h = last_amplitude_over_h_;
    else if (period_open_)
      row.amplitude_over_h = 0.5 * (w_max_ - w_min_) / thickness_;
    return row;
  }

  void AdaptationRun::begin_period(const double t)
  {
    const SystemState &s = stepper_.state();
    current_             = PeriodRecord();
    current_.index       = static_cast<unsigned int>(std::llround(t / period_));
    current_.t_start     = t;
    current_.energy_start = stepper_.beam_energy() + stepper_.slider_kinetic_energy();
    w_min_ = w_max_ = centre_grad_w_.dot(s.q);
    x_sum_ = impulse_x_ = 0;
    period_steps_ = contact_steps_ = 0;
    period_open_  = true;
  }

  void AdaptationRun::close_period(const double t)
  {
    PeriodRecord &p = current_;
    p.t_end         = t;
    p.energy_end    = stepper_.beam_energy() + stepper_.slider_kinetic_energy();
    const double duration = p.t_end - p.t_start;
    p.slider_x_over_L     = x_sum_ / std::max<unsigned long>(period_steps_, 1) / beam_.length();
    p.amplitude_over_h    = 0.5 * (w_max_ - w_min_) / thickness_;
    p.mean_horizontal_contact_force = impulse_x_ / duration;
    p.contact_fraction    = static_cast<double>(contact_steps_) / std::max<unsigned long>(period_steps_, 1);
    p.energy_residual     = (p.energy_end - p.energy_start) -
                        (p.work_gravity + p.work_damping + p.work_excitation + p.work_impact + p.work_friction +
                         p.work_base_contact);
    last_amplitude_over_h_ = p.amplitude_over_h;
    have_amplitude_        = true;
    period_open_           = false;
    if (on_period)
      on_period(p);
  }

  RunResult AdaptationRun::run()
  {
    RunResult result = run_until(options_.end_time);
    finish_trace();
    return result;
  }

  void AdaptationRun::finish_trace()
  {
    if (!last_row_is_current_ && on_trace_row)
      on_trace_row(make_row());
    last_row_is_current_ = true;
  }

  void AdaptationRun::emit_row_if_due(const double output_interval, const double eps)
  {
    const double t = stepper_.state().t;
    if (t + eps >= next_output_)
      {
        if (on_trace_row)
          on_trace_row(make_row());
        last_row_is_current_ = true;
        if (output_interval > 0.)
          while (next_output_ <= t + eps)
            next_output_ += output_interval;
        else
          next_output_ = t + eps;
      }
    else
      last_row_is_current_ = false;
  }

  bool AdaptationRun::stop_if_interrupted(RunResult &result) const
  {
    if (!options_.stop_on_request || !interruption_requested())
      return false;
    std::ostringstream m;
    m << "interrupted by signal " << interruption_signal() << " at t = " << stepper_.state().t
      << " s; every step up to then is complete";
    result.status  = RunStatus::interrupted;
    result.message = m.str();
    return true;
  }

  const StepReport *AdaptationRun::step_or_stop(RunResult &result)
  {
    const double t_B = stepper_.state().t;
    try
      {
        return &stepper_.step();
      }
    catch (const SliderAtSupport &e)
      {
        result.status  = RunStatus::slider_at_support;
        result.message = e.what();
      }
    catch (const ContactSolverFailure &e)
      {
        result.status  = RunStatus::contact_solver_failure;
        result.message = e.what();
      }
    catch (const NonFiniteState &e)
      {
        result.status  = RunStatus::non_finite_state;
        result.message = e.what();
      }
    catch (const UnphysicalState &e)
      {
        result.status  = RunStatus::unphysical_state;
        result.message = e.what();
      }
    catch (const std::runtime_error &e)
      {
        // The beam's own solver (e.g. the FE model's Newton iteration on
        // the von Kármán forces) gave up: the state before the step stays.
        std::ostringstream m;
        m << "the beam model failed in the step from t = " << t_B
          << " s (x_C/L = " << stepper_.state().s[0] / beam_.length() << "): " << e.what();
        result.status  = RunStatus::beam_solver_failure;
        result.message = m.str();
      }
    return nullptr;
  }

  void AdaptationRun::record_step(const StepReport &report, RunResult &result)
  {
    const SystemState &s = stepper_.state();
    ++result.n_steps;
    result.max_solver_iterations = std::max(result.max_solver_iterations, report.iterations);
    if (report.n_active > 0)
      ++result.n_contact_steps;
    result.solver_iterations += report.iterations;
    if (!period_open_)
      return;
    PeriodRecord &p = current_;
    p.work_gravity += report.work_gravity;
    p.work_damping += report.work_damping;
    p.work_excitation += report.work_excitation;
    p.work_impact += report.work_impact;
    p.work_friction += report.work_friction;
    p.work_base_contact += report.work_base_contact;
    p.max_solver_iterations = std::max(p.max_solver_iterations, report.iterations);
    impulse_x_ += report.slider_impulse[0];
    x_sum_ += s.s[0];
    ++period_steps_;
    if (report.n_active > 0)
      ++contact_steps_;
    const double w_centre = centre_grad_w_.dot(s.q);
    w_min_                = std::min(w_min_, w_centre);
    w_max_                = std::max(w_max_, w_centre);
  }

  RunResult AdaptationRun::run_until(const double t_end)
  {
    using clock      = std::chrono::steady_clock;
    const auto start = clock::now();
    const double dt  = stepper_.time_step();
    const double L   = beam_.length();
    RunResult result;

    const double t0            = stepper_.state().t;
    const unsigned long n_steps = t_end > t0 ? static_cast<unsigned long>(std::llround((t_end - t0) / dt)) : 0;
    const double output_interval = options_.output_rate > 0. ? 1. / options_.output_rate : 0.;
    const double eps             = 1e-9 * dt;

    // Periods run on the absolute grid k T; a run that starts off the grid
    // starts bookkeeping at the next grid point.
    auto on_grid = [&](const double t) { return std::abs(t - std::round(t / period_) * period_) < 0.5 * dt; };
    if (!period_open_ && on_grid(t0))
      begin_period(t0);
    emit_row_if_due(output_interval, eps);

    for (unsigned long k = 0; k < n_steps; ++k)
      {
        if (stop_if_interrupted(result))
          break;
        const double t_B         = stepper_.state().t;
        const StepReport *report = step_or_stop(result);
        if (!report)
          break;
        record_step(*report, result);

        // Period boundary crossed in this step?
        const SystemState &s = stepper_.state();
        if (std::floor(s.t / period_ + 1e-9) > std::floor(t_B / period_ + 1e-9))
          {
            if (period_open_)
              close_period(s.t);
            begin_period(s.t);
          }

        emit_row_if_due(output_interval, eps);

        if (on_progress && s.t + eps >= next_progress_)
          {
            const double wall = elapsed_seconds(start);
            RunProgress pr;
            pr.t                = s.t;
            pr.end_time         = t_end;
            pr.slider_x_over_L  = s.s[0] / L;
            pr.amplitude_over_h = last_amplitude_over_h_;
            pr.steps_per_second = wall > 0 ? result.n_steps / wall : 0.;
            on_progress(pr);
            while (next_progress_ <= s.t + eps)
              next_progress_ += options_.progress_interval;
          }
      }

    // A stopped run ends its trace with the last good state.
    if (result.status != RunStatus::completed)
      finish_trace();

    result.t_end            = stepper_.state().t;
    result.slider_x_over_L  = stepper_.state().s[0] / L;
    result.wall_seconds     = elapsed_seconds(start);
    result.steps_per_second = result.wall_seconds > 0 ? result.n_steps / result.wall_seconds : 0.;
    return result;
  }

  std::vector<std::string> trace_csv_columns()
  {
    return {"t_s", "slider_x_over_L", "slider_z_m", "slider_beta_rad", "w_center_m", "w_probe_m", "amplitude_over_h"};
  }

  void write_trace_row(CsvWriter &csv, const TraceRow &r)
  {
    const std::array<double, 7> values = trace_row_values(r);
    csv.numbers(std::vector<double>(values.begin(), values.end()), 10);
  }

  std::vector<std::string> period_csv_columns()
  {
    return {"period",           "t_start_s",         "t_end_s",         "slider_x_over_L",
            "amplitude_over_h", "mean_contact_force_x_N", "energy_start_J", "energy_end_J",
            "work_gravity_J",   "work_damping_J",    "work_excitation_J", "work_impact_J",
            "work_friction_J",  "work_base_contact_J", "energy_residual_J", "max_solver_iterations",
            "contact_fraction"};
  }

  void write_period_row(CsvWriter &csv, const PeriodRecord &p)
  {
    auto c = [](const double x) { return CsvWriter::cell(x, 10); };
    csv.row({CsvWriter::cell(p.index), c(p.t_start), c(p.t_end), c(p.slider_x_over_L), c(p.amplitude_over_h),
             c(p.mean_horizontal_contact_force), c(p.energy_start), c(p.energy_end), c(p.work_gravity),
             c(p.work_damping), c(p.work_excitation), c(p.work_impact), c(p.work_friction), c(p.work_base_contact),
             c(p.energy_residual), CsvWriter::cell(p.max_solver_iterations), c(p.contact_fraction)});
  }
} // namespace beamslider
