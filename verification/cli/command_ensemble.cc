// `beamslider ensemble [SCENE] --model rom|fe [--case NAME] [--members K]
// [--perturbation EPS] [--end-time S] [--against DIR]`: K runs that differ
// only by the start x_C/L + m·EPS (verification/studies/ensemble.h), in
// threads, or under `mpirun -n P` on P ranks (verification/studies/member_runs.h).
//
// Writes into the output folder:
//   member_runs.csv    every finished member, appended as it finishes (all
//                      of the run, bit for bit): a stopped ensemble started
//                      again the same way into the same folder runs only
//                      the members not there yet (member_runs.h)
//   members.csv        member,perturbation,status,jump_time_s,turn_x_over_L,
//                      final_x_over_L,final_amplitude_over_h,wall_s,outcome
//                      (an empty field where the event did not happen)
//   member_periods.csv member,t_s,x_over_L,amplitude_over_h: every member's
//                      period records, for the fan chart
//   statistics.csv     outcome,n,median,q1,q3,min,max
//   comparison.csv     with --against DIR: each outcome of this ensemble
//                      against DIR's members.csv (compare_samples)
//   ensemble.png       fan chart: every member's x_C/L and amplitude envelope
//   summary.md         settings, outcome definitions, statistics, classes
#include "io/csv_writer.h"
#include "io/input_file.h"
#include "io/interruption.h"
#include "io/output_file.h"
#include "fem/solid_reduced_model.h"
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/ladder_cache.h"
#include "verification/cli/study_results.h"
#include "numerics/elapsed.h"
#include "verification/report/member_files.h"
#include "verification/studies/member_runs.h"
#include "verification/report/report_convergence.h"
#include "io/console.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/simulation_cases.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

namespace beamslider
{
  namespace
  {
    std::string cell_or_empty(const bool happened, const double value)
    {
      return happened ? CsvWriter::cell(value) : std::string();
    }

    std::string fixed(const double x, const int digits)
    {
      std::ostringstream s;
      s << std::fixed << std::setprecision(digits) << x;
      return s.str();
    }

    // Outcome samples from another ensemble's members.csv (columns as
    // written below; empty cells are events that did not happen). Read and
    // checked before any member runs: a bad file is an input error at once.
    OutcomeSamples read_members_csv(const std::string &path)
    {
      const std::string text = read_option_file(path, "--against: no readable members.csv");
      std::istringstream in(text);
      std::string line;
      std::getline(in, line);
      if (line.rfind("member,perturbation,status,jump_time_s,turn_x_over_L,final_x_over_L,final_amplitude_over_h", 0) != 0)
        throw InputError("--against: '" + path + "' is not an ensemble's members.csv");
      // Every row as wide as the header, and the file ends its last line: a
      // file cut short (a full disk, a killed writer) is refused, not read
      // as fewer members or a number cut to fewer digits.
      const auto cells_of = [](const std::string &l) {
        std::vector<std::string> cells;
        std::stringstream row(l);
        std::string cell;
        while (std::getline(row, cell, ','))
          cells.push_back(cell);
        if (!l.empty() && l.back() == ',')
          cells.emplace_back();
        return cells;
      };
      const std::size_t width = cells_of(line).size();
      if (text.back() != '\n')
        throw InputError("--against: '" + path + "' does not end with a whole line (a file cut short?)");
      OutcomeSamples s;
      std::size_t line_number = 1;
      while (std::getline(in, line))
        {
          ++line_number;
          const std::vector<std::string> cells = cells_of(line);
          if (cells.size() != width)
            throw InputError("--against: '" + path + "' line " + std::to_string(line_number) + " has " +
                             std::to_string(cells.size()) + " cells, its header " + std::to_string(width));
          const auto number = [&](const std::size_t column, std::vector<double> &into) {
            if (cells[column].empty())
              return;
            double x         = 0;
            std::size_t used = 0;
            try
              {
                x = std::stod(cells[column], &used);
              }
            catch (const std::exception &)
              {
                used = 0;
              }
            if (used != cells[column].size() || !std::isfinite(x))
              throw InputError("--against: '" + path + "' line " + std::to_string(line_number) + ", column " +
                               std::to_string(column + 1) + ": not a finite number");
            into.push_back(x);
          };
          number(3, s.jump_time);
          number(4, s.turn_position);
          number(5, s.final_position);
          number(6, s.final_amplitude);
        }
      return s;
    }

