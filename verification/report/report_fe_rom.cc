// Verification section 5, "FE against ROM": the error ladder as ensembles
// (verification/studies/error_ladder.h), the slow manifold of FE and ROM
// (prescribed-position sweeps, verification/studies/pcs_comparison.h) and
// where the explicit ROM scheme fails. Single traces are not compared: the
// rattling slider parts runs that differ in round-off after a few dozen
// periods, so models are judged by the distributions of their outcomes.
//
// Files written into the report folder:
//   ladder.csv          one row per rung (index = place in the ladder): settings, cost, outcome statistics,
//                       W₁ distance of the final position to the reference
//   ladder_members.csv  one row per rung and member (the trace analysis)
//   ladder_steps.csv    each step of the ladder: rung i−1 against rung i
//   ladder.png          final x_C/L of every member per rung; speed against
//                       accuracy (cost against W₁ with its interval)
//   slow_manifold_{fe,rom}/  the two sweeps, comparison.csv, pcs_compare.png
//   explicit_time_step_limit.{csv,png}
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "verification/cli/commands.h"
#include "verification/report/csv_writer.h"
#include "verification/report/report.h"
#include "verification/studies/error_ladder.h"
#include "verification/studies/pcs_comparison.h"
#include "verification/studies/pcs_sweep.h"
#include "verification/studies/console.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>

namespace beamslider
{
  namespace
  {
    using clock = std::chrono::steady_clock;

    std::string seconds_since(const clock::time_point &start)
    {
      return fixed(std::chrono::duration<double>(clock::now() - start).count(), 0) + " s";
    }

    // "0.331 [0.330, 0.332]", or a dash for an outcome no member had.
    std::string median_range(const OutcomeStatistics &s, const int digits)
    {
      if (s.n == 0)
        return "–";
      return fixed(s.median, digits) + " [" + fixed(s.min, digits) + ", " + fixed(s.max, digits) + "]";
    }

    std::string distance(const SampleComparison &c)
    {
      if (c.n_a == 0 || std::isnan(c.wasserstein))
        return "–";
      return fixed(c.wasserstein, 3) + " [" + fixed(c.interval_low, 3) + ", " + fixed(c.interval_high, 3) + "]";
    }

    std::string classes(const std::map<std::string, unsigned int> &counts)
    {
      std::string s;
      for (const auto &[name, n] : counts)
        s += (s.empty() ? "" : ", ") + std::to_string(n) + "× " + name;
      return s.empty() ? "–" : s;
    }

    // Rough wall time of one member [s] on this machine, for the announcement
    // only (measured: ROM N=5 at 2e-5 s 0.05 s per simulated second, FE on
    // 32 elements at 1e-5 s 3.4 s per simulated second).
    double expected_member_seconds(const ModelSetting &s, const Scene &scene, const double end_time)
    {
      return cost_per_simulated_second(s, scene) * end_time * 0.6e-6;
    }

    void write_ladder_rows(CsvWriter &rungs_csv, CsvWriter &members_csv, const LadderRungResult &r,
                           const std::size_t index, const bool is_reference)
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
      rungs_csv.row(cells);

      for (const auto &member : r.members)
        {
          const TraceAnalysis &a = member.analysis;
          members_csv.row({r.rung.name, CsvWriter::cell(member.index), CsvWriter::cell(member.perturbation),
                           to_string(member.result.status), a.valid && a.jumped ? CsvWriter::cell(a.jump_time, 6) : "",
                           a.valid ? CsvWriter::cell(a.final_position, 6) : "",
                           a.valid ? CsvWriter::cell(a.final_amplitude, 6) : "", CsvWriter::cell(member.wall_seconds, 4),
                           a.valid ? to_string(a.outcome) : ""});
        }
    }

