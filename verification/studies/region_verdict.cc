// The verdict across the signature-move region, see region_verdict.h.
#include "verification/studies/region_verdict.h"

#include "verification/studies/simulation_cases.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    // Every site's scene, rungs, checks and member groups, in the order
    // rank 0 and the other ranks both build them.
    struct SitePlan
    {
      std::vector<std::string> labels; // per site
      std::vector<Scene> scenes;       // per site, its end time set
      std::vector<std::vector<LadderRung>> rungs;
      std::vector<std::size_t> references;      // per site: its reference rung
      std::vector<LadderChecks> checks;         // per site
      std::vector<std::size_t> first_group;     // per site: its first group in `groups`
      std::vector<MemberGroup> groups;          // every site's rungs and first refinements
      std::vector<RefinementPlan> check_plans;  // every site's checks, in site order
      std::vector<Scene> check_scenes;          // the scene of each
    };

    SitePlan site_plan(const std::vector<StudySite> &sites, const SiteRungs &rungs_of, const unsigned int members)
    {
      SitePlan plan;
      for (const StudySite &site : sites)
        {
          const Scene &s                = site.scene;
          const double end_time         = s.time_stepping.end_time;
          std::size_t reference         = 0;
          std::vector<LadderRung> rungs = rungs_of(s, reference);
          LadderChecks checks           = ladder_checks(s, rungs, reference);
          for (RefinementPlan &c : checks.plans)
            c.name = site.label + ": " + c.name;
          plan.first_group.push_back(plan.groups.size());
          for (MemberGroup g : ladder_groups_with_checks(s, rungs, checks, end_time, members))
            {
              if (g.name.rfind(site.label, 0) != 0) // the checks' groups carry the site already
                g.name = site.label + ": " + g.name;
              plan.groups.push_back(g);
            }
          for (const RefinementPlan &c : checks.plans)
            {
              plan.check_plans.push_back(c);
              plan.check_scenes.push_back(s);
            }
          plan.labels.push_back(site.label);
          plan.scenes.push_back(s);
          plan.rungs.push_back(rungs);
          plan.references.push_back(reference);
          plan.checks.push_back(checks);
        }
      return plan;
    }

    std::vector<StudySite> region_sites(const Scene &scene, const std::vector<OperatingPoint> &points,
                                        const double end_time)
    {
      std::vector<StudySite> sites;
      for (const OperatingPoint &p : points)
        {
          Scene s                  = at_point(scene, p);
          s.time_stepping.end_time = end_time;
          sites.push_back({p.label(), s});
        }
      return sites;
    }

    using Share = std::function<unsigned long(unsigned long)>;
    unsigned long shared(const Share &share, const unsigned long x) { return share ? share(x) : x; }

    // Where a site's reference check took its reference: the index of the
    // accepted trial's model among the check's models, so that the other
    // ranks, which never see the trials, grow the same model (the models'
    // count when the reference is the rung's own model).
    unsigned long accepted_trial(const SitePlan &plan, const std::size_t p, const LadderStudy &ladder)
    {
      const ModelSetting &taken = ladder.rungs[ladder.reference].rung.model;
      for (std::size_t c = 0; c < plan.checks[p].plans.size(); ++c)
        if (plan.checks[p].rung[c] == plan.references[p])
          {
            const std::vector<ModelSetting> &models = plan.checks[p].plans[c].models;
            for (std::size_t k = 0; k < models.size(); ++k)
              if (models[k].time_step == taken.time_step && models[k].label() == taken.label())
                return k;
          }
      return ~0ul;
    }

    // Site p's reference model: its check's model `accepted` (accepted_trial),
    // or the rung's own.
    ModelSetting reference_model(const SitePlan &plan, const std::size_t p, const unsigned long accepted)
    {
      const std::size_t r = plan.references[p];
      for (std::size_t c = 0; c < plan.checks[p].plans.size(); ++c)
        if (plan.checks[p].rung[c] == r && accepted < plan.checks[p].plans[c].models.size())
          return plan.checks[p].plans[c].models[accepted];
      return plan.rungs[p][r].model;
    }

    // The class rounds as every rank sees them: each site's rung models
    // (the reference at the step its check took) and how many members each
    // has run.
    struct ClassRounds
    {
      std::vector<std::vector<ModelSetting>> models;
      std::vector<std::vector<unsigned int>> counts;
      std::vector<std::pair<std::size_t, std::size_t>> grown; // the (site, rung) of each group of the last round

      ClassRounds(const SitePlan &plan, const unsigned int members, const std::vector<unsigned long> &accepted)
      {
        for (std::size_t p = 0; p < plan.rungs.size(); ++p)
          {
            // A round's mask holds one bit a rung.
            if (plan.rungs[p].size() > std::numeric_limits<unsigned long>::digits)
              throw std::logic_error("class rounds: site " + plan.labels[p] + " has " +
                                     std::to_string(plan.rungs[p].size()) + " rungs, more than a mask's " +
                                     std::to_string(std::numeric_limits<unsigned long>::digits) + " bits");
            models.emplace_back();
            counts.emplace_back();
            for (const LadderRung &rung : plan.rungs[p])
              {
                models.back().push_back(rung.model);
                counts.back().push_back(rung_members(rung, members));
              }
            models.back()[plan.references[p]] = reference_model(plan, p, accepted[p]);
          }
      }

      // More members of every (site, rung) whose bit is set in masks[site].
      std::vector<MemberGroup> groups(const SitePlan &plan, const std::vector<unsigned long> &masks)
      {
        std::vector<MemberGroup> out;
        grown.clear();
        for (std::size_t p = 0; p < masks.size(); ++p)
          for (std::size_t i = 0; i < models[p].size(); ++i)
            if (masks[p] >> i & 1)
              {
                MemberGroup g;
                g.first_member = counts[p][i];
                g.n_members    = class_members_step;
                g.model        = models[p][i];
                g.name         = plan.labels[p] + ": " + g.model.label() + " (members " +
                         std::to_string(g.first_member) + "–" + std::to_string(g.first_member + g.n_members - 1) + ")";
                g.scene        = plan.scenes[p];
                g.perturbation = EnsembleSettings().perturbation;
                counts[p][i] += g.n_members;
                out.push_back(std::move(g));
                grown.emplace_back(p, i);
              }
        return out;
      }
    };

    // Which rungs of each site need more members: those whose classified
    // members do not decide their majority class, while the ceiling allows.
    std::vector<unsigned long> undecided(const std::vector<LadderStudy> &ladders, const ClassRounds &rounds)
    {
      std::vector<unsigned long> masks(ladders.size(), 0);
      for (std::size_t p = 0; p < ladders.size(); ++p)
        for (std::size_t i = 0; i < ladders[p].rungs.size(); ++i)
          {
            const ClassCounts counts = class_counts(ladders[p].rungs[i].members);
            if (!counts.empty() && !majority_decided(counts) &&
                rounds.counts[p][i] + class_members_step <= class_members_ceiling)
              masks[p] |= 1ul << i;
          }
      return masks;
    }

    // Rank 0's class rounds (see region_verdict.h, majority_decided): more
    // members where a rung's class is undecided, each site's ladder
    // assembled again with them; its checks stay as judged.
    void decide_classes(const SitePlan &plan, const unsigned int members, std::vector<LadderStudy> &ladders,
                        const MemberGroupRunner &runner, const Share &share)
    {
      std::vector<unsigned long> accepted;
      for (std::size_t p = 0; p < ladders.size(); ++p)
        accepted.push_back(shared(share, accepted_trial(plan, p, ladders[p])));
      ClassRounds rounds(plan, members, accepted);
      for (;;)
        {
          std::vector<unsigned long> masks = undecided(ladders, rounds);
          const bool any = std::any_of(masks.begin(), masks.end(), [](const unsigned long m) { return m != 0; });
          if (!shared(share, any))
            return;
          for (unsigned long &m : masks)
            m = shared(share, m);
          const std::vector<MemberGroup> groups = rounds.groups(plan, masks);
          std::vector<std::vector<EnsembleMember>> more = runner ? runner(groups) : run_groups_in_threads(groups);
          std::vector<bool> changed(ladders.size(), false);
          for (std::size_t j = 0; j < groups.size(); ++j)
            {
              const auto [p, i]                   = rounds.grown[j];
              std::vector<EnsembleMember> &grown = ladders[p].rungs[i].members;
              grown.insert(grown.end(), std::make_move_iterator(more[j].begin()), std::make_move_iterator(more[j].end()));
              changed[p] = true;
            }
          for (std::size_t p = 0; p < ladders.size(); ++p)
            if (changed[p])
              {
                LadderStudy &l = ladders[p];
                std::vector<LadderRung> rungs;
                std::vector<std::vector<EnsembleMember>> member_sets;
                for (LadderRungResult &r : l.rungs)
                  {
                    rungs.push_back(r.rung);
                    member_sets.push_back(std::move(r.members));
                  }
                LadderStudy again = assemble_ladder(plan.scenes[p], rungs, l.reference, l.end_time, std::move(member_sets));
                again.members     = l.members;
                again.checks      = std::move(l.checks);
                again.check_rungs = std::move(l.check_rungs);
                l                 = std::move(again);
              }
        }
    }

    // The other ranks' part of decide_classes: the same rounds, told by
    // rank 0's masks, each computing what rank 0 hands out by `work`.
    void work_on_classes(const SitePlan &plan, const unsigned int members,
                         const std::function<void(const std::vector<MemberGroup> &)> &work, const Share &share)
    {
      std::vector<unsigned long> accepted;
      for (std::size_t p = 0; p < plan.scenes.size(); ++p)
        accepted.push_back(share(0));
      ClassRounds rounds(plan, members, accepted);
      while (share(0))
        {
          std::vector<unsigned long> masks(plan.scenes.size());
          for (unsigned long &m : masks)
            m = share(0);
          work(rounds.groups(plan, masks));
        }
    }

    // The larger basis of site p's check in N (⌈1.5 N⌉ modes at its step).
    ModelSetting larger_basis(const SitePlan &plan, const std::size_t p)
    {
      for (const RefinementPlan &c : plan.checks[p].plans)
        if (c.parameter == "N" && c.models.size() > 1)
          return c.models[1];
      throw std::logic_error("larger_basis: site " + plan.labels[p] + " has no check in N");
    }

    // The model-form probes of the sites rank 0 flags (basis_gap), as every
    // rank builds them: rank 0 shares per site the flag and, if set, where
    // its reference check took its reference (accepted_trial).
    struct ProbeRound
    {
      std::vector<std::size_t> sites;
      std::vector<std::vector<LadderRung>> probes; // per flagged site
      std::vector<MemberGroup> groups;             // every probe's members, in order

      ProbeRound(const SitePlan &plan, const unsigned int members, const std::function<unsigned long(std::size_t)> &flag,
                 const std::function<unsigned long(std::size_t)> &accepted)
      {
        for (std::size_t p = 0; p < plan.scenes.size(); ++p)
          {
            if (!flag(p))
              continue;
            const ModelSetting reference = reference_model(plan, p, accepted(p));
            sites.push_back(p);
            probes.push_back(model_form_probes(plan.scenes[p], reference, larger_basis(plan, p)));
            for (const LadderRung &r : probes.back())
              groups.push_back({plan.labels[p] + ": " + r.name, plan.scenes[p], r.model, members,
                                EnsembleSettings().perturbation});
          }
      }
    };

    // Rank 0's probes: run where basis_gap holds, each with the site's
    // reference as its last rung.
    std::vector<std::pair<std::size_t, LadderStudy>> probe_model_form(const SitePlan &plan, const unsigned int members,
                                                                      const std::vector<LadderStudy> &ladders,
                                                                      const MemberGroupRunner &runner, const Share &share)
    {
      const ProbeRound round(
        plan, members, [&](const std::size_t p) { return shared(share, basis_gap(ladders[p]) ? 1 : 0); },
        [&](const std::size_t p) { return shared(share, accepted_trial(plan, p, ladders[p])); });
      if (round.groups.empty())
        return {};
      std::vector<std::vector<EnsembleMember>> results = runner ? runner(round.groups) : run_groups_in_threads(round.groups);
      std::vector<std::pair<std::size_t, LadderStudy>> out;
      std::size_t next = 0;
      for (std::size_t j = 0; j < round.sites.size(); ++j)
        {
          const std::size_t p            = round.sites[j];
          const LadderRungResult &ref    = ladders[p].rungs[ladders[p].reference];
          std::vector<LadderRung> rungs = round.probes[j];
          std::vector<std::vector<EnsembleMember>> member_sets;
          for (std::size_t k = 0; k < rungs.size(); ++k)
            member_sets.push_back(std::move(results[next++]));
          rungs.push_back(ref.rung);
          member_sets.push_back(ref.members);
          out.emplace_back(p, assemble_ladder(plan.scenes[p], rungs, rungs.size() - 1, ladders[p].end_time,
                                              std::move(member_sets)));
        }
      return out;
    }

    // The other ranks' part of probe_model_form.
    void work_on_probes(const SitePlan &plan, const unsigned int members,
                        const std::function<void(const std::vector<MemberGroup> &)> &work, const Share &share)
    {
      const ProbeRound round(
        plan, members, [&](std::size_t) { return share(0); }, [&](std::size_t) { return share(0); });
      if (!round.groups.empty())
        work(round.groups);
    }

    // run_sites on a plan made already (run_region needs it after).
    std::vector<LadderStudy> run_planned_sites(const SitePlan &plan, const unsigned int members,
                                               const MemberGroupRunner &runner, const MemberGroupRunner &rounds,
                                               const Share &share);
    void work_on_planned_sites(const SitePlan &plan, const unsigned int members,
                               const std::function<void(const std::vector<MemberGroup> &)> &work, const Share &share);
  } // namespace

  std::string OperatingPoint::label() const
  {
    std::ostringstream s;
    s << frequency_hz << " Hz / " << acceleration_m_s2 << " m/s²";
    return s.str();
  }

  std::vector<OperatingPoint> signature_move_region(const Scene &scene)
  {
    // On mueller2023 (124 Hz, 14 m/s²): 116/12, 120/9, 124/14, 124/19,
    // 129/16, 133/19, each a signature-move cell of the map or between two;
    // other scenes get the same pattern around their own excitation.
    const double f = scene.excitation.frequency_hz, a = scene.excitation.acceleration_amplitude;
    const std::vector<std::pair<double, double>> factors = {{116. / 124, 12. / 14}, {120. / 124, 9. / 14},
                                                            {1., 1.},               {1., 19. / 14},
                                                            {129. / 124, 16. / 14}, {133. / 124, 19. / 14}};
    std::vector<OperatingPoint> points;
    for (const auto &[kf, ka] : factors)
      {
        // Rounded as a user would type them (0.1 Hz, 0.1 m/s²).
        const auto round1 = [](const double x) { return std::round(10 * x) / 10; };
        points.push_back({round1(kf * f), round1(ka * a)});
      }
    return points;
  }

  Scene at_point(const Scene &scene, const OperatingPoint &point)
  {
    Scene s                                = scene;
    s.excitation.frequency_hz              = point.frequency_hz;
    s.excitation.acceleration_amplitude    = point.acceleration_m_s2;
    validate_scene(s);
    return s;
  }

  std::vector<LadderRung> region_rungs(const Scene &scene, std::size_t &reference)
  {
    // The quick ladder's models: published, N = 10, N = 20 (converged in
    // N), the front's N = 15 and 6 + 4 corrections, the reference; every
    // explicit ROM but N = 20 checked at Δt/2. Where the front's pick holds
    // is what the region shows.
    return default_ladder(scene, LadderScope::quick, reference);
  }

  std::vector<LadderStudy> run_sites(const std::vector<StudySite> &sites, const SiteRungs &rungs_of,
                                     const unsigned int members, const MemberGroupRunner &runner,
                                     const MemberGroupRunner &rounds,
                                     const std::function<unsigned long(unsigned long)> &share)
  {
    if (sites.empty())
      throw std::invalid_argument("run_sites: no site");
    return run_planned_sites(site_plan(sites, rungs_of, members), members, runner, rounds, share);
  }

  namespace
  {
  std::vector<LadderStudy> run_planned_sites(const SitePlan &plan, const unsigned int members,
                                             const MemberGroupRunner &runner, const MemberGroupRunner &rounds,
                                             const Share &share)
  {
    const std::size_t n_sites = plan.scenes.size();
    std::vector<std::vector<EnsembleMember>> results = runner ? runner(plan.groups) : run_groups_in_threads(plan.groups);

    // Each site's rungs and its checks' first trials (the rung's members and
    // the trials ladder_groups_with_checks puts after the rungs), split as
    // the ladder splits its own (first_check_trials).
    std::vector<std::vector<std::vector<EnsembleMember>>> done, site_members(n_sites);
    for (std::size_t p = 0; p < n_sites; ++p)
      {
        const std::size_t first = plan.first_group[p], n_rungs = plan.rungs[p].size();
        std::size_t n_groups = n_rungs;
        for (const std::size_t n : first_trial_counts(plan.checks[p]))
          n_groups += n - 1;
        site_members[p].assign(std::make_move_iterator(results.begin() + first),
                               std::make_move_iterator(results.begin() + first + n_groups));
        for (auto &trials : first_check_trials(site_members[p], n_rungs, plan.checks[p]))
          done.push_back(std::move(trials));
      }
    std::vector<ConvergenceCheck> checks =
      run_convergence_checks(plan.check_scenes, plan.check_plans, std::move(done), members,
                             EnsembleSettings().perturbation, rounds ? rounds : runner, share);

    std::vector<LadderStudy> ladders;
    std::size_t next_check = 0;
    for (std::size_t p = 0; p < n_sites; ++p)
      {
        std::vector<ConvergenceCheck> checks_p(checks.begin() + next_check,
                                               checks.begin() + next_check + plan.checks[p].plans.size());
        next_check += plan.checks[p].plans.size();
        ladders.push_back(assemble_ladder(plan.scenes[p], plan.rungs[p], plan.references[p],
                                          plan.scenes[p].time_stepping.end_time, std::move(site_members[p]),
                                          std::move(checks_p), plan.checks[p]));
      }
    decide_classes(plan, members, ladders, rounds ? rounds : runner, share);
    return ladders;
  }
  } // namespace

  void work_on_sites(const std::vector<StudySite> &sites, const SiteRungs &rungs_of, const unsigned int members,
                     const std::function<void(const std::vector<MemberGroup> &)> &work,
                     const std::function<unsigned long(unsigned long)> &share)
  {
    work_on_planned_sites(site_plan(sites, rungs_of, members), members, work, share);
  }

  namespace
  {
  void work_on_planned_sites(const SitePlan &plan, const unsigned int members,
                             const std::function<void(const std::vector<MemberGroup> &)> &work, const Share &share)
  {
    work(plan.groups);
    std::vector<std::size_t> n_first;
    for (const RefinementPlan &c : plan.check_plans)
      n_first.push_back(first_round_size(c));
    work_on_convergence_checks(plan.check_scenes, plan.check_plans, n_first, members,
                               EnsembleSettings().perturbation, work, share);
    work_on_classes(plan, members, work, share);
  }
  } // namespace

  RegionStudy run_region(const Scene &scene, const std::vector<OperatingPoint> &points, const double end_time,
                         const unsigned int members, const MemberGroupRunner &runner, const MemberGroupRunner &rounds,
                         const std::function<unsigned long(unsigned long)> &share)
  {
    if (points.empty())
      throw std::invalid_argument("run_region: no operating point");
    RegionStudy study;
    study.points          = points;
    const SitePlan plan   = site_plan(region_sites(scene, points, end_time), region_rungs, members);
    study.ladders         = run_planned_sites(plan, members, runner, rounds, share);
    study.model_form      = probe_model_form(plan, members, study.ladders, rounds ? rounds : runner, share);
    return study;
  }

  void work_on_region(const Scene &scene, const std::vector<OperatingPoint> &points, const double end_time,
                      const unsigned int members, const std::function<void(const std::vector<MemberGroup> &)> &work,
                      const std::function<unsigned long(unsigned long)> &share)
  {
    const SitePlan plan = site_plan(region_sites(scene, points, end_time), region_rungs, members);
    work_on_planned_sites(plan, members, work, share);
    work_on_probes(plan, members, work, share);
  }

  std::vector<LadderRung> case_rungs(const Scene &scene, std::size_t &reference)
  {
    // The quick ladder without N = 10 and N = 20 (its check against N = 30
    // at Δt/8 would cost more than the rest on 60–120 s cases).
    std::vector<LadderRung> rungs;
    std::size_t quick_reference = 0;
    const std::vector<LadderRung> quick = default_ladder(scene, LadderScope::quick, quick_reference);
    for (std::size_t i = 0; i < quick.size(); ++i)
      if (i == 0 || quick[i].front_candidate || i == quick_reference)
        rungs.push_back(quick[i]);
    reference = rungs.size() - 1;
    return rungs;
  }

  std::vector<StudySite> published_case_sites(const std::string &scene_file, const std::vector<std::string> &overrides)
  {
    std::vector<StudySite> sites;
    for (const SimulationCase &c : published_cases())
      sites.push_back({c.name, read_case_scene(scene_file, c, overrides)});
    return sites;
  }

  ClassCounts class_counts(const std::vector<EnsembleMember> &members)
  {
    ClassCounts counts;
    for (const EnsembleMember &m : members)
      if (m.analysis.valid)
        ++counts[to_string(m.analysis.outcome)];
    return counts;
  }

  std::string majority_class(const ClassCounts &counts)
  {
    std::string best;
    unsigned int n = 0;
    bool tie       = false;
    for (const auto &[name, k] : counts)
      if (k > n)
        best = name, n = k, tie = false;
      else if (k == n)
        tie = true;
    return n == 0 ? "–" : tie ? "split" : best;
  }

  bool basis_gap(const LadderStudy &l)
  {
    const auto rung  = std::find_if(l.rungs.begin(), l.rungs.end(),
                                    [](const LadderRungResult &r) { return r.rung.converged_in_n; });
    const auto check = std::find_if(l.checks.begin(), l.checks.end(),
                                    [](const ConvergenceCheck &c) { return c.parameter == "N" && c.trials.size() > 1; });
    if (rung == l.rungs.end() || check == l.checks.end())
      return false;
    const std::vector<double> ref = outcome_samples(l.rungs[l.reference].members).final_position;
    const std::vector<double> a   = outcome_samples(rung->members).final_position;
    const std::vector<double> b   = outcome_samples(check->trials[1].members).final_position;
    if (ref.empty() || a.empty() || b.empty())
      return false;
    return !ends_alike(compare_samples(a, ref)) && !ends_alike(compare_samples(b, ref));
  }

  std::vector<LadderRung> model_form_probes(const Scene &scene, const ModelSetting &reference,
                                            const ModelSetting &larger_basis)
  {
    ModelSetting all = scene_model(scene, "rom");
    all.n_modes      = fe_bending_modes(scene);
    all.integrator   = "implicit";
    all.theta        = reference.theta;
    all.time_step    = reference.time_step;
    all.damped_modes = scene.discretisation.n_modes;
    ModelSetting basis = larger_basis;
    basis.integrator   = "implicit";
    basis.theta        = reference.theta;
    std::ostringstream theta;
    theta << reference.theta;
    return {{"ROM all " + std::to_string(all.n_modes) + " modes at the reference's step and θ",
             "every bending mode of the FE mesh, stepped as the reference (implicit, its θ and Δt), damping the "
             "scene's N: the FE's dynamics in the ROM's form",
             all},
            {"ROM N=" + std::to_string(basis.n_modes) + " with θ=" + theta.str(),
             "the N check's larger basis at its own step, stepped with the reference's θ instead of the explicit "
             "midpoint rule",
             basis}};
  }

  double majority_p_value(const ClassCounts &counts)
  {
    unsigned int n = 0;
    for (const auto &[name, k] : counts)
      n += k;
    const std::string majority = majority_class(counts);
    if (n == 0 || majority == "split")
      return 1;
    const unsigned int k = counts.at(majority);
    // P(X ≥ k) = Σ_{j ≥ k} C(n, j) / 2ⁿ, the binomial coefficients by
    // their recurrence (n is a few dozen members at most).
    double c = 1, tail = 0; // C(n, j) from j = 0
    for (unsigned int j = 0; j <= n; ++j)
      {
        if (j >= k)
          tail += c;
        c = c * (n - j) / (j + 1);
      }
    return tail / std::pow(2., n);
  }

  bool majority_decided(const ClassCounts &counts) { return majority_p_value(counts) < class_decision_level; }

  bool alike_with_reference(const SampleComparison &end_positions, const ClassCounts &model,
                            const ClassCounts &reference)
  {
    const std::string a = majority_class(model), b = majority_class(reference);
    const bool decided  = a != "–" && a != "split" && b != "–" && b != "split";
    return decided && a == b && ends_alike(end_positions);
  }
} // namespace beamslider
