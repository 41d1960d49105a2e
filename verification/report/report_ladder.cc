// The error ladder's files and its Markdown, see report_ladder.h.
#include "verification/report/report_ladder.h"

#include "verification/report/charts.h"
#include "verification/report/member_files.h"
#include "verification/report/report.h"
#include "verification/report/report_convergence.h"
#include "io/console.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/model_choice.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

namespace beamslider
{
  namespace
  {
    using clock = std::chrono::steady_clock;

    // "0.331 [0.330, 0.332]", or a dash for an outcome no member had.
    std::string median_range(const OutcomeStatistics &s, const int digits)
    {
      if (s.n == 0)
        return "–";
      return fixed(s.median, digits) + " [" + fixed(s.min, digits) + ", " + fixed(s.max, digits) + "]";
    }

    // Decimals of a distance in x_C/L: 3, or 4 below 0.01 so that a small
    // W₁ and its interval do not print as 0.001 [0.000, 0.001].
    int distance_digits(const double upper)
    {
      return upper < 0.01 ? 4 : 3;
    }

    std::string distance(const SampleComparison &c)
    {
      if (c.n_a == 0 || std::isnan(c.wasserstein))
        return "–";
      const int d = distance_digits(std::max(c.interval_high, c.spread));
      return fixed(c.wasserstein, d) + " [" + fixed(c.interval_low, d) + ", " + fixed(c.interval_high, d) + "]";
    }

    std::string spread(const SampleComparison &c)
    {
      return fixed(c.spread, distance_digits(std::max(c.interval_high, c.spread)));
    }

    std::string classes(const std::map<std::string, unsigned int> &counts)
    {
      std::string s;
      for (const auto &[name, n] : counts)
        s += (s.empty() ? "" : ", ") + std::to_string(n) + "× " + name;
      return s.empty() ? "–" : s;
    }

    // What the ladder's convergence checks compare, on the console.
    void announce_checks(const LadderChecks &checks, const std::string &prefix)
    {
      for (const RefinementPlan &plan : checks.plans)
        console() << prefix << "check: " << plan.name << ", " << plan.models[0].label() << " against "
                  << plan.models[1].label() << " beside the rungs"
                  << (plan.models.size() > 2 ? ", refined further until they agree (at most " +
                                                 std::to_string(plan.models.size() - 1) + " refinements)"
                                             : std::string())
                  << std::endl;
    }

    // The checks' evidence under the ladder's headline table.
    std::string ladder_convergence_paragraph(const std::vector<ConvergenceCheck> &checks)
    {
      const bool proven =
        std::all_of(checks.begin(), checks.end(), [](const ConvergenceCheck &c) { return c.converged; });
      std::ostringstream md;
      md << "**The reference proves itself.** Every check runs the same ensemble with the model refined (the FE "
            "reference in Δt, halved at most "
         << reference_max_halvings
         << " times; the ROM that claims to be converged in N against ⌈1.5 N⌉ modes) and accepts it when the "
            "refinement ends where it ends: within the ensembles' spread (the test above), or closer than "
         << fixed(convergence_resolution, 3) << " L, a difference no verdict here rests on. "
         << (proven ? "Every check converged."
                    : "**Not every check converged: the verdicts below rest on an unproven model.**")
         << "\n\n"
         << describe_convergence(checks);
      return md.str();
    }

    // Rough wall time of one member [s] on this machine, for the announcement
    // only (measured: ROM N=5 at 2e-5 s 0.05 s per simulated second, FE on
    // 32 elements at 1e-5 s 3.4 s per simulated second).
    double expected_member_seconds(const ModelSetting &s, const Scene &scene, const double end_time)
    {
      return cost_per_simulated_second(s, scene) * end_time * 0.6e-6;
    }

    // Shift of the median final position from rung i − 1 to rung i [x_C/L].
    double median_shift(const LadderStudy &study, const std::size_t i)
    {
      return study.rungs[i].final_position.median - study.rungs[i - 1].final_position.median;
    }

    // How many members the ladder runs, for the text.
    struct LadderSize
    {
      // " (2 on the 3 diagnostic rungs)": the diagnostic rungs run fewer
      // members; empty without diagnostic rungs.
      std::string diagnostic_members;
      unsigned int n_member_runs = 0;
    };

