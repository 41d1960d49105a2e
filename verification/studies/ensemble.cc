// Ensembles of perturbed runs and two-sample comparisons, see ensemble.h.
#include "verification/studies/ensemble.h"
#include "numerics/elapsed.h"

#include "contact/beam_system.h"
#include "runtime/parallel_for.h"
#include "verification/studies/simulation_cases.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    using clock = std::chrono::steady_clock;

    // The model set-up (the FE modes behind every model and behind the
    // trace thresholds) one at a time: its eigensolver is not thread-safe.
    std::mutex &setup_mutex()
    {
      static std::mutex m;
      return m;
    }

    // Doubles in their shortest form that reads back to the same bits.
    std::string exact(const double x)
    {
      char buffer[32];
      const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, x);
      if (error != std::errc())
        throw std::logic_error("exact: to_chars failed");
      return std::string(buffer, end);
    }

    double read_double(const std::string &text, const char *what)
    {
      double x               = 0;
      const char *const last = text.data() + text.size();
      const auto [end, error] = std::from_chars(text.data(), last, x);
      if (error != std::errc() || end != last || text.empty())
        throw std::invalid_argument(std::string("member record: ") + what + " '" + text + "' is not a number");
      return x;
    }

    unsigned long read_unsigned(const std::string &text, const char *what)
    {
      unsigned long x        = 0;
      const char *const last = text.data() + text.size();
      const auto [end, error] = std::from_chars(text.data(), last, x);
      if (error != std::errc() || end != last || text.empty())
        throw std::invalid_argument(std::string("member record: ") + what + " '" + text + "' is not a count");
      return x;
    }

    RunStatus read_status(const std::string &text)
    {
      for (int k = 0; k <= static_cast<int>(RunStatus::interrupted); ++k)
        if (to_string(static_cast<RunStatus>(k)) == text)
          return static_cast<RunStatus>(k);
      throw std::invalid_argument("member record: unknown status '" + text + "'");
    }
  } // namespace

  EnsembleMember run_member(const Scene &scene, const ModelSetting &model, const unsigned int index,
                            const double perturbation)
  {
    const auto start = clock::now();
    EnsembleMember member;
    member.index        = index;
    member.perturbation = index * perturbation;
    Scene s             = scene;
    s.initial.slider_position_over_L += member.perturbation;
    validate_scene(s);
    std::unique_ptr<BeamSystem> beam;
    TraceThresholds thresholds;
    {
      const std::lock_guard<std::mutex> lock(setup_mutex());
      beam       = make_beam_model(s, model);
      thresholds = trace_thresholds(scene);
    }
    RunOptions options        = RunOptions::from_scene(s, model.time_step);
    options.progress_interval = 1e300;
    AdaptationRun run(s, *beam, options);
    run.on_period       = [&member](const PeriodRecord &p) { member.periods.push_back(p); };
    member.result       = run.run();
    member.analysis     = analyse_trace(member.periods, member.result.status, thresholds);
    member.wall_seconds = elapsed_seconds(start);
    return member;
  }

  EnsembleMember run_member(const MemberGroup &group, const unsigned int m)
  {
    return run_member(group.scene, group.model, group.first_member + m, group.perturbation);
  }

  std::size_t n_runs(const std::vector<MemberGroup> &groups)
  {
    std::size_t n = 0;
    for (const MemberGroup &g : groups)
      n += g.n_members;
    return n;
  }

  std::pair<std::size_t, unsigned int> group_and_member(const std::vector<MemberGroup> &groups, std::size_t run)
  {
    for (std::size_t g = 0; g < groups.size(); ++g)
      {
        if (run < groups[g].n_members)
          return {g, static_cast<unsigned int>(run)};
        run -= groups[g].n_members;
      }
    throw std::out_of_range("group_and_member: run " + std::to_string(run) + " beyond the list");
  }

  std::vector<std::size_t> longest_first(const std::vector<MemberGroup> &groups)
  {
    std::vector<std::size_t> order(n_runs(groups));
    std::iota(order.begin(), order.end(), 0);
    std::vector<double> cost(order.size());
    for (std::size_t r = 0; r < order.size(); ++r)
      {
        const MemberGroup &g = groups[group_and_member(groups, r).first];
        cost[r]              = cost_per_simulated_second(g.model, g.scene) * g.scene.time_stepping.end_time;
      }
    std::stable_sort(order.begin(), order.end(), [&cost](const std::size_t a, const std::size_t b) {
      return cost[a] > cost[b];
    });
    return order;
  }

  std::vector<std::string> member_record_columns()
  {
    return {"group",        "rung",         "member",          "perturbation",          "status",
            "message",      "t_end_s",      "slider_x_over_L", "n_steps",               "run_wall_s",
            "steps_per_s",  "max_solver_iterations", "n_contact_steps", "solver_iterations", "wall_s",
            "n_periods",    "periods"};
  }

  std::vector<std::string> member_record(const std::size_t group, const std::string &group_name,
                                         const EnsembleMember &m)
  {
    const RunResult &r = m.result;
    // Periods as "index t_start t_end x_C/L amplitude;", each ended by ';':
    // a line cut inside its last number (still a number) lacks the ';'.
    std::string periods;
    for (const PeriodRecord &p : m.periods)
      periods += std::to_string(p.index) + ' ' + exact(p.t_start) + ' ' + exact(p.t_end) + ' ' +
                 exact(p.slider_x_over_L) + ' ' + exact(p.amplitude_over_h) + ';';
    return {std::to_string(group),
            group_name,
            std::to_string(m.index),
            exact(m.perturbation),
            to_string(r.status),
            r.message,
            exact(r.t_end),
            exact(r.slider_x_over_L),
            std::to_string(r.n_steps),
            exact(r.wall_seconds),
            exact(r.steps_per_second),
            std::to_string(r.max_solver_iterations),
            std::to_string(r.n_contact_steps),
            std::to_string(r.solver_iterations),
            exact(m.wall_seconds),
            std::to_string(m.periods.size()),
            periods};
  }

  EnsembleMember member_from_record(const std::vector<std::string> &c, const TraceThresholds &thresholds,
                                    std::size_t &group, std::string &group_name)
  {
    if (c.size() != member_record_columns().size())
      throw std::invalid_argument("member record: " + std::to_string(c.size()) + " cells, not " +
                                  std::to_string(member_record_columns().size()));
    EnsembleMember m;
    group                          = read_unsigned(c[0], "group");
    group_name                     = c[1];
    m.index                        = read_unsigned(c[2], "member");
    m.perturbation                 = read_double(c[3], "perturbation");
    m.result.status                = read_status(c[4]);
    m.result.message               = c[5];
    m.result.t_end                 = read_double(c[6], "t_end_s");
    m.result.slider_x_over_L       = read_double(c[7], "slider_x_over_L");
    m.result.n_steps               = read_unsigned(c[8], "n_steps");
    m.result.wall_seconds          = read_double(c[9], "run_wall_s");
    m.result.steps_per_second      = read_double(c[10], "steps_per_s");
    m.result.max_solver_iterations = read_unsigned(c[11], "max_solver_iterations");
    m.result.n_contact_steps       = read_unsigned(c[12], "n_contact_steps");
    m.result.solver_iterations     = read_unsigned(c[13], "solver_iterations");
    m.wall_seconds                 = read_double(c[14], "wall_s");
    const std::size_t n_periods    = read_unsigned(c[15], "n_periods");
    if (!c[16].empty() && c[16].back() != ';')
      throw std::invalid_argument("member record: the periods end without ';' (a line cut short)");
    std::istringstream periods(c[16]);
    std::string period;
    while (std::getline(periods, period, ';'))
      {
        std::istringstream fields(period);
        std::string index, t_start, t_end, x, a, extra;
        if (!(fields >> index >> t_start >> t_end >> x >> a) || (fields >> extra))
          throw std::invalid_argument("member record: period '" + period + "' is not 5 numbers");
        PeriodRecord p;
        p.index            = read_unsigned(index, "period index");
        p.t_start          = read_double(t_start, "period start");
        p.t_end            = read_double(t_end, "period end");
        p.slider_x_over_L  = read_double(x, "period x_C/L");
        p.amplitude_over_h = read_double(a, "period amplitude");
        m.periods.push_back(p);
      }
    if (m.periods.size() != n_periods) // a line cut short
      throw std::invalid_argument("member record: " + std::to_string(m.periods.size()) + " periods of " +
                                  std::to_string(n_periods));
    m.analysis = analyse_trace(m.periods, m.result.status, thresholds);
    return m;
  }

  std::vector<std::vector<EnsembleMember>>
  run_groups_in_threads(const std::vector<MemberGroup> &groups, const unsigned int n_threads,
                        const std::function<void(std::size_t, const EnsembleMember &)> &on_member)
  {
    std::vector<std::vector<EnsembleMember>> members(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g)
      members[g].resize(groups[g].n_members);
    const std::vector<std::size_t> order = longest_first(groups);
    std::mutex report;
    parallel_for(order.size(), n_threads, [&](const std::size_t i) {
      const auto [g, m]     = group_and_member(groups, order[i]);
      EnsembleMember member = run_member(groups[g], m);
      const std::lock_guard<std::mutex> lock(report);
      members[g][m] = std::move(member);
      if (on_member)
        on_member(g, members[g][m]);
    });
    return members;
  }

  std::vector<EnsembleMember> run_ensemble(const Scene &scene, const EnsembleSettings &settings,
                                           const std::function<void(const EnsembleMember &)> &on_member,
                                           const MemberGroupRunner &runner)
  {
    if (settings.n_members == 0)
      throw InputError("--members 0: an ensemble needs at least one member");
    const std::vector<MemberGroup> groups = {
      {"", scene, settings.model, settings.n_members, settings.perturbation}};
    if (runner)
      return runner(groups).front();
    return run_groups_in_threads(groups, settings.n_threads,
                                 [&on_member](std::size_t, const EnsembleMember &m) {
                                   if (on_member)
                                     on_member(m);
                                 })
      .front();
  }

  double quantile(std::vector<double> sample, const double q)
  {
    if (sample.empty())
      return std::nan("");
    std::sort(sample.begin(), sample.end());
    const double h       = q * (sample.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(h));
    const std::size_t hi = std::min(lo + 1, sample.size() - 1);
    return sample[lo] + (h - lo) * (sample[hi] - sample[lo]);
  }

  OutcomeStatistics statistics(const std::string &name, const std::vector<double> &sample)
  {
    OutcomeStatistics s;
    s.name = name;
    s.n    = sample.size();
    if (sample.empty())
      {
        s.median = s.q1 = s.q3 = s.min = s.max = std::nan("");
        return s;
      }
    s.median = quantile(sample, 0.5);
    s.q1     = quantile(sample, 0.25);
    s.q3     = quantile(sample, 0.75);
    s.min    = *std::min_element(sample.begin(), sample.end());
    s.max    = *std::max_element(sample.begin(), sample.end());
    return s;
  }

  OutcomeSamples outcome_samples(const std::vector<EnsembleMember> &members)
  {
    OutcomeSamples s;
    for (const auto &m : members)
      {
        const TraceAnalysis &a = m.analysis;
        if (!a.valid || a.outcome == AdaptationClass::failed)
          continue;
        if (a.jumped)
          s.jump_time.push_back(a.jump_time);
        if (a.turned)
          s.turn_position.push_back(a.turn_position);
        s.final_position.push_back(a.final_position);
        s.final_amplitude.push_back(a.final_amplitude);
      }
    return s;
  }

  // Both empirical distribution functions are steps at the pooled sample
  // points; between neighbouring points they are constant, so both integrals
  // and the supremum are exact sums over the pooled, sorted points.
  namespace
  {
    template <typename Accumulate>
    void walk_distributions(std::vector<double> a, std::vector<double> b, Accumulate &&accumulate)
    {
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      std::vector<double> pooled(a);
      pooled.insert(pooled.end(), b.begin(), b.end());
      std::sort(pooled.begin(), pooled.end());
      for (std::size_t i = 0; i + 1 <= pooled.size(); ++i)
        {
          const double x  = pooled[i];
          const double Fa = double(std::upper_bound(a.begin(), a.end(), x) - a.begin()) / a.size();
          const double Fb = double(std::upper_bound(b.begin(), b.end(), x) - b.begin()) / b.size();
          const double width = i + 1 < pooled.size() ? pooled[i + 1] - x : 0.;
          accumulate(std::abs(Fa - Fb), width);
        }
    }
  } // namespace

  double wasserstein_1(std::vector<double> a, std::vector<double> b)
  {
    if (a.empty() || b.empty())
      return std::nan("");
    double w = 0;
    walk_distributions(std::move(a), std::move(b), [&w](const double d, const double width) { w += d * width; });
    return w;
  }

  double kolmogorov_smirnov(std::vector<double> a, std::vector<double> b)
  {
    if (a.empty() || b.empty())
      return std::nan("");
    double d_max = 0;
    walk_distributions(std::move(a), std::move(b), [&d_max](const double d, double) { d_max = std::max(d_max, d); });
    return d_max;
  }

  SampleComparison compare_samples(const std::vector<double> &a, const std::vector<double> &b,
                                   const unsigned int n_bootstrap, const unsigned int seed)
  {
    SampleComparison c;
    c.n_a = a.size();
    c.n_b = b.size();
    if (a.empty() || b.empty())
      {
        c.shift = c.wasserstein = c.ks = c.interval_low = c.interval_high = c.spread = std::nan("");
        return c;
      }
    c.shift       = quantile(b, 0.5) - quantile(a, 0.5);
    c.wasserstein = wasserstein_1(a, b);
    c.ks          = kolmogorov_smirnov(a, b);

    std::mt19937 random(seed);
    auto resample = [&random](const std::vector<double> &x) {
      std::uniform_int_distribution<std::size_t> pick(0, x.size() - 1);
      std::vector<double> r(x.size());
      for (auto &v : r)
        v = x[pick(random)];
      return r;
    };
    std::vector<double> boot(n_bootstrap);
    for (auto &w : boot)
      w = wasserstein_1(resample(a), resample(b));
    c.interval_low  = quantile(boot, 0.05);
    c.interval_high = quantile(boot, 0.95);

    // The ensembles' own scatter: W₁ between the halves of each.
    auto halves = [](const std::vector<double> &x) {
      if (x.size() < 2)
        return 0.;
      const std::vector<double> first(x.begin(), x.begin() + x.size() / 2), second(x.begin() + x.size() / 2, x.end());
      return wasserstein_1(first, second);
    };
    c.spread          = std::max(halves(a), halves(b));
    c.distinguishable = c.interval_low > c.spread;
    return c;
  }
} // namespace beamslider
