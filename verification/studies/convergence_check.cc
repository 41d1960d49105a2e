// The reference's convergence check, see convergence_check.h.
#include "verification/studies/convergence_check.h"

#include "contact/beam_system.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    std::string fixed(const double x, const int digits)
    {
      std::ostringstream s;
      s << std::fixed << std::setprecision(digits) << x;
      return s.str();
    }

    std::string w1(const SampleComparison &c)
    {
      return fixed(c.wasserstein, 4) + " [" + fixed(c.interval_low, 4) + ", " + fixed(c.interval_high, 4) + "]";
    }

    // What the parameter of a trial is, in words: "Δt = 1e-05 s", "N = 30".
    std::string setting_text(const std::string &parameter, const ModelSetting &m)
    {
      std::ostringstream s;
      if (parameter == "N")
        s << "N = " << m.n_modes << " (Δt = " << m.time_step << " s)";
      else
        s << "Δt = " << m.time_step << " s";
      return s.str();
    }

    // The trials each undecided check runs next: up to trial 1 at once (the
    // pair is the least that decides anything; judged by order, the witness
    // with it), then one at a time.
    std::pair<std::size_t, std::size_t> next_trials(const RefinementPlan &plan, const std::size_t n_done)
    {
      const std::size_t last = n_done == 0 ? first_round_size(plan) - 1 : std::min(n_done, plan.models.size() - 1);
      return {n_done, last};
    }

    // A trial decides nothing on too few end states: at least two, and at
    // least half its members (the others failed: outcome_samples).
    bool enough_end_states(const ConvergenceTrial &t)
    {
      return t.final_position.n >= std::max<std::size_t>(2, (t.members.size() + 1) / 2);
    }

    // Judged by order: trial k (sorted coarsest first, with both neighbours)
    // gets its observed order, remaining error and tolerance; returns
    // whether its drift is within the tolerance.
    bool drift_within_tolerance(std::vector<ConvergenceTrial> &trials, const std::size_t k)
    {
      ConvergenceTrial &t = trials[k];
      const OutcomeStatistics &coarse = trials[k - 1].final_position, &fine = trials[k + 1].final_position;
      if (!enough_end_states(trials[k - 1]) || !enough_end_states(t) || !enough_end_states(trials[k + 1]))
        return false; // a step without end states shows no order
      const double d1 = std::abs(coarse.median - t.final_position.median);
      const double d2 = std::abs(t.final_position.median - fine.median);
      t.tolerance     = std::max(convergence_resolution, t.position_to_next.spread);
      if (d1 <= convergence_resolution && d2 <= convergence_resolution)
        return true; // no difference above the resolution: no drift to extrapolate
      if (d2 == 0)
        {
          t.observed_order  = INFINITY;
          t.remaining_error = 0;
          return true;
        }
      t.observed_order = std::log2(d1 / d2);
      if (t.observed_order < minimum_extrapolation_order)
        return false; // too slow (or growing) to extrapolate
      const double r    = std::exp2(t.observed_order);
      t.remaining_error = d2 * r / (r - 1);
      return t.remaining_error <= t.tolerance;
    }

    std::string order_text(const ConvergenceTrial &t)
    {
      if (std::isnan(t.tolerance))
        return "";
      if (std::isnan(t.observed_order))
        return "; every difference below the resolution " + fixed(convergence_resolution, 3) + " L";
      std::string s = "; observed order " + (std::isinf(t.observed_order) ? std::string("∞") : fixed(t.observed_order, 2));
      if (std::isnan(t.remaining_error))
        return s + ", below " + fixed(minimum_extrapolation_order, 1) + ": too slow to extrapolate";
      return s + ", extrapolated remaining error " + fixed(t.remaining_error, 4) + " against the tolerance " +
             fixed(t.tolerance, 4);
    }
  } // namespace

  RefinementPlan step_refinements(const std::string &name, const ModelSetting &model, const unsigned int max_halvings)
  {
    RefinementPlan plan{name, "Δt", {model}};
    for (unsigned int k = 0; k < max_halvings; ++k)
      {
        ModelSetting finer = plan.models.back();
        finer.time_step /= 2;
        plan.models.push_back(finer);
      }
    return plan;
  }

  RefinementPlan step_sequence(const std::string &name, const ModelSetting &model, const unsigned int max_halvings)
  {
    if (max_halvings < 1)
      throw std::invalid_argument("step_sequence: a sequence needs at least one halving");
    RefinementPlan plan = step_refinements(name, model, max_halvings);
    ModelSetting witness = model;
    witness.time_step *= 2;
    plan.models.insert(plan.models.begin() + 2, witness);
    plan.judged_by_order = true;
    return plan;
  }

  ModelSetting more_modes(const Scene &scene, const ModelSetting &rom)
  {
    if (rom.family != "rom")
      throw std::invalid_argument("more_modes: '" + rom.label() + "' is not a reduced model");
    ModelSetting finer = rom;
    finer.n_modes      = static_cast<unsigned int>(std::ceil(1.5 * rom.n_modes));
    return at_stable_step(scene, finer);
  }

  ModelSetting at_stable_step(const Scene &scene, ModelSetting model)
  {
    if (model.family != "rom" || model.integrator != "explicit")
      return model;
    // The explicit scheme's limit 2/ω_max of the basis, read off the model
    // itself (built at a step it surely takes).
    ModelSetting probe = model;
    probe.time_step    = 1e-12;
    const double limit = make_beam_model(scene, probe)->max_stable_time_step();
    while (model.time_step > limit)
      model.time_step /= 2;
    return model;
  }

  RefinementPlan mode_refinements(const std::string &name, const Scene &scene, const ModelSetting &rom)
  {
    return {name, "N", {rom, more_modes(scene, rom)}};
  }

  bool ends_alike(const SampleComparison &c)
  {
    return c.n_a > 0 && c.n_b > 0 && (!c.distinguishable || c.interval_high <= convergence_resolution);
  }

  const ConvergenceTrial &ConvergenceCheck::reference() const
  {
    if (trials.empty())
      throw std::logic_error("ConvergenceCheck::reference: no trial has run");
    return converged ? trials[accepted] : trials.back();
  }

  std::string ConvergenceCheck::verdict() const
  {
    std::ostringstream s;
    if (trials.size() < 2)
      {
        s << name << ": not checked (no refinement ran)";
        return s.str();
      }
    if (converged)
      {
        const ConvergenceTrial &a = trials[accepted], &b = trials[accepted + 1];
        s << name << ": converged at " << setting_text(parameter, a.model) << ": it ends at x_C/L = "
          << fixed(a.final_position.median, 4) << ", " << setting_text(parameter, b.model) << " at "
          << fixed(b.final_position.median, 4) << "; W₁ " << w1(a.position_to_next) << " against the spread "
          << fixed(a.position_to_next.spread, 4)
          << (a.position_to_next.distinguishable ? ", within the resolution " + fixed(convergence_resolution, 3) + " L"
                                                  : ", indistinguishable at this ensemble size")
          << order_text(a);
        const std::size_t own = trials.front().witness ? 1 : 0; // the model under test
        if (accepted > own)
          s << " (the coarser " << setting_text(parameter, trials[own].model) << " was not: W₁ "
            << w1(trials[own].position_to_next) << ", spread " << fixed(trials[own].position_to_next.spread, 4)
            << order_text(trials[own]) << ")";
        return s.str();
      }
    s << name << ": NOT CONVERGED in " << parameter << " down to " << setting_text(parameter, trials.back().model)
      << ": the end states";
    for (std::size_t k = 0; k < trials.size(); ++k)
      {
        const ConvergenceTrial &t = trials[k];
        s << (k ? ", " : " ") << (t.final_position.n > 0 ? fixed(t.final_position.median, 4) : std::string("none"));
        if (t.final_position.n < t.members.size())
          s << " (" << t.members.size() - t.final_position.n << " of " << t.members.size()
            << " members without an end state: failed or too short)";
      }
    s << "; W₁ between neighbours";
    for (std::size_t k = 0; k + 1 < trials.size(); ++k)
      {
        const SampleComparison &c = trials[k].position_to_next;
        s << (k ? ", " : " ")
          << (c.n_a == 0 ? std::string("none (too few end states)")
                         : w1(c) + " (spread " + fixed(c.spread, 4) + ")");
      }
    for (const ConvergenceTrial &t : trials)
      if (!std::isnan(t.tolerance))
        s << "; at " << setting_text(parameter, t.model) << order_text(t);
    s << ". The finest is used, unproven";
    return s.str();
  }

  ConvergenceCheck judge_convergence(const RefinementPlan &plan, std::vector<std::vector<EnsembleMember>> trial_members)
  {
    if (trial_members.size() > plan.models.size())
      throw std::invalid_argument("judge_convergence: more trials than the plan has models");
    ConvergenceCheck check;
    check.name      = plan.name;
    check.parameter = plan.parameter;
    for (std::size_t k = 0; k < trial_members.size(); ++k)
      {
        ConvergenceTrial t;
        t.model   = plan.models[k];
        t.witness = plan.judged_by_order && k == 2;
        t.members = std::move(trial_members[k]);
        for (const EnsembleMember &m : t.members)
          t.wall_seconds_per_member += m.wall_seconds / t.members.size();
        check.trials.push_back(std::move(t));
      }
    // Coarsest first: the witness 2Δt runs after the pair but leads the sequence.
    if (plan.judged_by_order)
      std::stable_sort(check.trials.begin(), check.trials.end(), [](const ConvergenceTrial &a, const ConvergenceTrial &b) {
        return a.model.time_step > b.model.time_step;
      });
    // Each trial's end states once, in the sorted order.
    std::vector<OutcomeSamples> samples;
    for (ConvergenceTrial &t : check.trials)
      {
        samples.push_back(outcome_samples(t.members));
        t.final_position  = statistics("final x_C/L", samples.back().final_position);
        t.final_amplitude = statistics("final amplitude [h]", samples.back().final_amplitude);
      }
    for (std::size_t k = 0; k + 1 < check.trials.size(); ++k)
      {
        ConvergenceTrial &t = check.trials[k];
        if (!enough_end_states(t) || !enough_end_states(check.trials[k + 1]))
          continue; // too few end states to compare (members failed): not accepted
        t.position_to_next  = compare_samples(samples[k].final_position, samples[k + 1].final_position);
        t.amplitude_to_next = compare_samples(samples[k].final_amplitude, samples[k + 1].final_amplitude);
      }
    // Judged by order, every step with both neighbours gets its estimates
    // (the evidence, whether or not its pair ends alike).
    std::vector<bool> drift_ok(check.trials.size(), !plan.judged_by_order);
    if (plan.judged_by_order)
      for (std::size_t k = 1; k + 1 < check.trials.size(); ++k)
        drift_ok[k] = !check.trials[k].witness && drift_within_tolerance(check.trials, k);
    for (std::size_t k = 0; k + 1 < check.trials.size() && !check.converged; ++k)
      if (!check.trials[k].witness && drift_ok[k] && ends_alike(check.trials[k].position_to_next))
        {
          check.converged = true;
          check.accepted  = k;
        }
    check.decided = check.converged || (!check.trials.empty() && check.trials.size() == plan.models.size());
    return check;
  }

  std::size_t first_round_size(const RefinementPlan &plan)
  {
    return std::min<std::size_t>(plan.judged_by_order ? 3 : 2, plan.models.size());
  }

  std::vector<MemberGroup> trial_groups(const Scene &scene, const RefinementPlan &plan, const std::size_t first,
                                        const std::size_t last, const unsigned int n_members, const double perturbation)
  {
    std::vector<MemberGroup> groups;
    for (std::size_t k = first; k <= last && k < plan.models.size(); ++k)
      groups.push_back({plan.name + ": " + plan.models[k].label(), scene, plan.models[k], n_members, perturbation});
    return groups;
  }

  std::vector<ConvergenceCheck>
  run_convergence_checks(const Scene &scene, const std::vector<RefinementPlan> &plans,
                         std::vector<std::vector<std::vector<EnsembleMember>>> done, const unsigned int n_members,
                         const double perturbation, const MemberGroupRunner &runner,
                         const std::function<unsigned long(unsigned long)> &share)
  {
    return run_convergence_checks(std::vector<Scene>(plans.size(), scene), plans, std::move(done), n_members,
                                  perturbation, runner, share);
  }

  std::vector<ConvergenceCheck>
  run_convergence_checks(const std::vector<Scene> &scenes, const std::vector<RefinementPlan> &plans,
                         std::vector<std::vector<std::vector<EnsembleMember>>> done, const unsigned int n_members,
                         const double perturbation, const MemberGroupRunner &runner,
                         const std::function<unsigned long(unsigned long)> &share)
  {
    if (scenes.size() != plans.size())
      throw std::invalid_argument("run_convergence_checks: a scene per plan");
    if (plans.size() > 8 * sizeof(unsigned long))
      throw std::invalid_argument("run_convergence_checks: too many checks for one mask");
    done.resize(plans.size());
    std::vector<ConvergenceCheck> checks(plans.size());
    while (true)
      {
        unsigned long mask = 0;
        for (std::size_t i = 0; i < plans.size(); ++i)
          {
            checks[i] = judge_convergence(plans[i], done[i]);
            if (!checks[i].decided)
              mask |= 1ul << i;
          }
        if (share)
          share(mask);
        if (mask == 0)
          return checks;
        // One round: the next trials of every undecided check, as one list.
        std::vector<MemberGroup> groups;
        std::vector<std::size_t> owner; // the check of each group; its trials come in order
        for (std::size_t i = 0; i < plans.size(); ++i)
          if (mask & (1ul << i))
            {
              const auto [first, last] = next_trials(plans[i], done[i].size());
              for (const MemberGroup &g : trial_groups(scenes[i], plans[i], first, last, n_members, perturbation))
                {
                  owner.push_back(i);
                  groups.push_back(g);
                }
            }
        std::vector<std::vector<EnsembleMember>> results = runner ? runner(groups) : run_groups_in_threads(groups);
        for (std::size_t g = 0; g < groups.size(); ++g)
          done[owner[g]].push_back(std::move(results[g]));
      }
  }

  void work_on_convergence_checks(const Scene &scene, const std::vector<RefinementPlan> &plans,
                                  std::vector<std::size_t> n_done, const unsigned int n_members,
                                  const double perturbation,
                                  const std::function<void(const std::vector<MemberGroup> &)> &work,
                                  const std::function<unsigned long(unsigned long)> &share)
  {
    work_on_convergence_checks(std::vector<Scene>(plans.size(), scene), plans, std::move(n_done), n_members,
                               perturbation, work, share);
  }

  void work_on_convergence_checks(const std::vector<Scene> &scenes, const std::vector<RefinementPlan> &plans,
                                  std::vector<std::size_t> n_done, const unsigned int n_members,
                                  const double perturbation,
                                  const std::function<void(const std::vector<MemberGroup> &)> &work,
                                  const std::function<unsigned long(unsigned long)> &share)
  {
    n_done.resize(plans.size());
    while (true)
      {
        const unsigned long mask = share(0);
        if (mask == 0)
          return;
        std::vector<MemberGroup> groups;
        for (std::size_t i = 0; i < plans.size(); ++i)
          if (mask & (1ul << i))
            {
              const auto [first, last] = next_trials(plans[i], n_done[i]);
              for (const MemberGroup &g : trial_groups(scenes[i], plans[i], first, last, n_members, perturbation))
                groups.push_back(g);
              n_done[i] = last + 1;
            }
        work(groups);
      }
  }
} // namespace beamslider