    // Counts the members.
    LadderSize ladder_size(const std::vector<LadderRung> &rungs, const LadderRunSettings &settings)
    {
      const unsigned int n_members = settings.members;
      unsigned int n_diagnostic    = 0;
      LadderSize size;
      for (const auto &r : rungs)
        {
          n_diagnostic += r.diagnostic;
          size.n_member_runs += rung_members(r, n_members);
        }
      if (n_diagnostic > 0)
        size.diagnostic_members = " (" + std::to_string(rung_members(LadderRung{"", "", {}, true}, n_members)) +
                                  " on the " + std::to_string(n_diagnostic) + " diagnostic rungs)";
      return size;
    }

    // Says on the console what runs and roughly how long it takes.
    void announce_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, const LadderRunSettings &settings)
    {
      double expected = 0;
      for (const auto &r : rungs)
        expected += expected_member_seconds(r.model, scene, settings.end_time) * rung_members(r, settings.members) /
                    2; // two cores
      console() << settings.progress_prefix << "error ladder, " << rungs.size() << " rungs × " << settings.members
                << " members" << ladder_size(rungs, settings).diagnostic_members << " over " << settings.end_time
                << " s, expected about " << fixed(expected / 60, 1) << " min" << std::endl;
    }

    // Runs the members of every rung and of the reference's convergence
    // checks (member_runs.csv) and says on the console how each check
    // ended. `n_kept`: the members read back from an earlier, stopped run.
    LadderStudy run_ladder_members(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                                   const std::size_t reference, const LadderRunSettings &settings,
                                   std::size_t &n_kept)
    {
      MemberRunsSettings runs = member_files_settings(dir, "ladder", MpiSession::active(), settings.progress_prefix);
      runs.n_kept             = &n_kept;
      if (!settings.shared_members_root.empty())
        share_fe_members(runs, settings.shared_members_root); // its FE reference, if the region or the cases ran it
      const auto rounds = count_check_rounds(runs);
      announce_checks(ladder_checks(scene, rungs, reference), settings.progress_prefix);
      const LadderStudy study = run_ladder(
        scene, rungs, reference, settings.end_time, settings.members,
        [&](const LadderRung &rung, const std::size_t i) {
          console() << settings.progress_prefix << "rung " << i << ": " << rung.name << " (" << rung.model.label()
                    << ")" << std::endl;
        },
        member_runs_runner(runs), check_rounds_runner(runs), round_sharer(runs.mpi));
      for (const ConvergenceCheck &c : study.checks)
        (c.converged ? console() : std::cerr) << settings.progress_prefix << c.verdict() << std::endl;
      if (!runs.mpi || runs.mpi->rank() == 0)
        remove_unreached_check_files(dir, "member_runs.csv", *rounds);
      return study;
    }

    // "### 5.1 title" in the report (numbering "5."), "## title" in a summary of its own.
    std::string ladder_heading(const std::string &numbering, const unsigned int k, const std::string &title)
    {
      return numbering.empty() ? "## " + title + "\n\n" : "### " + numbering + std::to_string(k) + " " + title + "\n\n";
    }

    // What the ensembles are and how they are compared, then the headline
    // table: every rung against the reference.
    void describe_headline(std::ostream &md, const LadderStudy &study, const std::size_t reference,
                           const LadderRunSettings &settings, const std::string &diagnostic_members)
    {
      const LadderRungResult &ref = study.rungs[reference];
      md << "Every model runs as an ensemble of " << settings.members << " members" << diagnostic_members << " over "
         << settings.end_time << " s; member m starts at x_C/L + m·1e-9, nothing else differs. The outcomes come from the one trace analysis "
            "(doc/verification.md §5): the final x_C/L and amplitude are means over the last seconds, the jump time is "
            "that of the first jump to the upper branch. Two ensembles are compared by the Wasserstein distance W₁ of "
            "their final positions (in x_C/L; the mean distance the members must move to match) with a 90 % bootstrap "
            "interval; the spread is W₁ between the halves of one ensemble, i.e. what its own scatter gives at this size. "
            "A model is distinguishable from another when the interval's lower end exceeds the spread. Reference: **"
         << ref.rung.name << "** (" << ref.rung.model.label() << ")"
         << (!settings.quick_ladder ? "" : "; `verify --full` runs 8 members over 40 s and adds the implicit ROM with 20 modes; "
                         "`verify --full --diagnostics` adds, with 4 members each, the implicit ROM with all the mesh's "
                         "bending modes at Δt/4 and the midpoint-rule FE (θ = ½) at Δt/4, Δt/8, Δt/2 and Δt")
         << ". Cost: the stated model of `fe_rom_study.h` in units of one step of the published ROM (not a clock reading); "
            "wall time is per member on this machine, for information.\n\n"
         << ladder_heading(settings.numbering, 1, "Headline: every model against the FE reference")
         << "| model | what it changes | wall per member [s] | cost [units] | final x_C/L median [min, max] | final amplitude "
            "[h] median [min, max] | jump time [s] median [min, max] (members) | W₁ to reference [90 %] | outcomes |\n"
            "|---|---|---|---|---|---|---|---|---|\n";
      for (std::size_t i = 0; i < study.rungs.size(); ++i)
        {
          const LadderRungResult &r = study.rungs[i];
          md << "| " << (i == reference ? "**" + r.rung.name + "**" : r.rung.name) << " | " << r.rung.change << " | "
             << fixed(r.wall_seconds_per_member, 1) << " | " << sci(r.cost_units, 2) << " | "
             << median_range(r.final_position, 3) << " | " << median_range(r.final_amplitude, 2) << " | "
             << median_range(r.jump_time, 2) << " (" << r.jump_time.n << "/" << r.members.size() << ") | "
             << (i == reference ? "reference" : distance(r.position_to_reference) +
                                                    (r.position_to_reference.distinguishable ? "" : " (indistinguishable)"))
             << " | " << classes(r.outcome_classes) << (r.n_failed ? ", " + std::to_string(r.n_failed) + " failed" : "")
             << " |\n";
        }
    }