    // The model and its settings from the scene and the options, checked
    // before any member runs.
    EnsembleSettings ensemble_settings(const Scene &scene, const EnsembleOptions &options, const unsigned int n_ranks,
                                       std::string &why)
    {
      EnsembleSettings settings;
      settings.n_members    = options.members;
      settings.perturbation = options.perturbation;
      if (options.model == "auto")
        {
          if (options.integrator != "explicit" || options.theta || !options.coefficients.empty())
            throw InputError("--model auto picks the model, its integrator and coefficients from the scene's error "
                             "ladder: --integrator, --theta and --coefficients do not apply");
          settings.model = choose_model(scene, options.tolerance, choice_cache_dir(scene), why, n_ranks);
          return settings;
        }
      if (options.tolerance)
        throw InputError("--tolerance applies to --model auto only");
      settings.model = scene_model(scene, options.model);
      if (options.integrator != "explicit" && options.model != "rom")
        throw InputError("--integrator " + options.integrator + " applies to --model rom only (the FE is implicit)");
      settings.model.integrator = options.integrator;
      if (options.theta)
        {
          if (options.integrator != "implicit")
            throw InputError("--theta applies to --integrator implicit only (the explicit ROM is the midpoint rule; "
                             "the FE takes the scene's 'Time stepping/FE theta')");
          settings.model.theta = *options.theta;
        }
      if (!options.coefficients.empty())
        {
          if (options.model != "rom")
            throw InputError("--coefficients " + options.coefficients + " applies to --model rom only");
          const bool solid = scene.solid.enabled();
          const std::vector<std::string> allowed =
            solid ? solid_rom_coefficient_methods() : std::vector<std::string>{"analytic", "step-condensed", "ice"};
          if (std::find(allowed.begin(), allowed.end(), options.coefficients) == allowed.end())
            throw InputError("--coefficients " + options.coefficients + " is not one of " +
                             (solid ? solid_rom_coefficient_method_list() + " (a solid scene's ROM)"
                                    : "analytic, step-condensed, ice (a beam scene's ROM)"));
          settings.model.coefficients = options.coefficients;
        }
      return settings;
    }

    // members.csv and member_periods.csv.
    void write_member_tables(const std::string &dir, const std::vector<EnsembleMember> &members)
    {
      CsvWriter rows(dir + "/members.csv", {"member", "perturbation", "status", "jump_time_s", "turn_x_over_L",
                                            "final_x_over_L", "final_amplitude_over_h", "wall_s", "outcome"});
      for (const auto &m : members)
        {
          const TraceAnalysis &a = m.analysis;
          rows.row({CsvWriter::cell(m.index), CsvWriter::cell(m.perturbation, 6), to_string(m.result.status),
                    cell_or_empty(a.jumped, a.jump_time), cell_or_empty(a.turned, a.turn_position),
                    cell_or_empty(a.valid, a.final_position), cell_or_empty(a.valid, a.final_amplitude),
                    CsvWriter::cell(m.wall_seconds, 4), to_string(a.outcome)});
        }
      rows.close();
      CsvWriter periods(dir + "/member_periods.csv", {"member", "t_s", "x_over_L", "amplitude_over_h"});
      for (const auto &m : members)
        for (const auto &p : m.periods)
          periods.row({CsvWriter::cell(m.index), CsvWriter::cell(p.t_end, 8), CsvWriter::cell(p.slider_x_over_L, 8),
                       CsvWriter::cell(p.amplitude_over_h, 8)});
      periods.close();
    }

    // Rank 0's part of the ensemble's rounds (convergence_check.h): the
    // first (the model, and its refinement when checked) into
    // member_runs.csv, later ones into member_runs.check-r.csv.
    ConvergenceCheck run_plan(const Scene &scene, const RefinementPlan &plan, const EnsembleSettings &settings,
                              const MemberRunsSettings &runs)
    {
      const MemberGroupRunner later = check_rounds_runner(runs);
      bool first                    = true;
      const MemberGroupRunner runner = [&](const std::vector<MemberGroup> &g) {
        if (!std::exchange(first, false))
          return later(g);
        return run_member_groups(g, runs);
      };
      return run_convergence_checks(scene, {plan}, {}, settings.n_members, settings.perturbation, runner,
                                    round_sharer(runs.mpi))
        .front();
    }

    // The evidence of the FE's check in summary.md.
    std::string convergence_section(const ConvergenceCheck &check)
    {
      std::ostringstream md;
      md << "\n## Convergence in Δt\n\nThe same members at the FE's Δt, refined (Δt/2, …, at most "
         << reference_max_halvings
         << " halvings) and at 2Δt (the witness); a step is accepted when its half ends within the ensembles' own "
            "spread (W₁ of the final positions, 90 % interval against the spread) or closer than "
         << convergence_resolution
         << " L, and when the drift of the median end state over the step, its coarser and its finer neighbour "
            "shows an observed order of at least "
         << minimum_extrapolation_order
         << " and a remaining error, extrapolated by Richardson, within the larger of the spread and that "
            "resolution. The statistics above are those of "
         << (check.converged ? "the accepted step" : "the finest step tried, NOT CONVERGED") << " (convergence.csv).\n\n"
         << describe_convergence({check});
      return md.str();
    }

