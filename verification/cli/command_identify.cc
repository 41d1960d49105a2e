// `beamslider identify [SCENE] --axis "Section/Name=A:B:STEP"... [--fact ID]...
// [--members K]`: the identification of System 1's unknown parameters
// (verification/studies/system1_facts.h). For each of the seed's facts, one
// map (the `map` command's cells, operating_map.h) over the unknowns' axes
// with the fact's scenario; each candidate (a cell of the unknowns' grid) is
// scored by every fact's criterion and the scores are summed.
//
// Writes into the output folder:
//   facts.csv             id, name, scenario (overrides), end time, seed text
//   <fact id>/map.csv     the fact's map, in the map command's format
//   identification.csv    one row per candidate: the unknowns' values, each
//                         fact's score (mean over the members) and members
//                         passing, the total
//   verdicts.csv          one row per candidate and fact: score, pass, reason
//   summary.md            the search, the best candidate and its verdicts
// After Ctrl-C, a fact whose map did not reach a candidate has empty score
// and pass cells there ("not run (interrupted)"), that candidate no total,
// and summary.md names the leading candidate so far.
//
// Not restartable (unlike `map`): a search of this size runs in minutes.
#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/output_file.h"
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "verification/report/map_files.h"
#include "numerics/elapsed.h"
#include "io/console.h"
#include "verification/studies/operating_map.h"
#include "verification/studies/system1_facts.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string joined(const std::vector<std::string> &parts, const std::string &separator)
    {
      std::string s;
      for (const std::string &p : parts)
        s += (s.empty() ? "" : separator) + p;
      return s;
    }

    // The search, shared by the stages that run and report it: the
    // unknowns' grid, the facts, the members per run, and the runs' result.
    struct Identification
    {
      MapGrid unknowns;
      std::vector<const System1Fact *> facts;
      unsigned int members = 1;
      IdentificationResult result;
      bool complete = true; // false after Ctrl-C: some facts not run
    };

    MapGrid unknowns_grid(const IdentifyOptions &options)
    {
      MapGrid unknowns;
      for (const std::string &a : options.axes)
        unknowns.axes.push_back(parse_parameter_axis(a));
      if (unknowns.axes.empty())
        throw InputError("identify: no unknown given: use --axis \"Section/Name=A:B:STEP\" (repeatable)");
      unknowns.check_distinct_parameters("identify");
      return unknowns;
    }

    // Every scene the runs will read is checked before any work, built as
    // the runs build it (system1_fact_map, then map_cell_scene), so a
    // candidate outside the allowed ranges is an input error up front.
    // Returns the number of cells of all the facts' maps.
    std::size_t check_fact_scenes(const std::string &scene_file, const std::vector<std::string> &overrides,
                                  const Identification &search)
    {
      std::size_t cells_to_run = 0;
      for (const System1Fact *f : search.facts)
        {
          const FactMap map = system1_fact_map(*f, search.unknowns, overrides);
          for (std::size_t c = 0; c < map.grid.n_cells(); ++c)
            map_cell_scene(scene_file, map.overrides, map.grid, c, f->end_time);
          cells_to_run += map.grid.n_cells();
        }
      return cells_to_run;
    }

    void write_facts_csv(const std::string &dir, const std::vector<const System1Fact *> &facts)
    {
      CsvWriter csv(dir + "/facts.csv", {"id", "name", "overrides", "end_time_s", "seed"});
      for (const System1Fact *f : facts)
        csv.row({f->id, f->name, joined(f->overrides, "; "), CsvWriter::cell(f->end_time, 6), f->seed});
      csv.close();
    }

    // identification.csv (a row per candidate) and verdicts.csv (a row per
    // candidate and fact).
    void write_identification_tables(const std::string &dir, const Identification &search)
    {
      const MapGrid &unknowns             = search.unknowns;
      const IdentificationResult &result = search.result;
      std::vector<std::string> columns;
      for (const MapAxis &a : unknowns.axes)
        columns.push_back(a.column);
      for (const std::string &id : result.fact_ids)
        {
          columns.push_back("score_" + id);
          columns.push_back("pass_" + id);
        }
      columns.push_back("total");
      CsvWriter table(dir + "/identification.csv", columns);
      CsvWriter verdicts(dir + "/verdicts.csv", {"candidate", "fact", "score", "members_passing", "reason"});
      for (std::size_t c = 0; c < unknowns.n_cells(); ++c)
        {
          std::vector<std::string> row;
          for (const double v : unknowns.cell_values(c))
            row.push_back(CsvWriter::cell(v, 9));
          // A fact not run (interrupted) has empty cells, and the candidate no total.
          bool all_judged = true;
          for (std::size_t i = 0; i < result.fact_ids.size(); ++i)
            {
              const bool judged = result.judged[c][i];
              all_judged        = all_judged && judged;
              const std::string score = judged ? CsvWriter::cell(result.scores[c][i], 4) : "";
              const std::string pass  = judged ? CsvWriter::cell(result.passes[c][i]) : "";
              row.push_back(score);
              row.push_back(pass);
              verdicts.row({CsvWriter::cell(c), result.fact_ids[i], score, pass, result.reasons[c][i]});
            }
          row.push_back(all_judged ? CsvWriter::cell(result.total(c), 4) : "");
          table.row(row);
        }
      table.close();
      verdicts.close();
    }

    // summary.md's head: the search, its cost, and the unknowns' values.
    void write_search_summary(std::ostream &summary, const std::string &scene_name, const Identification &search,
                              const std::vector<std::string> &overrides, const double wall_seconds)
    {
      const IdentificationResult &result = search.result;
      summary << "# Identification of `" << scene_name << "` by the seed's System 1 facts\n\n"
              << "- " << search.unknowns.n_cells() << " candidates (every combination of the unknowns' values), "
              << search.facts.size() << " facts, " << search.members
              << " member(s) per run, ROM; one map per fact (`<fact>/map.csv`).\n"
              << "- Wall time " << std::fixed << std::setprecision(0) << wall_seconds << " s";
      for (std::size_t i = 0; i < result.wall_seconds.size(); ++i)
        summary << (i == 0 ? " (" : ", ") << result.fact_ids[i] << " " << result.wall_seconds[i] << " s";
      summary << (result.wall_seconds.empty() ? "" : ")") << ".\n" << std::defaultfloat;
      for (const std::string &o : overrides)
        summary << "- Held at (`--set`): " << o << "\n";
      if (!search.complete)
        summary << "- **Interrupted**: the facts not run have no verdict (empty cells in the CSV files); the "
                   "candidate below leads only on what ran.\n";
      summary << std::setprecision(6) << "\n## Unknowns\n\n| parameter | values |\n|---|---|\n";
      for (const MapAxis &a : search.unknowns.axes)
        {
          summary << "| " << a.parameter << " |";
          for (const double v : a.values)
            summary << " " << v;
          summary << " |\n";
        }
    }

    // The best candidate (leading so far, if interrupted): its values and
    // each fact's verdict on it.
    void write_best_candidate(std::ostream &summary, const Identification &search)
    {
      const IdentificationResult &result = search.result;
      const std::size_t b                = result.best;
      summary << "\n## " << (search.complete ? "Best candidate" : "Leading candidate so far") << " (total "
              << std::setprecision(3) << result.total(b) << " of " << search.facts.size() << ")\n\n";
      const std::vector<double> best_values = search.unknowns.cell_values(b);
      for (std::size_t k = 0; k < search.unknowns.axes.size(); ++k)
        summary << "- " << search.unknowns.axes[k].parameter << " = " << best_values[k] << "\n";
      summary << "\n| fact | score | members passing | reason (member 0) |\n|---|---|---|---|\n";
      for (std::size_t i = 0; i < result.fact_ids.size(); ++i)
        if (result.judged[b][i])
          summary << "| " << system1_fact(result.fact_ids[i]).name << " | " << result.scores[b][i] << " | "
                  << result.passes[b][i] << "/" << search.members << " | " << result.reasons[b][i] << " |\n";
        else
          summary << "| " << system1_fact(result.fact_ids[i]).name << " | — | — | " << result.reasons[b][i] << " |\n";
    }

    // How often each fact passes over all candidates: a fact no candidate
    // passes is a result too.
    void write_facts_over_candidates(std::ostream &summary, const Identification &search)
    {
      const IdentificationResult &result = search.result;
      summary << "\n## Each fact over all candidates\n\n| fact | candidates passing | best score |\n|---|---|---|\n";
      for (std::size_t i = 0; i < result.fact_ids.size(); ++i)
        {
          unsigned int n_pass = 0;
          double best_score   = 0;
          for (std::size_t c = 0; c < search.unknowns.n_cells(); ++c)
            {
              n_pass += result.passes[c][i] == search.members;
              best_score = std::max(best_score, result.scores[c][i]);
            }
          summary << "| " << result.fact_ids[i] << " | " << n_pass << " of " << search.unknowns.n_cells() << " | "
                  << best_score << " |\n";
        }
    }
  } // namespace

  int run_identify(const CommonOptions &common, const IdentifyOptions &options)
  {
    const auto start_time        = std::chrono::steady_clock::now();
    const std::string scene_file = resolve_scene_path(common.scene_file);
    check_overrides_unique(common.overrides);
    const Scene base = read_scene(scene_file, common.overrides);

    Identification search;
    search.unknowns                 = unknowns_grid(options);
    search.facts                    = select_system1_facts(options.facts);
    search.members                  = options.members;
    const std::size_t cells_to_run = check_fact_scenes(scene_file, common.overrides, search);

    const std::string dir = prepare_output_dir(common, base, "identify");
    MapSettings settings;
    settings.model.family = "rom";
    settings.n_members    = options.members;
    settings.perturbation = options.perturbation;

    write_facts_csv(dir, search.facts);
    console() << "identify " << base.name << ": " << search.unknowns.n_cells() << " candidates x "
              << search.facts.size() << " facts, " << cells_to_run * options.members << " ROM runs; into " << dir
              << std::endl;

    std::vector<std::string> ids;
    for (const System1Fact *f : search.facts)
      ids.push_back(f->id);
    search.result = identify_system1(
      scene_file, common.overrides, search.unknowns, ids, settings, search.complete,
      [&](const System1Fact &fact, const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells) {
        std::filesystem::create_directories(dir + "/" + fact.id);
        write_map_csv(dir + "/" + fact.id + "/map.csv", grid, cells);
        console() << "  " << fact.name << ": " << cells.size() << " cell(s) done" << std::endl;
      });
    write_identification_tables(dir, search);

    std::ostringstream summary;
    write_search_summary(summary, base.name, search, common.overrides, elapsed_seconds(start_time));
    write_best_candidate(summary, search);
    write_facts_over_candidates(summary, search);
    summary << "\nFiles: identification.csv, verdicts.csv, facts.csv, <fact>/map.csv.\n";
    write_text_file(dir + "/summary.md", summary.str());
    const IdentificationResult &result = search.result;
    console() << "identify: " << (search.complete ? "best" : "leading (interrupted)") << " candidate " << result.best
              << " (total " << result.total(result.best) << " of " << search.facts.size() << "); " << dir
              << "/summary.md" << std::endl;
    return 0; // after Ctrl-C, main() turns the interruption into 130/143
  }
} // namespace beamslider