    // The tables in ladder order, from the members (read back or computed).
    // Each file is renamed into place as it closes here, before the chart reads it.
    void write_ladder_tables(const std::string &dir, const LadderStudy &study, const std::size_t reference)
    {
      LadderFiles files(dir);
      for (std::size_t i = 0; i < study.rungs.size(); ++i)
        files.add_rung(study.rungs[i], i, i == reference);
      files.write_steps(study);
    }

    // The ROM that claims to be converged in N: the last explicit ROM rung.
    const LadderRungResult *converged_rom(const LadderStudy &study)
    {
      const LadderRungResult *converged = nullptr;
      for (const auto &r : study.rungs)
        if (r.rung.model.family == "rom" && r.rung.model.integrator == "explicit" && !r.rung.front_candidate)
          converged = &r;
      return converged;
    }

    // The midpoint-rule FE rungs (θ = ½, the scene's damped set) but the
    // reference, by step from the largest.
    std::vector<const LadderRungResult *> midpoint_fe_by_step(const LadderStudy &study, const LadderRungResult &ref)
    {
      std::vector<const LadderRungResult *> midpoint_fe;
      for (const auto &r : study.rungs)
        if (&r != &ref && r.rung.model.family == "fe" && r.rung.model.theta == 0.5 && r.rung.model.damped_modes == 0 &&
            r.rung.model.axial_inertia)
          midpoint_fe.push_back(&r);
      std::sort(midpoint_fe.begin(), midpoint_fe.end(), [](const LadderRungResult *a, const LadderRungResult *b) {
        return a->rung.model.time_step > b->rung.model.time_step;
      });
      return midpoint_fe;
    }

    // One rung's end state against the reference's, in a sentence.
    std::string end_state_verdict(const LadderRungResult &r, const LadderRungResult &ref)
    {
      const SampleComparison &d = r.position_to_reference;
      std::ostringstream s;
      s << r.rung.name << " ends at x_C/L = " << fixed(r.final_position.median, 3) << " against the reference's "
        << fixed(ref.final_position.median, 3) << ": W₁ = " << distance(d) << ", spread " << spread(d) << " — "
        << (d.distinguishable ? "distinguishable" : "indistinguishable at this ensemble size");
      return s.str();
    }