    using NamedSamples = std::vector<std::pair<std::string, const std::vector<double> *>>;

    // statistics.csv, and its table in Markdown.
    std::string statistics_table(const std::string &dir, const NamedSamples &outcomes)
    {
      std::ostringstream md;
      md << "| outcome | members with it | median | quartiles | min … max |\n|---|---|---|---|---|\n";
      CsvWriter csv(dir + "/statistics.csv", {"outcome", "n", "median", "q1", "q3", "min", "max"});
      for (const auto &[name, sample] : outcomes)
        {
          const OutcomeStatistics s = statistics(name, *sample);
          // No member had the event: empty cells, as in members.csv, not NaN.
          const bool any = s.n > 0;
          csv.row({name, std::to_string(s.n), cell_or_empty(any, s.median), cell_or_empty(any, s.q1),
                   cell_or_empty(any, s.q3), cell_or_empty(any, s.min), cell_or_empty(any, s.max)});
          if (any)
            md << "| " << name << " | " << s.n << " | " << fixed(s.median, 4) << " | " << fixed(s.q1, 4) << " … "
               << fixed(s.q3, 4) << " | " << fixed(s.min, 4) << " … " << fixed(s.max, 4) << " |\n";
          else
            md << "| " << name << " | 0 | – | – | – |\n";
        }
      csv.close();
      return md.str();
    }

    // comparison.csv against another ensemble, and its section in Markdown.
    std::string comparison_section(const std::string &dir, const NamedSamples &outcomes, const OutcomeSamples &other,
                                   const std::string &against)
    {
      const std::vector<const std::vector<double> *> theirs = {&other.jump_time, &other.turn_position,
                                                               &other.final_position, &other.final_amplitude};
      CsvWriter csv(dir + "/comparison.csv", {"outcome", "n_this", "n_other", "median_shift", "wasserstein",
                                              "wasserstein_low", "wasserstein_high", "ks", "own_spread",
                                              "distinguishable"});
      std::ostringstream md;
      md << "\n## Against `" << against
         << "`\n\nWasserstein-1 distance W between the outcome distributions (the mean distance the members must "
            "move), a 90 % bootstrap interval, Kolmogorov–Smirnov D, and the larger W between the halves of either "
            "ensemble (their own scatter at this size). Distinguishable when the interval's lower end exceeds that "
            "scatter.\n\n| outcome | median shift (other − this) | W [90 % interval] | KS D | own scatter | verdict |\n"
            "|---|---|---|---|---|---|\n";
      for (std::size_t i = 0; i < outcomes.size(); ++i)
        {
          const SampleComparison c = compare_samples(*outcomes[i].second, *theirs[i]);
          csv.row({outcomes[i].first, std::to_string(c.n_a), std::to_string(c.n_b), CsvWriter::cell(c.shift),
                   CsvWriter::cell(c.wasserstein), CsvWriter::cell(c.interval_low), CsvWriter::cell(c.interval_high),
                   CsvWriter::cell(c.ks), CsvWriter::cell(c.spread), c.distinguishable ? "1" : "0"});
          md << "| " << outcomes[i].first << " | " << fixed(c.shift, 4) << " | " << fixed(c.wasserstein, 4) << " ["
             << fixed(c.interval_low, 4) << ", " << fixed(c.interval_high, 4) << "] | " << fixed(c.ks, 2) << " | "
             << fixed(c.spread, 4) << " | "
             << (c.n_a == 0 || c.n_b == 0 ? "no sample"
                 : c.distinguishable     ? "distinguishable"
                                         : "indistinguishable at this ensemble size")
             << " |\n";
        }
      csv.close();
      return md.str();
    }

