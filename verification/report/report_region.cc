// The verdict across the signature-move region as Markdown and CSV, see
// report_region.h.
#include "verification/report/report_region.h"

#include "io/csv_writer.h"
#include "verification/report/member_files.h"
#include "verification/report/report.h"
#include "verification/report/report_convergence.h"
#include "io/console.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // One model at one point: its members' statistics and its distance to
    // the point's reference.
    struct Column
    {
      std::string name;
      ModelSetting model;
      OutcomeStatistics position, amplitude;
      SampleComparison to_reference; // n_a = 0 for the reference
      ClassCounts classes;
      bool moved = false; // its check at Δt/2 did not end alike
      double wall_ratio = NAN; // wall time per member over the published ROM's at the same point
    };

    Column column(const std::string &name, const ModelSetting &model, const std::vector<EnsembleMember> &members,
                  const OutcomeSamples *reference)
    {
      Column c{name, model, {}, {}, {}, {}};
      const OutcomeSamples s = outcome_samples(members);
      c.position             = statistics("final x_C/L", s.final_position);
      c.amplitude            = statistics("final amplitude [h]", s.final_amplitude);
      if (reference && !s.final_position.empty() && !reference->final_position.empty())
        c.to_reference = compare_samples(s.final_position, reference->final_position);
      c.classes = class_counts(members);
      return c;
    }

    // The column of an N check's larger basis ("ROM N=30").
    std::string larger_basis_name(const ConvergenceCheck &n_check)
    {
      return "ROM N=" + std::to_string(n_check.trials[1].model.n_modes);
    }

    // The columns of one point: the ROM rungs (each marked if it moved at
    // Δt/2), the N-check's refinement (N = 30), and the reference last.
    std::vector<Column> point_columns(const LadderStudy &l)
    {
      const LadderRungResult &ref        = l.rungs[l.reference];
      const OutcomeSamples ref_samples   = outcome_samples(ref.members);
      std::vector<Column> columns;
      for (std::size_t i = 0; i < l.rungs.size(); ++i)
        if (i != l.reference)
          {
            columns.push_back(column(l.rungs[i].rung.name, l.rungs[i].rung.model, l.rungs[i].members, &ref_samples));
            const ConvergenceCheck *check = l.refinement_check(i);
            columns.back().moved          = check && check->parameter == "Δt" && !check->converged;
            if (l.rungs.front().wall_seconds_per_member > 0)
              columns.back().wall_ratio = l.rungs[i].wall_seconds_per_member / l.rungs.front().wall_seconds_per_member;
          }
      for (const ConvergenceCheck &c : l.checks)
        if (c.parameter == "N" && c.trials.size() > 1)
          columns.push_back(column(larger_basis_name(c), c.trials[1].model,
                                   c.trials[1].members, &ref_samples));
      columns.push_back(column(ref.rung.name, ref.rung.model, ref.members, nullptr));
      return columns;
    }

    std::string end_state(const Column &c)
    {
      if (c.position.n == 0)
        return "–";
      return fixed(c.position.median, 3) + " [" + fixed(c.position.min, 3) + ", " + fixed(c.position.max, 3) + "]";
    }

    std::string w1(const SampleComparison &d)
    {
      if (d.n_a == 0 || std::isnan(d.wasserstein))
        return "–";
      const int digits = d.interval_high < 0.01 ? 4 : 3;
      return fixed(d.wasserstein, digits) + " [" + fixed(d.interval_low, digits) + ", " +
             fixed(d.interval_high, digits) + "]";
    }

    std::string classes(const std::map<std::string, unsigned int> &counts)
    {
      std::string s;
      for (const auto &[name, n] : counts)
        s += (s.empty() ? "" : ", ") + std::to_string(n) + "× " + name;
      return s.empty() ? "–" : s;
    }

    // The reference's own check in Δt (by its rung, not by its place among
    // the checks, where the ROMs' checks in Δt are too).
    const ConvergenceCheck *reference_check(const LadderStudy &l)
    {
      return l.refinement_check(l.reference);
    }

    // One row per site and model (region.csv, published_cases.csv): the
    // site's own columns first (`site_header`, `site_cells(p)`), then the
    // model, its members' end state and classes, its W₁ to the site's
    // reference and whether it is alike there (region_verdict.h); the
    // reference's row says whether it converged in Δt.
    // How the members of a model whose classes split are added to.
    std::string class_rounds_sentence()
    {
      std::ostringstream s;
      s << "A model (or reference) whose members do not decide its outcome class runs " << class_members_step
        << " more members at a time, up to " << class_members_ceiling
        << ": decided means the sign test puts the majority class above a coin's toss with "
        << std::lround(100 * (1 - class_decision_level))
        << " % confidence (4 of 4, 7 of 8, 9 of 12, 12 of 16); its class counts say how many members it ran, and "
           "its end state and W₁ are over all of them (the convergence checks are judged on the first members).";
      return s.str();
    }

    void write_sites_csv(const std::string &path, const std::vector<std::string> &site_header,
                         const std::function<std::vector<std::string>(std::size_t)> &site_cells,
                         const std::vector<LadderStudy> &ladders)
    {
      std::vector<std::string> header = site_header;
      header.insert(header.end(),
                    {"model", "time_step_s", "n_modes", "static_corrections", "members", "final_x_median", "final_x_min",
                     "final_x_max", "final_amplitude_median", "w1", "w1_low", "w1_high", "spread", "distinguishable",
                     "classes", "majority_class", "alike", "moves_at_half_step", "reference_convergence"});
      CsvWriter csv(path, header);
      for (std::size_t p = 0; p < ladders.size(); ++p)
        {
          const ConvergenceCheck *in_t = reference_check(ladders[p]);
          const std::vector<Column> cs = point_columns(ladders[p]);
          for (const Column &c : cs)
            {
              const bool compared = c.to_reference.n_a > 0;
              const auto maybe = [compared](const double x) { return compared ? CsvWriter::cell(x) : std::string(); };
              const auto flag  = [compared](const bool b) { return compared ? std::string(b ? "1" : "0") : std::string(); };
              std::vector<std::string> row = site_cells(p);
              row.insert(row.end(),
                         {c.name, CsvWriter::cell(c.model.time_step), CsvWriter::cell(c.model.n_modes),
                          CsvWriter::cell(c.model.n_static_corrections), CsvWriter::cell(c.position.n),
                          CsvWriter::cell(c.position.median), CsvWriter::cell(c.position.min),
                          CsvWriter::cell(c.position.max), CsvWriter::cell(c.amplitude.median),
                          maybe(c.to_reference.wasserstein), maybe(c.to_reference.interval_low),
                          maybe(c.to_reference.interval_high), maybe(c.to_reference.spread),
                          flag(c.to_reference.distinguishable), classes(c.classes), majority_class(c.classes),
                          flag(alike_with_reference(c.to_reference, c.classes, cs.back().classes)),
                          c.moved ? "1" : "0",
                          !compared && in_t ? (in_t->converged ? "converged" : "not converged") : ""});
              csv.row(row);
            }
        }
      csv.close();
    }

    // The points where more modes do not bring the ROM to the FE: the rung
    // converged in N and its check's larger basis (N = 30) both end apart
    // from the reference. There the basis is not what separates ROM and FE.
    std::string basis_limit(const RegionStudy &study, const std::vector<std::vector<Column>> &columns)
    {
      std::string converged, larger, where;
      for (std::size_t p = 0; p < study.ladders.size(); ++p)
        {
          const LadderStudy &l = study.ladders[p];
          const auto rung      = std::find_if(l.rungs.begin(), l.rungs.end(),
                                              [](const LadderRungResult &r) { return r.rung.converged_in_n; });
          const auto check     = std::find_if(l.checks.begin(), l.checks.end(), [](const ConvergenceCheck &c) {
            return c.parameter == "N" && c.trials.size() > 1;
          });
          if (rung == l.rungs.end() || check == l.checks.end())
            continue;
          const std::string more = larger_basis_name(*check);
          const auto find        = [&](const std::string &name) -> const Column * {
            for (const Column &c : columns[p])
              if (c.name == name && c.to_reference.n_a > 0)
                return &c;
            return nullptr;
          };
          const Column *a = find(rung->rung.name), *b = find(more);
          if (!a || !b || !basis_gap(l))
            continue;
          converged = rung->rung.name;
          larger    = more;
          where += (where.empty() ? "" : "; ") + study.points[p].label() + " (W₁ " +
                   fixed(a->to_reference.wasserstein, 4) + " and " + fixed(b->to_reference.wasserstein, 4) + " L)";
        }
      if (where.empty())
        return "";
      return " At " + where + ", " + converged + ", converged in N, and " + larger +
             ", its check, both end apart from the reference: more modes do not bring the ROM to the FE there, so "
             "what separates them is not the modal basis, and no cheaper basis can be expected to land there.";
    }

    // What the model-form probes found where more modes do not reach the
    // reference (region_verdict.h, model_form_probes).
    std::string model_form_finding(const RegionStudy &study)
    {
      std::ostringstream s;
      for (const auto &[p, l] : study.model_form)
        {
          const LadderRungResult &all = l.rungs[0], &basis = l.rungs[1], &ref = l.rungs[l.reference];
          const bool form_alike   = ends_alike(all.position_to_reference);
          const bool scheme_alike = ends_alike(basis.position_to_reference);
          s << " Which difference separates them at " << study.points[p].label() << ": " << all.rung.name
            << " (Δt = " << all.rung.model.time_step << " s, damping the scene's N modes) ends at "
            << fixed(all.final_position.median, 4) << ", W₁ " << w1(all.position_to_reference) << " to the reference, "
            << (form_alike ? "alike" : "apart") << "; " << basis.rung.name << " at its own step ("
            << basis.rung.model.time_step << " s) ends at " << fixed(basis.final_position.median, 4) << ", W₁ "
            << w1(basis.position_to_reference) << ", " << (scheme_alike ? "alike" : "apart") << ".";
          s << (form_alike ? " The model's form (no axial inertia, the cubic membrane, the contact on the modal sum) "
                             "does not separate ROM and FE there."
                           : " The model's form (no axial inertia, the cubic membrane, the contact on the modal sum) "
                             "separates ROM and FE there: with every mode of the mesh and the FE's step the ROM "
                             "still ends apart.");
          if (scheme_alike)
            s << " The same basis stepped with the reference's θ = " << ref.rung.model.theta
              << " lands on the FE: the scheme's numerical damping of the modes that ring after each impact, "
                 "not the basis, separates the region's ROM from the FE reference there (a property of the "
                 "reference's θ, doc/verification.md §6).";
          else
            s << " Stepped with the reference's θ the larger basis still ends apart: the scheme's damping does "
                 "not close the gap either.";
        }
      return s.str();
    }
  } // namespace

  // The summary the README quotes: each model's W₁ range over the
  // points, where it meets the reference, and the reference's evidence.
  std::string region_summary(const RegionStudy &study)
  {
    std::ostringstream md;
    const std::size_t n_points = study.points.size();
    // Each model's column at each point, with whether it is alike there
    // (region_verdict.h: the same majority class, and end states alike).
    std::map<std::string, std::vector<std::pair<const Column *, bool>>> by_model;
    std::vector<std::vector<Column>> columns;
    for (const LadderStudy &l : study.ladders)
      columns.push_back(point_columns(l));
    std::vector<std::string> order;
    for (const auto &points : columns)
      for (const Column &c : points)
        if (c.to_reference.n_a > 0)
          {
            if (!by_model.count(c.name))
              order.push_back(c.name);
            by_model[c.name].emplace_back(&c, alike_with_reference(c.to_reference, c.classes, points.back().classes));
          }
    unsigned int converged = 0;
    for (const LadderStudy &l : study.ladders)
      {
        const ConvergenceCheck *in_t = reference_check(l);
        converged += in_t && in_t->converged;
      }
    md << "**Across the region** (" << n_points << " points): the FE reference converged in Δt at " << converged
       << " of " << n_points << " points" << (converged < n_points ? " (**not at every point**: see below)" : "")
       << ". W₁ to the reference, smallest and largest over the points, and where the model ends alike (most "
          "of its members in the class most of the reference's take, and its end positions indistinguishable, or "
          "closer than "
       << fixed(convergence_resolution, 3) << " L; members split evenly between classes decide no class):";
    std::string first_everywhere;
    for (const std::string &name : order)
      {
        const auto &cs = by_model[name];
        double lo = INFINITY, hi = 0, ratio_lo = INFINITY, ratio_hi = 0;
        unsigned int alike = 0, moved = 0, other_class = 0;
        for (const auto &[c, is_alike] : cs)
          {
            lo = std::min(lo, c->to_reference.wasserstein);
            hi = std::max(hi, c->to_reference.wasserstein);
            if (std::isfinite(c->wall_ratio))
              ratio_lo = std::min(ratio_lo, c->wall_ratio), ratio_hi = std::max(ratio_hi, c->wall_ratio);
            alike += is_alike;
            other_class += ends_alike(c->to_reference) && !is_alike; // close end states, other or no class
            moved += c->moved;
          }
        md << " " << name << " " << fixed(lo, 4) << "–" << fixed(hi, 4) << " L (alike at " << alike << " of "
           << cs.size()
           << (other_class ? "; ends near but in another or no majority class at " + std::to_string(other_class)
                           : std::string())
           << (moved ? "; moves at Δt/2 at " + std::to_string(moved) : std::string())
           << (ratio_hi > 0 ? "; " + fixed(ratio_lo, 1) + "–" + fixed(ratio_hi, 1) + "× the published ROM's wall time"
                            : std::string())
           << ");";
        if (first_everywhere.empty() && alike == cs.size() && moved == 0 && cs.size() == n_points)
          first_everywhere = name;
      }
    md << (first_everywhere.empty()
             ? " no reduced model tried meets the reference at every point."
             : " the first model in this list that meets the reference at every point is " + first_everywhere + ".")
       << basis_limit(study, columns) << model_form_finding(study) << "\n\n";
    return md.str();
  }

  namespace
  {
    // The published cases' table: a row per case, its checked reference and
    // each model's classes, end state and W₁; then per model the cases where
    // its majority class is the reference's.
    std::string describe_cases(const std::vector<StudySite> &sites, const std::vector<LadderStudy> &ladders)
    {
      std::ostringstream md;
      const std::vector<Column> first = point_columns(ladders.front());
      md << "| case | FE reference: step, end x_C/L, classes |";
      for (std::size_t i = 0; i + 1 < first.size(); ++i)
        md << " " << first[i].name << " |";
      md << "\n|---|---|";
      for (std::size_t i = 0; i + 1 < first.size(); ++i)
        md << "---|";
      md << "\n";
      std::map<std::string, std::vector<std::string>> held, missed;
      for (std::size_t p = 0; p < sites.size(); ++p)
        {
          const std::vector<Column> cs = point_columns(ladders[p]);
          const Column &ref            = cs.back();
          const ConvergenceCheck *in_t = reference_check(ladders[p]);
          md << "| `" << sites[p].label << "` | Δt = " << ref.model.time_step << " s"
             << (in_t && !in_t->converged ? " (**not converged**)" : "") << ": " << end_state(ref) << ", "
             << classes(ref.classes) << " |";
          for (std::size_t i = 0; i + 1 < cs.size(); ++i)
            {
              const bool same_class = majority_class(cs[i].classes) == majority_class(ref.classes);
              (same_class && !cs[i].moved ? held : missed)[cs[i].name].push_back(sites[p].label);
              md << " " << classes(cs[i].classes) << "; " << end_state(cs[i]) << ", W₁ " << w1(cs[i].to_reference)
                 << (cs[i].moved ? " **moves at Δt/2**" : "") << (same_class ? "" : " **other class**") << " |";
            }
          md << "\n";
        }
      md << "\nA model takes a case's class when most of its members end in the class most of the reference's "
            "members end in, and it does not move at Δt/2.";
      for (std::size_t i = 0; i + 1 < first.size(); ++i)
        {
          const std::string &name = first[i].name;
          md << " " << name << ": " << held[name].size() << " of " << sites.size();
          if (!missed[name].empty())
            {
              md << " (not ";
              for (std::size_t k = 0; k < missed[name].size(); ++k)
                md << (k ? ", " : "") << "`" << missed[name][k] << "`";
              md << ")";
            }
          md << ".";
        }
      md << "\n\n";
      return md.str();
    }

  } // namespace

  std::string run_and_describe_region(const std::string &dir, const Scene &scene, const RegionRunSettings &settings)
  {
    const auto start                          = std::chrono::steady_clock::now();
    const std::vector<OperatingPoint> points = signature_move_region(scene);
    console() << settings.progress_prefix << "the verdict across the signature-move region: " << points.size()
              << " operating points × (the quick ladder's models and their checks) × " << settings.members << " members over "
              << settings.end_time << " s" << std::endl;
    MemberRunsSettings runs =
      member_files_settings(dir, "region", MpiSession::active(), settings.progress_prefix, "member_runs.region.csv");
    if (!settings.shared_members_root.empty())
      share_fe_members(runs, settings.shared_members_root); // the FE references the cases and the ladder may run too
    const RegionStudy study = run_region(scene, points, settings.end_time, settings.members, member_runs_runner(runs),
                                         check_rounds_runner(runs), round_sharer(runs.mpi));
    write_sites_csv(dir + "/region.csv", {"frequency_hz", "acceleration_m_s2"},
                    [&points](const std::size_t p) {
                      return std::vector<std::string>{CsvWriter::cell(points[p].frequency_hz),
                                                      CsvWriter::cell(points[p].acceleration_m_s2)};
                    },
                    study.ladders);
    std::vector<LadderStudy> probes;
    std::vector<std::size_t> probe_points;
    for (const auto &[p, l] : study.model_form)
      {
        probe_points.push_back(p);
        probes.push_back(l);
      }
    if (!probes.empty())
      write_sites_csv(dir + "/region_model_form.csv", {"frequency_hz", "acceleration_m_s2"},
                      [&](const std::size_t j) {
                        const OperatingPoint &point = points[probe_points[j]];
                        return std::vector<std::string>{CsvWriter::cell(point.frequency_hz),
                                                        CsvWriter::cell(point.acceleration_m_s2)};
                      },
                      probes);
    std::vector<ConvergenceCheck> all_checks;
    for (const LadderStudy &l : study.ladders)
      all_checks.insert(all_checks.end(), l.checks.begin(), l.checks.end());
    write_convergence_csv(dir, all_checks, "region_convergence.csv");

    std::ostringstream md;
    md << "Is the verdict of one operating point the verdict of the region? At " << points.size()
       << " operating points spread over the signature-move region of the operating-range map (section 6), the "
          "same models run as ensembles of "
       << settings.members << " members over " << settings.end_time
       << " s from the scene's start, each against the FE reference of its own point. Every reference proves "
          "itself: the same members at half its step run beside it, and the step is halved further (at most "
       << reference_max_halvings
       << " times) until two steps end alike; the ROM with N = 20 is checked against N = 30 the same way, and "
          "its members are the N = 30 column; every other ROM runs at half its step too, once, and a cell says "
          "where that moved it. "
       << class_rounds_sentence() << "\n\n"
       << region_summary(study);
    // The header from the first point's columns: every point has the same models.
    const std::vector<Column> first = point_columns(study.ladders.front());
    md << "| point | FE reference: step, end x_C/L median [min, max] | its half step: end x_C/L, W₁ [90 %] / spread |";
    for (std::size_t i = 0; i + 1 < first.size(); ++i)
      md << " " << first[i].name << " |";
    md << " classes (reference) |\n|---|---|---|";
    for (std::size_t i = 0; i < first.size(); ++i)
      md << "---|";
    md << "\n";
    for (std::size_t p = 0; p < points.size(); ++p)
      {
        const LadderStudy &l          = study.ladders[p];
        const std::vector<Column> cs  = point_columns(l);
        const Column &ref             = cs.back();
        const ConvergenceCheck *in_t  = reference_check(l);
        md << "| " << points[p].label() << " | Δt = " << ref.model.time_step << " s: " << end_state(ref) << " | ";
        if (in_t && in_t->trials.size() > 1)
          {
            const std::size_t k = in_t->converged ? in_t->accepted : in_t->trials.size() - 2;
            const ConvergenceTrial &half = in_t->trials[k + 1];
            md << fixed(half.final_position.median, 3) << ", " << w1(in_t->trials[k].position_to_next) << " / "
               << fixed(in_t->trials[k].position_to_next.spread, 4)
               << (in_t->converged ? "" : " **not converged**");
          }
        else
          md << "–";
        md << " |";
        for (std::size_t i = 0; i + 1 < cs.size(); ++i)
          md << " " << classes(cs[i].classes) << "; " << end_state(cs[i]) << ", W₁ " << w1(cs[i].to_reference)
             << (cs[i].moved ? " **moves at Δt/2**" : "")
             << (majority_class(cs[i].classes) != majority_class(ref.classes) ? " **other class**" : "") << " |";
        for (std::size_t i = cs.size(); i < first.size(); ++i)
          md << " – |"; // a model this point's ladder lacks
        md << " " << classes(ref.classes) << " |\n";
      }
    md << "\nEach ROM cell: its members' outcome classes; end x_C/L median [min, max], W₁ of its final positions to "
          "the point's reference [90 % interval]; **other class** where its majority class is not the reference's. "
          "The checks' evidence (every trial, its end state and W₁ to the next):\n\n"
       << describe_convergence(all_checks)
       << "\nFiles: region.csv, region_convergence.csv"
       << (probes.empty() ? "" : ", region_model_form.csv (the model-form probes, the point's reference last)")
       << "; member_runs.region.csv (and .check-1.csv, …) hold every "
          "member as it finished. This study took "
       << seconds_since(start) << ".\n\n";
    return md.str();
  }

  std::string run_and_describe_cases(const std::string &dir, const std::vector<StudySite> &sites,
                                     const RegionRunSettings &settings)
  {
    const auto start = std::chrono::steady_clock::now();
    console() << settings.progress_prefix << "the published cases: " << sites.size()
              << " cases × (the published ROM, the front's candidates and the FE reference, with their checks) × "
              << settings.members << " members over each case's end time" << std::endl;
    MemberRunsSettings runs =
      member_files_settings(dir, "cases", MpiSession::active(), settings.progress_prefix, "member_runs.cases.csv");
    if (!settings.shared_members_root.empty())
      share_fe_members(runs, settings.shared_members_root);
    const std::vector<LadderStudy> ladders = run_sites(sites, case_rungs, settings.members, member_runs_runner(runs),
                                                       check_rounds_runner(runs), round_sharer(runs.mpi));
    write_sites_csv(dir + "/published_cases.csv", {"case"},
                    [&sites](const std::size_t p) { return std::vector<std::string>{sites[p].label}; }, ladders);
    std::vector<ConvergenceCheck> all_checks;
    for (const LadderStudy &l : ladders)
      all_checks.insert(all_checks.end(), l.checks.begin(), l.checks.end());
    write_convergence_csv(dir, all_checks, "published_cases_convergence.csv");

    std::ostringstream md;
    md << "Does a model that lands on the signature move also take the outcome class the FE takes on the other "
          "published cases (section 4)? Each case runs as `ensemble --case` runs it, "
       << settings.members
       << " members over the case's end time, with the published ROM, the front's candidates of the quick ladder "
          "(each also at half its step) and the FE reference, which proves itself as in 5.0. "
       << class_rounds_sentence() << "\n\n"
       << describe_cases(sites, ladders) << "The checks' evidence:\n\n"
       << describe_convergence(all_checks)
       << "\nFiles: published_cases.csv, published_cases_convergence.csv, member_runs.cases.csv (and its "
          ".check-k.csv). This study took "
       << seconds_since(start) << ".\n\n";
    return md.str();
  }

  void work_on_case_members(const std::vector<StudySite> &sites, const RegionRunSettings &settings)
  {
    const MemberRunsSettings runs = member_files_settings("", "cases", MpiSession::active(), "");
    work_on_sites(
      sites, case_rungs, settings.members,
      [&runs](const std::vector<MemberGroup> &groups) { run_member_groups(groups, runs); }, round_sharer(runs.mpi));
  }

  void work_on_region_members(const Scene &scene, const RegionRunSettings &settings)
  {
    const MemberRunsSettings runs = member_files_settings("", "region", MpiSession::active(), "");
    work_on_region(
      scene, signature_move_region(scene), settings.end_time, settings.members,
      [&runs](const std::vector<MemberGroup> &groups) { run_member_groups(groups, runs); }, round_sharer(runs.mpi));
  }
} // namespace beamslider