    // The verdict in words: the published ROM, the converged ROM, and the
    // midpoint-rule FE in Δt where the ladder has it.
    void describe_end_state(std::ostream &md, const LadderStudy &study, const LadderRungResult &ref,
                            const LadderRunSettings &settings)
    {
      const LadderRungResult &published = study.rungs.front();
      const LadderRungResult *converged = converged_rom(study);
      const std::vector<const LadderRungResult *> midpoint_fe = midpoint_fe_by_step(study, ref);
      md << "\n**Verdict on the end state.** " << end_state_verdict(published, ref) << ". ";
      if (converged && converged != &published)
        md << end_state_verdict(*converged, ref) << ". ";
      if (!midpoint_fe.empty())
        {
          md << "The midpoint-rule FE (θ = ½) ends at";
          for (std::size_t k = 0; k < midpoint_fe.size(); ++k)
            md << (k ? "," : "") << " " << fixed(midpoint_fe[k]->final_position.median, 3) << " ("
               << midpoint_fe[k]->rung.name.substr(3) << ")";
          md << ": where it stops moving for a halving of Δt it sits on a plateau, not at its limit; the reference, "
                "with the modes its step cannot resolve damped by the scheme, is at that limit (on mueller2023 the "
                "midpoint rule ends at 0.409 L at 1.25e-6 s and at 6.25e-7 s, doc/verification.md §7). ";
        }
      if (midpoint_fe.empty())
        md << "The reference is the scene's FE model (" << ref.rung.model.label()
           << "). On mueller2023 it ends, after 40 s, where the midpoint-rule FE converged in Δt ends (0.409 L at "
              "1.25e-6 and 6.25e-7 s, 2 members each) and where the ROM converged in N ends, with an eighth of the "
              "steps; the midpoint rule at 5e-6 and 2.5e-6 s sits on a plateau at 0.371 L (doc/verification.md §7). "
              "`verify --full --diagnostics` shows that plateau. ";
      if (settings.quick_ladder)
        md << "This quick ladder stops at " << settings.end_time << " s (the reference's median here: "
           << fixed(ref.final_position.median, 3)
           << " L); on mueller2023 that is before the end state: the reference's members are still moving and end at "
              "0.409 L after 40 s (reports/mueller2023-full), so the positions above are a snapshot on the way and the "
              "verdict on the end state is that of `verify --full`. ";
      // Every sentence above ends with ". ".
      md << "What all models share is in the last column (the class of each member's adaptation) and the jump-time "
            "column.\n\n";
    }

    // Which steps carry the difference: computed from this run, not
    // asserted (the distinguishable steps, largest shift first).
    void describe_carrying_steps(std::ostream &md, const LadderStudy &study)
    {
      std::vector<std::size_t> carried;
      for (std::size_t i = 1; i < study.rungs.size(); ++i)
        if (study.steps[i].n_a > 0 && study.steps[i].distinguishable)
          carried.push_back(i);
      std::sort(carried.begin(), carried.end(), [&](const std::size_t a, const std::size_t b) {
        return std::abs(median_shift(study, a)) > std::abs(median_shift(study, b));
      });
      if (carried.empty())
        {
          md << "\nNo step of this ladder is distinguishable from its neighbour at this ensemble size.\n";
          return;
        }
      md << "\n**Which steps carry the differences** (distinguishable steps, largest shift first): ";
      for (std::size_t k = 0; k < carried.size(); ++k)
        md << (k ? "; " : "") << study.rungs[carried[k] - 1].rung.name << " → " << study.rungs[carried[k]].rung.name
           << " (" << signed_fixed(median_shift(study, carried[k]), 3) << " L: "
           << study.rungs[carried[k]].rung.change << ")";
      md << ". Every other step is within the ensembles' own scatter.\n";
    }

    // Each step of the ladder, rung i − 1 against rung i, under `heading`.
    void describe_steps(std::ostream &md, const LadderStudy &study, const std::string &heading)
    {
      md << heading
         << "Each row compares a rung with the one before it (W₁ of the final positions, interval and spread as above; shift = "
            "difference of the medians).\n\n"
         << "| step | shift of the median x_C/L | W₁ [90 %] | spread | distinguishable |\n|---|---|---|---|---|\n";
      for (std::size_t i = 1; i < study.rungs.size(); ++i)
        {
          const SampleComparison &c = study.steps[i];
          md << "| " << study.rungs[i - 1].rung.name << " → " << study.rungs[i].rung.name << " | ";
          if (c.n_a == 0)
            {
              md << "– | – | – | – |\n";
              continue;
            }
          md << signed_fixed(median_shift(study, i), 3) << " | " << distance(c) << " | " << spread(c) << " | "
             << (c.distinguishable ? "yes" : "no") << " |\n";
        }
      describe_carrying_steps(md, study);
    }