    // The scene (and case) with --end-time, checked before any member runs.
    Scene ensemble_scene(const CommonOptions &common, const EnsembleOptions &options)
    {
      if (options.model != "rom" && options.model != "fe" && options.model != "auto")
        throw InputError("--model '" + options.model + "' is not one of rom, fe, auto");
      Scene scene = read_command_scene(common, options.case_name);
      if (options.end_time)
        {
          scene.time_stepping.end_time = *options.end_time;
          validate_scene(scene);
        }
      // member_periods.csv holds a row per member and excitation period: as
      // simulate's trace.csv, at most max_trace_rows (about 1 GB).
      const double periods = scene.time_stepping.end_time * scene.excitation.frequency_hz;
      if (options.members * periods > SimulateOptions::max_trace_rows)
        throw InputError("--end-time " + std::to_string(scene.time_stepping.end_time) + " s with " +
                         std::to_string(options.members) + " members would write " +
                         std::to_string(static_cast<long long>(options.members * periods)) +
                         " rows to member_periods.csv (one per member and excitation period), more than " +
                         std::to_string(static_cast<long>(SimulateOptions::max_trace_rows)) +
                         " (about 1 GB): the end time is at most " +
                         std::to_string(SimulateOptions::max_trace_rows / (options.members * scene.excitation.frequency_hz)) +
                         " s for this ensemble");
      const double x_last = scene.initial.slider_position_over_L + (options.members - 1) * options.perturbation;
      if (!(x_last <= 1.))
        throw InputError("--perturbation " + std::to_string(options.perturbation) +
                         " moves the last member's start beyond the beam");
      return scene;
    }

    void announce_ensemble(const EnsembleRun &e, const EnsembleOptions &options, const bool checked)
    {
      console() << "ensemble " << e.scene.name << (options.case_name.empty() ? "" : " --case " + options.case_name)
                << ": " << e.settings.n_members << " members of " << e.settings.model.label() << ", "
                << e.scene.time_stepping.end_time << " s each, start x_C/L + m x " << e.settings.perturbation
                << (e.dir.empty() ? std::string(", in memory") : ", into " + e.dir) << std::endl;
      if (checked)
        console() << "  checked in Δt: the same members at Δt/2 beside them, halved further (at most "
                  << reference_max_halvings << " times) until two steps end alike" << std::endl;
    }

    // Runs the members (and, when checked, the refinements) on rank 0's
    // share; false when a signal stopped them.
    bool run_members(EnsembleRun &e, const RefinementPlan &plan, const MemberRunsSettings &runs, const bool checked)
    {
      const auto start = std::chrono::steady_clock::now();
      try
        {
          const ConvergenceCheck result = run_plan(e.scene, plan, e.settings, runs);
          e.members        = result.reference().members;
          e.settings.model = result.reference().model;
          if (checked)
            e.check = result;
        }
      catch (const MemberRunsStopped &stopped)
        {
          std::cerr << "ensemble: " << stopped.what() << std::endl;
          return false;
        }
      e.wall_seconds = elapsed_seconds(start);
      return true;
    }

    // summary.md's head: the model, members, cost and how the outcomes are defined.
    std::string ensemble_description(const EnsembleRun &e, const EnsembleOptions &options, const unsigned int n_ranks)
    {
      const Scene &scene = e.scene;
      std::ostringstream md;
      md << "# Ensemble: scene `" << scene.name << "`" << (options.case_name.empty() ? "" : ", case `" + options.case_name + "`")
         << "\n\n- Model: " << e.settings.model.label() << "; " << e.settings.n_members << " members, member m starts at x_C/L = "
         << scene.initial.slider_position_over_L << " + m × " << e.settings.perturbation << "; " << scene.time_stepping.end_time
         << " s simulated each.\n- Wall time of this run: " << fixed(e.wall_seconds, 1) << " s on "
         << (n_ranks > 1 ? std::to_string(n_ranks) + " MPI ranks" : std::string("the cores of one process"))
         << "; " << e.n_kept << " of the members read back from member_runs.csv (an earlier, stopped run of this "
            "build and settings), the others computed now.\n"
         << "- Outcomes by the one trace analysis (runs/trace_analysis.h): a jump is a rise of the 0.1 s amplitude "
            "envelope, after the 2 s build-up, to more than twice its lowest value over the second before, by a fifth of "
            "the run's largest envelope, lasting 1 s and reaching the scene's upper branch ("
         << fixed(trace_thresholds(scene).high_level_over_h, 2)
         << " h, where Eq. 4 lies 5 % above f1); the turn is the period-mean position farthest from the centre when the "
            "end lies 0.02 L back from it; the final state is the mean over the last 1 s.\n\n";
      if (!e.model_choice.empty())
        md << "The model by `--model auto`:\n\n```\n" << e.model_choice << "```\n\n";
      return md.str();
    }

