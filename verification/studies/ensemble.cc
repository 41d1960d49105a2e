// Ensembles of perturbed runs and two-sample comparisons, see ensemble.h.
#include "verification/studies/ensemble.h"

#include "contact/beam_system.h"
#include "verification/studies/parallel_for.h"
#include "verification/studies/simulation_cases.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>

namespace beamslider
{
  std::vector<EnsembleMember> run_ensemble(const Scene &scene, const EnsembleSettings &settings,
                                           const std::function<void(const EnsembleMember &)> &on_member)
  {
    using clock = std::chrono::steady_clock;
    const unsigned int K = settings.n_members;
    if (K == 0)
      throw InputError("--members 0: an ensemble needs at least one member");
    const TraceThresholds thresholds = trace_thresholds(scene);

    // The models are built here, one after another (the eigensolver behind
    // them is not thread-safe); only the time stepping runs in parallel.
    std::vector<EnsembleMember> members(K);
    std::vector<std::unique_ptr<BeamSystem>> models(K);
    std::vector<Scene> scenes(K, scene);
    for (unsigned int m = 0; m < K; ++m)
      {
        const auto start        = clock::now();
        members[m].index        = m;
        members[m].perturbation = m * settings.perturbation;
        scenes[m].initial.slider_position_over_L += members[m].perturbation;
        scenes[m].time_stepping.time_step = settings.model.time_step;
        validate_scene(scenes[m]);
        models[m]               = make_beam_model(scenes[m], settings.model);
        members[m].wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
      }

    std::mutex report;
    parallel_for(K, settings.n_threads, [&](const std::size_t m) {
      const auto start = clock::now();
      EnsembleMember &member = members[m];
      RunOptions options        = RunOptions::from_scene(scenes[m]);
      options.progress_interval = 1e300;
      AdaptationRun run(scenes[m], *models[m], options);
      run.on_period    = [&member](const PeriodRecord &p) { member.periods.push_back(p); };
      member.result    = run.run();
      member.analysis  = analyse_trace(member.periods, member.result.status, thresholds);
      member.wall_seconds += std::chrono::duration<double>(clock::now() - start).count();
      models[m].reset(); // its memory back as soon as it is done
      if (on_member)
        {
          const std::lock_guard<std::mutex> lock(report);
          on_member(member);
        }
    });
    return members;
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
        if (!a.valid)
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