    // What `--model auto` picks on this ladder's rows without a tolerance
    // (model_choice.h), and why, in a sentence.
    void describe_model_choice(std::ostream &md, const LadderStudy &study, const std::vector<LadderChoiceRow> &rows,
                               const double tolerance)
    {
      const LadderChoiceRow &chosen           = cheapest_within(rows, tolerance);
      const std::vector<std::size_t> front    = speed_accuracy_front(study);
      const std::size_t picked                = static_cast<std::size_t>(&chosen - rows.data());
      const LadderRungResult &r = study.rungs[picked], &published = study.rungs.front();
      md << "\n**The model choice on this ladder.** `--model auto` (without `--tolerance`) grants W₁ ≤ "
         << fixed(tolerance, 4)
         << " L: the upper end of the reference's own W₁ interval to its refinement, at least "
         << choice_tolerance_floor << " L. It picks the cheapest model by the stated cost whose W₁ interval to the "
         << "reference ends within that and which ends alike refined: **" << chosen.rung << "** ("
         << chosen.model.label() << ")";
      if (chosen.reference)
        md << ", the reference itself: no reduced model here met the tolerance.";
      else
        md << ", W₁ " << distance(r.position_to_reference) << ", " << fixed(r.cost_units / published.cost_units, 1)
           << "× the published ROM's stated cost and " << fixed(r.wall_seconds_per_member / published.wall_seconds_per_member, 1)
           << "× its wall time per member on this machine"
           << (std::find(front.begin(), front.end(), picked) != front.end()
                 ? "; it is on the front."
                 : "; it is off the front only because a cheaper model has the smaller W₁ with the wider interval.");
      md << " `simulate --model auto` decides on the quick ladder (4 members over 25 s) of the scene it is given.\n\n";
    }

    // What a refinement check ran: "Δt/2" or "N=30 Δt/8" against the rung.
    std::string refinement_text(const ModelSetting &rung, const ModelSetting &refined)
    {
      std::ostringstream t;
      if (refined.n_modes != rung.n_modes)
        t << "N=" << refined.n_modes << " ";
      t << "Δt/" << std::lround(rung.time_step / refined.time_step);
      return t.str();
    }

    // What 3× the published ROM's wall time per member buys on this ladder
    // (issue 58's budget), and, if no reduced model within it lands within
    // the choice's tolerance, the cheapest that does and what its step is:
    // an explicit rung's step halves from the scene's until it is below
    // 2/ω_max of its basis, so each vector that raises ω_max past a halving
    // doubles the cost.
    void describe_budget(std::ostream &md, const LadderStudy &study, const std::vector<std::size_t> &checked,
                         const std::vector<LadderChoiceRow> &rows, const double tolerance)
    {
      const LadderRungResult &published = study.rungs.front();
      const double budget               = 3 * published.wall_seconds_per_member;
      const auto lands                  = [&](const std::size_t i) { return lands_within(rows[i], tolerance); };
      const auto ratio = [&](const std::size_t i) {
        return fixed(study.rungs[i].wall_seconds_per_member / published.wall_seconds_per_member, 1) + "×";
      };
      md << "\n**Within 3× the published ROM's wall time per member** (" << fixed(budget, 2)
         << " s here), a model lands when its W₁ interval ends within " << fixed(tolerance, 4)
         << " L (the choice's tolerance below) and it ends alike refined: ";
      std::optional<std::size_t> cheapest_landing;
      bool first = true;
      for (const std::size_t i : checked)
        {
          if (lands(i) && (!cheapest_landing || study.rungs[i].wall_seconds_per_member <
                                                  study.rungs[*cheapest_landing].wall_seconds_per_member))
            cheapest_landing = i;
          if (study.rungs[i].wall_seconds_per_member > budget)
            continue;
          md << (first ? "" : "; ") << study.rungs[i].rung.name << " (" << ratio(i) << ", Δt "
             << study.rungs[i].rung.model.time_step << " s) "
             << (lands(i) ? "lands"
                          : !rows[i].refined_alike ? "moves when refined"
                                                   : "W₁ up to " + fixed(rows[i].w1_high, 3) + " L");
          first = false;
        }
      md << (first ? "no checked rung costs that little" : "") << ". ";
      if (cheapest_landing)
        md << "The cheapest checked rung that lands is " << study.rungs[*cheapest_landing].rung.name << " at "
           << ratio(*cheapest_landing) << " (Δt " << study.rungs[*cheapest_landing].rung.model.time_step << " s). ";
      else
        md << "No checked rung lands. ";
      md << "What sets the price: an explicit rung's cost is its coordinates times its steps, and its step is the "
            "scene's Δt halved until it is below 2/ω_max of its basis. The vectors that carry the slider's corner "
            "loads (higher modes, static corrections, Ritz vectors) are the stiff ones: each raises ω_max, and one "
            "that crosses a halving doubles the cost of all the others. An implicit rung is not bound to that "
            "limit: it keeps its step and pays a Newton solve a step instead, about "
         << implicit_rom_step_factor
         << " explicit steps of its basis (above ½ its θ damps what the step cannot resolve). Modes chosen by their participation instead "
            "of by frequency are not among the candidates: ranked by their energy over a run they are the lowest "
            "modes, and ranked by the impulse the impacts feed them they reach the highest mode offered, and its step "
            "(doc/findings.md, 2026-12-04; `scripts/modal_participation.py`).\n";
    }