    // 5.1 and 5.2: the ladder.
    std::string ladder_subsections(Report &report, const Scene &scene, const bool full)
    {
      const auto start             = clock::now();
      std::size_t reference        = 0;
      const auto rungs             = default_ladder(scene, full, reference);
      const unsigned int n_members = full ? 8 : 4;
      const double end_time        = full ? 40. : 25.;
      double expected              = 0;
      for (const auto &r : rungs)
        expected += expected_member_seconds(r.model, scene, end_time) * n_members / 2; // two cores
      console() << "[verify] FE against ROM: error ladder, " << rungs.size() << " rungs × " << n_members
                << " members over " << end_time << " s, expected about " << fixed(expected / 60, 1) << " min"
                << std::endl;

      CsvWriter rungs_csv(report.dir + "/ladder.csv",
                          {"index", "rung", "family", "n_modes", "n_elements", "integrator", "time_step_s", "damped_modes",
                           "reference", "members", "failed", "wall_s_per_member", "cost_units", "final_x_n",
                           "final_x_median", "final_x_min", "final_x_max", "final_amplitude_n", "final_amplitude_median",
                           "final_amplitude_min", "final_amplitude_max", "jump_n", "jump_time_median_s", "jump_time_min_s",
                           "jump_time_max_s", "w1_to_reference", "w1_low", "w1_high", "spread", "distinguishable"});
      CsvWriter members_csv(report.dir + "/ladder_members.csv",
                            {"rung", "member", "perturbation", "status", "jump_time_s", "final_x_over_L",
                             "final_amplitude_over_h", "wall_s", "outcome"});
      const LadderStudy study = run_ladder(
        scene, rungs, reference, end_time, n_members,
        [&](const LadderRung &rung, std::size_t) {
          console() << "[verify] FE against ROM (" << seconds_since(start) << "): ladder rung " << rung.name << " ("
                    << rung.model.label() << ")" << std::endl;
        },
        [&](const LadderRungResult &r) {
          std::size_t index = 0;
          while (rungs[index].name != r.rung.name)
            ++index;
          write_ladder_rows(rungs_csv, members_csv, r, index, index == reference);
        });

      CsvWriter steps_csv(report.dir + "/ladder_steps.csv",
                          {"from", "to", "median_shift", "w1", "w1_low", "w1_high", "spread", "distinguishable"});
      for (std::size_t i = 1; i < study.rungs.size(); ++i)
        {
          const SampleComparison &c = study.steps[i];
          if (c.n_a == 0)
            continue;
          steps_csv.row({study.rungs[i - 1].rung.name, study.rungs[i].rung.name,
                         CsvWriter::cell(study.rungs[i].final_position.median - study.rungs[i - 1].final_position.median, 6),
                         CsvWriter::cell(c.wasserstein, 6), CsvWriter::cell(c.interval_low, 6),
                         CsvWriter::cell(c.interval_high, 6), CsvWriter::cell(c.spread, 6), c.distinguishable ? "1" : "0"});
        }

      const LadderRungResult &ref = study.rungs[reference];
      std::ostringstream md;
      md << "Every model runs as an ensemble of " << n_members << " members over " << end_time
         << " s; member m starts at x_C/L + m·1e-9, nothing else differs. The outcomes come from the one trace analysis "
            "(doc/verification.md §5): the final x_C/L and amplitude are means over the last seconds, the jump time is "
            "that of the first jump to the upper branch. Two ensembles are compared by the Wasserstein distance W₁ of "
            "their final positions (in x_C/L; the mean distance the members must move to match) with a 90 % bootstrap "
            "interval; the spread is W₁ between the halves of one ensemble, i.e. what its own scatter gives at this size. "
            "A model is distinguishable from another when the interval's lower end exceeds the spread. Reference: **"
         << ref.rung.name << "** (" << ref.rung.model.label() << ")"
         << (full ? "" : "; `verify --full` runs 8 members over 40 s and adds the implicit ROM with 20 modes and with all "
                         "the mesh's bending modes (damping 20, then all), the FE without axial inertia (damping all, "
                         "then 20), the FE damping 20 and the FE at Δt, Δt/2 and Δt/8")
         << ". Cost: the stated model of `fe_rom_study.h` in units of one step of the published ROM (not a clock reading); "
            "wall time is per member on this machine, for information.\n\n"
         << "### 5.1 Headline: every model against the FE reference\n\n"
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

      // The verdict in words: the published ROM, the converged ROM, and the
      // FE reference's own time-step convergence where the ladder has it.
      const LadderRungResult &published = study.rungs.front();
      const LadderRungResult *converged = nullptr, *fe_refined = nullptr;
      for (const auto &r : study.rungs)
        {
          if (r.rung.model.family == "rom" && r.rung.model.integrator == "explicit")
            converged = &r;
          if (r.rung.model.family == "fe" && r.rung.model.time_step < ref.rung.model.time_step)
            fe_refined = &r;
        }
      auto verdict = [&](const LadderRungResult &r) {
        const SampleComparison &d = r.position_to_reference;
        std::ostringstream s;
        s << r.rung.name << " ends at x_C/L = " << fixed(r.final_position.median, 3) << " against the reference's "
          << fixed(ref.final_position.median, 3) << ": W₁ = " << distance(d) << ", spread " << fixed(d.spread, 3) << " — "
          << (d.distinguishable ? "distinguishable" : "indistinguishable at this ensemble size");
        return s.str();
      };
      md << "\n**Verdict on the end state.** " << verdict(published) << ". ";
      if (converged && converged != &published)
        md << verdict(*converged) << ". ";
      if (fe_refined)
        md << "The reference itself: " << verdict(*fe_refined)
           << (fe_refined->position_to_reference.distinguishable
                 ? "; the FE reference is not converged in the time step on the end position, so a ROM's distance to it "
                   "below that of the FE's own refinement is not a model error."
                 : "; the FE reference is converged in the time step as far as this ensemble size can tell.");
      if (!full)
        md << "The reference is the FE at a quarter of the scene's Δt because the FE's end position is not converged at "
              "larger steps (measured on mueller2023, 4 members over 25 s: median 0.458 L at Δt = 2e-5 s, 0.432 L at 1e-5 s, "
              "0.371 L at 5e-6 s and 0.371 L at 2.5e-6 s; doc/verification.md §7); `verify --full` shows that "
              "refinement itself.";
      md << " What all models share is in the last column (the class of each member's adaptation) and the jump-time "
            "column.\n\n";

      md << "### 5.2 The ladder: what each step contributes\n\n"
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
          md << signed_fixed(study.rungs[i].final_position.median - study.rungs[i - 1].final_position.median, 3) << " | " << distance(c) << " | " << fixed(c.spread, 3) << " | "
             << (c.distinguishable ? "yes" : "no") << " |\n";
        }
      // Which step carries the difference: computed from this run, not
      // asserted (the distinguishable steps, largest shift first).
      std::vector<std::size_t> carried;
      for (std::size_t i = 1; i < study.rungs.size(); ++i)
        if (study.steps[i].n_a > 0 && study.steps[i].distinguishable)
          carried.push_back(i);
      auto shift = [&](const std::size_t i) {
        return study.rungs[i].final_position.median - study.rungs[i - 1].final_position.median;
      };
      std::sort(carried.begin(), carried.end(),
                [&](const std::size_t a, const std::size_t b) { return std::abs(shift(a)) > std::abs(shift(b)); });
      if (carried.empty())
        md << "\nNo step of this ladder is distinguishable from its neighbour at this ensemble size.\n";
      else
        {
          md << "\n**Which steps carry the differences** (distinguishable steps, largest shift first): ";
          for (std::size_t k = 0; k < carried.size(); ++k)
            md << (k ? "; " : "") << study.rungs[carried[k] - 1].rung.name << " → " << study.rungs[carried[k]].rung.name
               << " (" << signed_fixed(shift(carried[k]), 3) << " L: "
               << study.rungs[carried[k]].rung.change << ")";
          md << ". Every other step is within the ensembles' own scatter.\n";
        }
      md << "\n![The ladder: final positions per rung, and speed against accuracy](ladder.png)\n\n"
         << "Files: ladder.csv, ladder_members.csv, ladder_steps.csv. The ladder took " << seconds_since(start) << ".\n\n";
      run_plot_script("plot_ladder.py", {report.dir, scene.name});
      return md.str();
    }

    // 5.3: F̄_x(x_C) and the amplitude branches of FE and ROM on the same
    // positions around the end states, with batch-means intervals.
    std::string slow_manifold_subsection(Report &report, const Scene &scene, const bool full)
    {
      const auto start = clock::now();
      PcsStudySettings settings;
      settings.sweep              = PcsSweepSettings::for_scene(scene);
      settings.sweep.low_over_L   = 0.25;
      settings.sweep.high_over_L  = 0.5;
      settings.sweep.step_over_L  = full ? 0.0125 : 0.025;
      settings.sweep.settle_time  = 0.5;
      settings.sweep.average_time = full ? 2.0 : 1.0;
      settings.free_time          = 0;
      settings.verbose            = false;
      settings.sweep.validate(scene);
      console() << "[verify] FE against ROM: slow manifold, sweeps x_C/L " << settings.sweep.low_over_L << " … "
                << settings.sweep.high_over_L << " on the FE and the ROM" << std::endl;

      const std::string fe_dir = report.dir + "/slow_manifold_fe", rom_dir = report.dir + "/slow_manifold_rom";
      std::filesystem::create_directories(fe_dir);
      std::filesystem::create_directories(rom_dir);
      // The FE at a fraction of the scene's (the ROM's) Δt: at Δt itself it
      // does not resolve the contacts once the amplitude is high (measured:
      // its up branch wedges the window, both sides through the beam, right
      // after 0.35 L); Δt/2 follows the Δt/4 branches to 1 % in amplitude
      // (0.556 → 0.861 h against 0.551 → 0.857 h at the jump), Δt/4 is the
      // ladder's converged reference.
      const unsigned int fe_step_divisor = full ? 4 : 2;
      Scene fe_scene                     = scene;
      fe_scene.time_stepping.time_step   = scene.time_stepping.time_step / fe_step_divisor;
      settings.model        = "fe";
      const PcsStudy fe     = run_pcs_sweep(fe_scene, settings, fe_dir);
      settings.model        = "rom";
      const PcsStudy rom    = run_pcs_sweep(scene, settings, rom_dir);
      // A branch that stopped early (its run left the physically possible
      // set, say) holds the first positions of the other's: compare those,
      // and say which branch stopped, where and why.
      std::string stopped;
      auto points = [](const PcsBranch &a, const PcsBranch &b) {
        const std::size_t n = std::min(a.points.size(), b.points.size());
        return std::vector<PcsPoint>(a.points.begin(), a.points.begin() + n);
      };
      auto both = [&](const PcsStudy &s, const PcsStudy &other) {
        std::vector<PcsPoint> p = points(s.up, other.up), down = points(s.down, other.down);
        p.insert(p.end(), down.begin(), down.end());
        return p;
      };
      for (const auto &[name, study] : {std::pair<const char *, const PcsStudy *>{"FE", &fe}, {"ROM", &rom}})
        for (const PcsBranch *b : {&study->up, &study->down})
          if (b->last_run.status != RunStatus::completed)
            stopped += std::string("The ") + name + " sweep's branch '" + to_string(b->direction) + "' stopped after " +
                       std::to_string(b->points.size()) + " positions (" + to_string(b->last_run.status) + ": " +
                       b->last_run.message + "); the comparison below covers the positions both sweeps reached. ";
      const PcsComparison comparison = compare_sweeps(both(rom, fe), both(fe, rom));
      write_pcs_comparison(comparison, rom_dir);
      run_plot_script("plot_pcs_compare.py", {rom_dir, fe_dir, "ROM N=" + std::to_string(scene.discretisation.n_modes), "FE"});

      std::ostringstream md;
      md << "### 5.3 The slow manifold: amplitude branches and F̄_x(x_C), FE against ROM\n\n"
         << "The slider is held at x_C/L = " << settings.sweep.low_over_L << " … " << settings.sweep.high_over_L << " (step "
         << settings.sweep.step_over_L << ", both directions, " << settings.sweep.settle_time << " s settling and "
         << settings.sweep.average_time
         << " s averaging per position) on the FE model at Δt/" << fe_step_divisor
         << " (at the ROM's Δt the FE does not resolve the contacts of the high branch and its sweep leaves the physically "
            "possible set; Δt/2 follows Δt/4 to 1 % in amplitude) and on the scene's ROM at Δt. The amplitude branches are "
            "deterministic; "
            "the period-mean horizontal force F̄_x is small against its rattling noise, so it carries a 95 % batch-means "
            "interval, and its zero crossings (the free slider's equilibria) carry the interval of positions where the "
            "sign is not resolved.\n\n"
         << (stopped.empty() ? "" : stopped + "\n\n") << describe(comparison, "ROM", "FE") << "\n![FE against ROM on the slow manifold](slow_manifold_rom/pcs_compare.png)\n\n"
         << "Files: slow_manifold_fe/pcs.csv, slow_manifold_rom/pcs.csv, slow_manifold_rom/comparison.csv and crossings.csv. "
            "The two sweeps took "
         << seconds_since(start) << ".\n\n";
      return md.str();
    }

    // 5.4: where the explicit midpoint scheme of the ROM fails: Δt < 2/ω_N.
    std::string explicit_limit_subsection(Report &report, const Scene &scene)
    {
      const double dt = scene.time_stepping.time_step;
      std::ostringstream md;
      md << "### 5.4 Where the explicit ROM scheme fails\n\n"
         << "The ROM's smooth forces are integrated by the explicit midpoint rule, stable for Δt < 2/ω_N (ω_N the highest kept "
            "mode). The chart shows that limit against N, the scene's Δt and the seed's rule Δt = 2π/(5ω_N). A run with a "
            "larger step is refused before it starts, with a message; here is what N = 7 at 1.05 × its limit says:\n\n";
      const FEBeam beam(scene);
      const FEModes modes = compute_bending_modes(beam, 10);
      CsvWriter limits(report.dir + "/explicit_time_step_limit.csv",
                       {"n_modes", "omega_N_rad_s", "stable_limit_s", "seed_rule_s"});
      for (unsigned int N = 1; N <= 10; ++N)
        limits.row({CsvWriter::cell(N), CsvWriter::cell(modes.omega[N - 1]), CsvWriter::cell(2. / modes.omega[N - 1]),
                    CsvWriter::cell(2 * M_PI / (5 * modes.omega[N - 1]))});
      ModelSetting too_large;
      too_large.n_modes   = 7;
      too_large.time_step = 1.05 * 2. / modes.omega[6];
      const ModelRun refused = run_setting(scene, too_large, 0.01);
      md << "> " << (refused.ok ? "(ran: the check did not trigger)" : refused.message) << "\n\n";
      unsigned int first_unstable = 0;
      for (unsigned int N = 1; N <= 10 && !first_unstable; ++N)
        if (dt >= 2. / modes.omega[N - 1])
          first_unstable = N;
      md << "At the scene's Δt = " << dt << " s the explicit ROM is stable up to N = "
         << (first_unstable ? std::to_string(first_unstable - 1) : std::string("10 (all tested)"))
         << ". The FE model integrates its smooth forces implicitly and has no such limit; the ROM with the same implicit "
            "rule (`ensemble --integrator implicit`) has none either.\n\n"
         << "![Explicit time-step limit](explicit_time_step_limit.png)\n\n";
      run_plot_script("plot_explicit_limit.py", {report.dir, std::to_string(dt)});
      return md.str();
    }
  } // namespace

  void add_fe_rom_section(Report &report, const Scene &scene, const bool full)
  {
    const auto start = clock::now();
    std::ostringstream md;
    md << "## 5. FE against ROM: ensembles, the error ladder, the slow manifold\n\n"
       << "Scene `" << scene.name << "` as it is (f_ex = " << scene.excitation.frequency_hz << " Hz, â = "
       << scene.excitation.acceleration_amplitude << " m/s², x_C/L = " << scene.initial.slider_position_over_L
       << " at t = 0), the same contact code on every beam model. The rattling slider makes single traces chaotic: runs "
          "that differ in round-off part after a few dozen periods and the jump time moves by seconds, while the end "
          "state is an attractor of the slow dynamics. So models are compared as ensembles (5.1, 5.2) and on the slow "
          "manifold the adaptation follows (5.3), never one trace against another.\n\n";
    md << ladder_subsections(report, scene, full);
    md << slow_manifold_subsection(report, scene, full);
    md << explicit_limit_subsection(report, scene);
    report.text << md.str();
    console() << "[verify] FE against ROM: done in " << seconds_since(start) << std::endl;
  }
} // namespace beamslider
