// One free-slider run in memory, see simulation.h.
#include "verification/studies/simulation.h"

#include "contact/beam_system.h"
#include "verification/studies/simulation_cases.h"

#include <sstream>

namespace beamslider
{
  Simulation::Simulation(const Scene &scene, const ModelSetting &setting)
    : scene_(scene)
    , setting_(setting)
    , beam_(make_beam_model(scene, setting))
  {
    require_stable_time_step(setting_, *beam_);
    RunOptions options        = RunOptions::from_scene(scene_, setting_.time_step);
    options.progress_interval = 1e300; // the caller steps in pieces and sees the time itself
    options.stop_on_request   = false; // ... and checks for its own interruptions between them
    run_                 = std::make_unique<AdaptationRun>(scene_, *beam_, options);
    run_->on_trace_row = [this](const TraceRow &row) { rows_.push_back(row); };
    run_->on_period    = [this](const PeriodRecord &p) { periods_.push_back(p); };
    // The state at t = 0, as simulate's trace starts with it.
    run_->run_until(0.);
  }

  Simulation::~Simulation() = default;

  std::optional<std::pair<std::string, std::string>> first_differing_lines(const std::string &now,
                                                                           const std::string &then)
  {
    std::istringstream x(now), y(then);
    std::string a, b;
    while (true)
      {
        const bool more_a = static_cast<bool>(std::getline(x, a)), more_b = static_cast<bool>(std::getline(y, b));
        if (!more_a && !more_b)
          return std::nullopt;
        if (!more_a || !more_b || a != b)
          return std::make_pair(more_a ? a : std::string("(end)"), more_b ? b : std::string("(end)"));
      }
  }

  RunResult Simulation::step(const unsigned long n)
  {
    if (stopped_ || n == 0)
      return last_;
    // run_until takes llround((t_end − t)/Δt) steps: exactly n.
    last_    = run_->run_until(time() + static_cast<double>(n) * setting_.time_step);
    stopped_ = last_.status != RunStatus::completed && last_.status != RunStatus::interrupted;
    return last_;
  }

  TraceAnalysis Simulation::analyse() const
  {
    return case_verdict(periods_, last_, trace_thresholds(scene_));
  }

  void Simulation::save(CheckpointWriter &out) const
  {
    save_setting(out, setting_);
    out.put(scene_file_text(scene_));
    out.put(stopped_);
    // The last result, so that a resumed run that had failed says so (and
    // takes no step), as the run it continues would.
    out.put(std::uint64_t(last_.status));
    out.put(last_.message);
    out.put(last_.t_end);
    out.put(last_.slider_x_over_L);
    run_->save(out);
    out.put(std::uint64_t(rows_.size()));
    for (const TraceRow &r : rows_)
      save_trace_row(out, r);
    out.put(std::uint64_t(periods_.size()));
    for (const PeriodRecord &p : periods_)
      save_period(out, p);
  }

  std::unique_ptr<Simulation> Simulation::load(CheckpointReader &in, const Scene &scene)
  {
    const ModelSetting setting = load_setting(in);
    const std::string saved_scene = in.get_string();
    if (const auto lines = first_differing_lines(scene_file_text(scene), saved_scene))
      throw InputError("the checkpoint is of another scene: this scene has '" + lines->first +
                       "' where the checkpoint's has '" + lines->second + "'");
    auto simulation      = std::make_unique<Simulation>(scene, setting);
    simulation->stopped_ = in.get_bool();
    const std::uint64_t status = in.get_uint();
    if (status > std::uint64_t(RunStatus::interrupted))
      throw CheckpointError("the checkpoint's run status " + std::to_string(status) + " is not one this program knows");
    simulation->last_.status          = static_cast<RunStatus>(status);
    simulation->last_.message         = in.get_string();
    simulation->last_.t_end           = in.get_double();
    simulation->last_.slider_x_over_L = in.get_double();
    const RunStatus saved = simulation->last_.status;
    if (simulation->stopped_ != (saved != RunStatus::completed && saved != RunStatus::interrupted))
      throw CheckpointError("the checkpoint's run status (" + to_string(simulation->last_.status) +
                            ") does not agree with whether it stopped");
    simulation->run_->load(in);
    simulation->rows_.clear();
    const std::uint64_t n_rows = in.get_count(7 * sizeof(double));
    for (std::uint64_t i = 0; i < n_rows; ++i)
      simulation->rows_.push_back(load_trace_row(in));
    const std::uint64_t n_periods = in.get_count(17 * sizeof(std::uint64_t));
    for (std::uint64_t i = 0; i < n_periods; ++i)
      simulation->periods_.push_back(load_period(in));
    return simulation;
  }
} // namespace beamslider
