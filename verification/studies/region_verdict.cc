// The verdict across the signature-move region, see region_verdict.h.
#include "verification/studies/region_verdict.h"

#include "verification/studies/simulation_cases.h"

#include <cmath>
#include <iterator>
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
      std::vector<Scene> scenes; // per site, its end time set
      std::vector<std::vector<LadderRung>> rungs;
      std::size_t reference = 0;
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
          std::vector<LadderRung> rungs = rungs_of(s, plan.reference);
          LadderChecks checks           = ladder_checks(s, rungs, plan.reference);
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
          plan.scenes.push_back(s);
          plan.rungs.push_back(rungs);
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
    const SitePlan plan = site_plan(sites, rungs_of, members);
    std::vector<std::vector<EnsembleMember>> results = runner ? runner(plan.groups) : run_groups_in_threads(plan.groups);

    // Each site's rungs and its checks' first trials (the rung's members and
    // the trials ladder_groups_with_checks puts after the rungs), split as
    // the ladder splits its own (first_check_trials).
    std::vector<std::vector<std::vector<EnsembleMember>>> done, site_members(sites.size());
    for (std::size_t p = 0; p < sites.size(); ++p)
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
    for (std::size_t p = 0; p < sites.size(); ++p)
      {
        std::vector<ConvergenceCheck> checks_p(checks.begin() + next_check,
                                               checks.begin() + next_check + plan.checks[p].plans.size());
        next_check += plan.checks[p].plans.size();
        ladders.push_back(assemble_ladder(plan.scenes[p], plan.rungs[p], plan.reference,
                                          plan.scenes[p].time_stepping.end_time, std::move(site_members[p]),
                                          std::move(checks_p), plan.checks[p]));
      }
    return ladders;
  }

  void work_on_sites(const std::vector<StudySite> &sites, const SiteRungs &rungs_of, const unsigned int members,
                     const std::function<void(const std::vector<MemberGroup> &)> &work,
                     const std::function<unsigned long(unsigned long)> &share)
  {
    const SitePlan plan = site_plan(sites, rungs_of, members);
    work(plan.groups);
    std::vector<std::size_t> n_first;
    for (const RefinementPlan &c : plan.check_plans)
      n_first.push_back(first_round_size(c));
    work_on_convergence_checks(plan.check_scenes, plan.check_plans, n_first, members,
                               EnsembleSettings().perturbation, work, share);
  }

  RegionStudy run_region(const Scene &scene, const std::vector<OperatingPoint> &points, const double end_time,
                         const unsigned int members, const MemberGroupRunner &runner, const MemberGroupRunner &rounds,
                         const std::function<unsigned long(unsigned long)> &share)
  {
    if (points.empty())
      throw std::invalid_argument("run_region: no operating point");
    RegionStudy study;
    study.points  = points;
    study.ladders = run_sites(region_sites(scene, points, end_time), region_rungs, members, runner, rounds, share);
    return study;
  }

  void work_on_region(const Scene &scene, const std::vector<OperatingPoint> &points, const double end_time,
                      const unsigned int members, const std::function<void(const std::vector<MemberGroup> &)> &work,
                      const std::function<unsigned long(unsigned long)> &share)
  {
    work_on_sites(region_sites(scene, points, end_time), region_rungs, members, work, share);
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

  bool alike_with_reference(const SampleComparison &end_positions, const ClassCounts &model,
                            const ClassCounts &reference)
  {
    const std::string a = majority_class(model), b = majority_class(reference);
    const bool decided  = a != "–" && a != "split" && b != "–" && b != "split";
    return decided && a == b && ends_alike(end_positions);
  }
} // namespace beamslider