    // The speed–accuracy front: every rung with a refinement check (in Δt,
    // or in N) and its cost, its W₁ to the reference, its end state refined,
    // and whether it is on the front; also as front.csv. Then the model
    // `--model auto` would pick from these rows (model_choice.h).
    void describe_front(std::ostream &md, const std::string &dir, const LadderStudy &study, const std::string &heading)
    {
      std::vector<std::size_t> checked;
      for (std::size_t i = 0; i < study.rungs.size(); ++i)
        if (study.refinement_check(i) && i != study.reference) // the reference's check: the paragraph above
          checked.push_back(i);
      if (checked.empty())
        return;
      const std::vector<std::size_t> front = speed_accuracy_front(study);
      const auto on_front = [&](const std::size_t i) { return std::find(front.begin(), front.end(), i) != front.end(); };
      CsvWriter csv(dir + "/front.csv",
                    {"rung", "n_modes", "static_corrections", "time_step_s", "wall_s_per_member", "cost_units",
                     "final_x_median", "w1_to_reference", "w1_low", "w1_high", "spread", "refinement",
                     "refined_final_x_median", "refined_alike", "on_front"});
      md << heading
         << "Every explicit ROM rung also ran at Δt/2 with the same members (the one converged in N with ⌈1.5 N⌉ "
            "modes at their smaller step): a model that lands where the reference lands only at one step has not "
            "shown it, because the end state can be bistable (~0.33 or ~0.41 L on mueller2023) and which state a "
            "discrete model reaches can change with its step. The front holds the rungs that end alike refined and "
            "that no other such rung beats on both the stated cost and W₁.\n\n"
         << "| rung | Δt [s] | wall s/member | cost [units] | end x_C/L | W₁ to the reference [90 %] | refined | "
            "on the front |\n|---|---|---|---|---|---|---|---|\n";
      for (const std::size_t i : checked)
        {
          const LadderRungResult &r     = study.rungs[i];
          const ConvergenceCheck &check = *study.refinement_check(i);
          const bool refined_ran        = check.trials.size() > 1;
          const double refined_median   = refined_ran ? check.trials[1].final_position.median : NAN;
          const std::string refinement  = refined_ran ? refinement_text(r.rung.model, check.trials[1].model) : "";
          const SampleComparison &c     = r.position_to_reference;
          md << "| " << r.rung.name << " | " << r.rung.model.time_step << " | " << fixed(r.wall_seconds_per_member, 2)
             << " | " << r.cost_units << " | " << median_range(r.final_position, 3) << " | " << distance(c) << " | "
             << (refined_ran ? fixed(refined_median, 3) + " at " + refinement +
                                 (check.converged ? " (alike)" : " (moves)")
                             : std::string("–"))
             << " | " << (on_front(i) ? "**yes**" : "no") << " |\n";
          csv.row({r.rung.name, CsvWriter::cell(r.rung.model.n_modes),
                   CsvWriter::cell(r.rung.model.n_static_corrections), CsvWriter::cell(r.rung.model.time_step),
                   CsvWriter::cell(r.wall_seconds_per_member, 4), CsvWriter::cell(r.cost_units),
                   r.final_position.n ? CsvWriter::cell(r.final_position.median, 6) : "",
                   c.n_a ? CsvWriter::cell(c.wasserstein, 6) : "", c.n_a ? CsvWriter::cell(c.interval_low, 6) : "",
                   c.n_a ? CsvWriter::cell(c.interval_high, 6) : "", c.n_a ? CsvWriter::cell(c.spread, 6) : "",
                   refinement, refined_ran ? CsvWriter::cell(refined_median, 6) : "", check.converged ? "1" : "0",
                   on_front(i) ? "1" : "0"});
        }
      csv.close();
      // The choice's rows and tolerance, once for both paragraphs.
      const std::vector<LadderChoiceRow> rows = choice_rows(study);
      const double tolerance                  = default_choice_tolerance(rows);
      describe_budget(md, study, checked, rows, tolerance);
      describe_model_choice(md, study, rows, tolerance);
    }
  } // namespace

  LadderFiles::LadderFiles(const std::string &dir)
    : dir_(dir)
    , rungs_(dir + "/ladder.csv",
             {"index", "rung", "family", "n_modes", "n_elements", "integrator", "time_step_s", "damped_modes",
              "reference", "members", "failed", "wall_s_per_member", "cost_units", "final_x_n", "final_x_median",
              "final_x_min", "final_x_max", "final_amplitude_n", "final_amplitude_median", "final_amplitude_min",
              "final_amplitude_max", "jump_n", "jump_time_median_s", "jump_time_min_s", "jump_time_max_s",
              "w1_to_reference", "w1_low", "w1_high", "spread", "distinguishable"})
    , members_(dir + "/ladder_members.csv",
               {"rung", "member", "perturbation", "status", "jump_time_s", "final_x_over_L", "final_amplitude_over_h",
                "wall_s", "outcome"})
  {}

  void LadderFiles::add_rung(const LadderRungResult &r, const std::size_t index, const bool is_reference)
  {
    const ModelSetting &m = r.rung.model;
    auto stats            = [](const OutcomeStatistics &s) {
      return std::vector<std::string>{CsvWriter::cell(static_cast<unsigned int>(s.n)),
                                      s.n ? CsvWriter::cell(s.median, 6) : "", s.n ? CsvWriter::cell(s.min, 6) : "",
                                      s.n ? CsvWriter::cell(s.max, 6) : ""};
    };
    std::vector<std::string> cells{CsvWriter::cell(static_cast<unsigned int>(index)),
                                   r.rung.name,
                                   m.family,
                                   CsvWriter::cell(m.family == "rom" ? m.n_modes : 0u),
                                   CsvWriter::cell(m.family == "fe" ? m.n_elements : 0u),
                                   m.family == "rom" ? m.integrator : "implicit",
                                   CsvWriter::cell(m.time_step),
                                   CsvWriter::cell(m.damped_modes),
                                   is_reference ? "1" : "0",
                                   CsvWriter::cell(static_cast<unsigned int>(r.members.size())),
                                   CsvWriter::cell(r.n_failed),
                                   CsvWriter::cell(r.wall_seconds_per_member, 4),
                                   CsvWriter::cell(r.cost_units, 4)};
    for (const auto *s : {&r.final_position, &r.final_amplitude, &r.jump_time})
      for (const auto &c : stats(*s))
        cells.push_back(c);
    const SampleComparison &d = r.position_to_reference;
    const bool compared       = d.n_a > 0 && !std::isnan(d.wasserstein);
    for (const double x : {d.wasserstein, d.interval_low, d.interval_high, d.spread})
      cells.push_back(compared ? CsvWriter::cell(x, 6) : "");
    cells.push_back(compared ? (d.distinguishable ? "1" : "0") : "");
    rungs_.row(cells);

    for (const auto &member : r.members)
      {
        const TraceAnalysis &a = member.analysis;
        members_.row({r.rung.name, CsvWriter::cell(member.index), CsvWriter::cell(member.perturbation),
                      to_string(member.result.status), a.valid && a.jumped ? CsvWriter::cell(a.jump_time, 6) : "",
                      a.valid ? CsvWriter::cell(a.final_position, 6) : "",
                      a.valid ? CsvWriter::cell(a.final_amplitude, 6) : "", CsvWriter::cell(member.wall_seconds, 4),
                      a.valid ? to_string(a.outcome) : ""});
      }
  }

  void LadderFiles::write_steps(const LadderStudy &study) const
  {
    CsvWriter steps(dir_ + "/ladder_steps.csv",
                    {"from", "to", "median_shift", "w1", "w1_low", "w1_high", "spread", "distinguishable"});
    for (std::size_t i = 1; i < study.rungs.size(); ++i)
      {
        const SampleComparison &c = study.steps[i];
        if (c.n_a == 0)
          continue;
        steps.row({study.rungs[i - 1].rung.name, study.rungs[i].rung.name,
                   CsvWriter::cell(median_shift(study, i), 6),
                   CsvWriter::cell(c.wasserstein, 6), CsvWriter::cell(c.interval_low, 6),
                   CsvWriter::cell(c.interval_high, 6), CsvWriter::cell(c.spread, 6), c.distinguishable ? "1" : "0"});
      }
  }

  LadderStudy run_ladder_study(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                               const std::size_t reference, const LadderRunSettings &settings, std::size_t &n_kept)
  {
    announce_ladder(scene, rungs, settings);
    return run_ladder_members(dir, scene, rungs, reference, settings, n_kept);
  }

  std::string write_and_describe_ladder(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                                        const LadderStudy &study, const LadderRunSettings &settings,
                                        const std::size_t n_kept, const std::string &took)
  {
    const std::size_t reference = study.reference;
    write_convergence_csv(dir, study.checks);
    write_ladder_tables(dir, study, reference);

    std::ostringstream md;
    describe_headline(md, study, reference, settings, ladder_size(rungs, settings).diagnostic_members);
    md << "\n" << ladder_convergence_paragraph(study.checks) << "\n";
    describe_end_state(md, study, study.rungs[reference], settings);
    describe_steps(md, study, ladder_heading(settings.numbering, 2, "The ladder: what each step contributes"));
    describe_front(md, dir, study, ladder_heading(settings.numbering, 3, "The speed–accuracy front"));
    md << "\n![The ladder: final positions per rung, and speed against accuracy](ladder.png)\n\n"
       << "Files: ladder.csv, ladder_members.csv, ladder_steps.csv, convergence.csv"
       << (std::any_of(rungs.begin(), rungs.end(), [](const LadderRung &r) { return r.checked_in_dt; }) ? ", front.csv"
                                                                                                        : "")
       << "; member_runs.csv holds every "
          "member as it finished, member_runs.check-1.csv, … the members of the checks' later rounds (the same "
          "command started again into this folder runs only the members not there yet). "
       // n_kept counts every round's members, the convergence checks' too,
       // so it is not a share of the ladder's own n_member_runs.
       << (n_kept ? std::to_string(n_kept) +
                      " members (the ladder's and its convergence checks') were read back from there, computed by "
                      "an earlier, stopped run of this same build and settings. "
                  : std::string())
       << "This run of the ladder took " << took << ".\n\n";
    run_plot_script("plot_ladder.py", {dir, scene.name});
    return md.str();
  }

  std::string run_and_describe_ladder(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                                      const std::size_t reference, const LadderRunSettings &settings, bool *proven)
  {
    const auto start                  = clock::now();
    const SharedMemberCounts before   = shared_member_counts();
    std::size_t n_kept                = 0;
    const LadderStudy study           = run_ladder_study(dir, scene, rungs, reference, settings, n_kept);
    const SharedMemberCounts after    = shared_member_counts();
    if (proven)
      *proven = study.proven();
    std::string md = write_and_describe_ladder(dir, scene, rungs, study, settings, n_kept, seconds_since(start));
    if (after.reused > before.reused)
      md += std::to_string(after.reused - before.reused) + " FE members were taken from " + after.folder +
            ", run before by this build with the same scene and settings (the region's, the published cases' or "
            "an earlier report's), not run again.\n\n";
    return md;
  }

  void work_on_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, const std::size_t reference,
                      const LadderRunSettings &settings)
  {
    const MemberRunsSettings runs = member_files_settings("", "ladder", MpiSession::active(), "");
    const LadderChecks checks     = ladder_checks(scene, rungs, reference);
    run_member_groups(ladder_groups_with_checks(scene, rungs, checks, settings.end_time, settings.members), runs);
    Scene s                  = scene;
    s.time_stepping.end_time = settings.end_time;
    work_on_check_rounds(s, checks.plans, first_trial_counts(checks), settings.members,
                         EnsembleSettings().perturbation, runs);
  }

  LadderScope ladder_scope(const bool full, const bool diagnostics)
  {
    return !full ? LadderScope::quick : diagnostics ? LadderScope::diagnostics : LadderScope::front;
  }

  LadderRunSettings ladder_run_settings(const bool full_length)
  {
    LadderRunSettings settings;
    settings.members  = full_length ? 8 : 4;
    settings.end_time = full_length ? 40. : 25.;
    return settings;
  }

  ReportLadder report_ladder(const Scene &scene, const bool full, const bool diagnostics)
  {
    ReportLadder l;
    l.rungs                    = default_ladder(scene, ladder_scope(full, diagnostics), l.reference);
    l.settings                 = ladder_run_settings(full);
    l.settings.quick_ladder    = !full;
    l.settings.numbering       = "5.";
    l.settings.progress_prefix = "[verify] FE against ROM: ";
    return l;
  }
} // namespace beamslider