    // summary.md, with statistics.csv, convergence.csv (checked) and
    // comparison.csv (--against) beside it.
    std::string ensemble_summary(const EnsembleRun &e, const EnsembleOptions &options, const unsigned int n_ranks,
                                 const std::optional<OutcomeSamples> &other)
    {
      const OutcomeSamples samples = outcome_samples(e.members);
      const NamedSamples outcomes = {
        {"jump_time_s", &samples.jump_time},
        {"turn_x_over_L", &samples.turn_position},
        {"final_x_over_L", &samples.final_position},
        {"final_amplitude_over_h", &samples.final_amplitude}};
      std::ostringstream md;
      md << ensemble_description(e, options, n_ranks) << statistics_table(e.dir, outcomes);
      std::map<std::string, unsigned int> classes;
      for (const auto &m : e.members)
        ++classes[to_string(m.analysis.outcome)];
      if (e.check)
        {
          md << convergence_section(*e.check);
          write_convergence_csv(e.dir, {*e.check});
        }
      else if (e.settings.model.family == "fe")
        md << "\n**Unchecked** (`--unchecked`): whether the FE has converged in Δt at this step was not tested.\n";
      md << "\nOutcome classes:";
      for (const auto &[name, count] : classes)
        md << " " << name << " × " << count << ";";
      md << "\n";

      if (other)
        md << comparison_section(e.dir, outcomes, *other, options.against);
      return md.str();
    }
  } // namespace

  int run_ensemble_command(const CommonOptions &common, const EnsembleOptions &options, StudyHandover *handover)
  {
    // Under mpirun every rank runs this; only rank 0 writes and prints.
    MpiSession mpi(launched_by_mpi_launcher());
    EnsembleRun e;
    e.scene     = ensemble_scene(common, options);
    e.settings  = ensemble_settings(e.scene, options, mpi.size(), e.model_choice);
    if (!e.model_choice.empty() && mpi.rank() == 0)
      console() << e.model_choice << std::endl;
    // Another ensemble to compare with, read before any member runs.
    std::optional<OutcomeSamples> other;
    if (!options.against.empty())
      other = read_members_csv(options.against + "/members.csv");
    // The FE proves itself: the same ensemble at Δt/2 beside it, then
    // halved until two steps agree (convergence_check.h). Unchecked, the
    // same code runs the model alone (a plan without refinements), so that
    // every rank takes part in the same rounds either way.
    const bool checked = e.settings.model.family == "fe" && !options.unchecked;
    const std::vector<RefinementPlan> plans = {checked ? step_sequence("the FE in Δt", e.settings.model,
                                                                       reference_max_halvings)
                                                       : step_refinements("ensemble", e.settings.model, 0)};
    if (mpi.rank() != 0)
      {
        // Computes what rank 0 hands out: the ensemble and the check's rounds.
        work_on_check_rounds(e.scene, plans, {0}, e.settings.n_members, e.settings.perturbation,
                             member_files_settings("", "ensemble", &mpi, ""));
        return 0;
      }
    const WorkerRelease release(mpi); // the other ranks stop with this one, however it ends

    const auto prepare_dir = [&] {
      return prepare_output_dir(common, e.scene,
                                options.case_name.empty() ? "ensemble" : "ensemble/" + options.case_name);
    };
    if (handover && handover->mode == StudyHandover::Mode::write)
      {
        // The ensemble computed before, from the same options (python/study_bindings.cc).
        const EnsembleRun &kept = std::any_cast<const EnsembleRun &>(handover->result);
        require_same_scene(kept.scene, e.scene, "ensemble");
        e     = kept;
        e.dir = prepare_dir();
      }
    else
      {
        // Computed for a handover: in memory only, nothing persisted.
        e.dir = handover ? std::string() : prepare_dir();
        MemberRunsSettings runs = member_files_settings(e.dir, "ensemble", &mpi, "  ");
        runs.n_kept             = &e.n_kept;
        const auto rounds       = count_check_rounds(runs);
        announce_ensemble(e, options, checked);
        if (!run_members(e, plans.front(), runs, checked))
          return interruption_exit_code();
        if (mpi.rank() == 0)
          remove_unreached_check_files(e.dir, "member_runs.csv", *rounds);
        if (handover)
          {
            e.against        = other;
            handover->result = e;
            return 0;
          }
      }

    write_member_tables(e.dir, e.members);
    const std::string md = ensemble_summary(e, options, mpi.size(), other);
    write_text_file(e.dir + "/summary.md", md);
    run_plot_script("plot_ensemble.py", {e.dir, e.scene.name + (options.case_name.empty() ? "" : " / " + options.case_name) +
                                                  " (" + e.settings.model.label() + ")"});
    console() << md;
    if (e.check && !e.check->converged)
      {
        std::cerr << "ensemble: " << e.check->verdict() << " (" << e.dir << "/summary.md)" << std::endl;
        return not_converged_exit_code;
      }
    return 0;
  }
} // namespace beamslider
