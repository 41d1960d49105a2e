// Persisted, distributed member runs, see member_runs.h.
#include "verification/studies/member_runs.h"

#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/output_file.h"
#include "verification/studies/build_info.h"
#include "io/console.h"
#include "verification/studies/model_choice.h"
#include "verification/studies/simulation_cases.h"

#include <charconv>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <optional>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string exact(const double x)
    {
      char buffer[32];
      const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, x);
      return error == std::errc() ? std::string(buffer, end) : std::string("?");
    }

    // The records of a CSV text: lines, except that a line break inside a
    // quoted cell belongs to the cell. A last record without its '\n' (a
    // write cut short) is returned too; its checks reject it.
    std::vector<std::string> records(const std::string &text)
    {
      std::vector<std::string> out;
      std::string current;
      bool in_quotes = false;
      for (const char c : text)
        {
          if (c == '"')
            in_quotes = !in_quotes; // "" inside quotes toggles twice
          if (c == '\n' && !in_quotes)
            {
              out.push_back(std::move(current));
              current.clear();
            }
          else
            current += c;
        }
      if (!current.empty())
        out.push_back(std::move(current));
      return out;
    }

    // Each member's scene checked on every rank before any work: a member
    // outside the allowed ranges is an input error everywhere alike.
    void check_groups(const std::vector<MemberGroup> &groups)
    {
      for (const MemberGroup &g : groups)
        {
          if (g.n_members == 0)
            throw InputError("--members 0: an ensemble needs at least one member");
          Scene s = g.scene;
          validate_scene(s);
          s.initial.slider_position_over_L += (g.n_members - 1) * g.perturbation;
          if (!(s.initial.slider_position_over_L <= 1.))
            throw InputError("--perturbation " + std::to_string(g.perturbation) +
                             " moves the last member's start beyond the beam");
        }
    }

    // Rank 0's members of the groups, members[group][m], each read back or
    // computed, and whether it is there yet.
    struct MemberTable
    {
      explicit MemberTable(const std::vector<MemberGroup> &member_groups)
        : groups(member_groups), members(member_groups.size()), have(member_groups.size())
      {
        for (std::size_t g = 0; g < groups.size(); ++g)
          {
            members[g].resize(groups[g].n_members);
            have[g].assign(groups[g].n_members, false);
          }
        for (const MemberGroup &g : groups)
          thresholds.push_back(trace_thresholds(g.scene));
      }

      // A row of an earlier member_runs.csv of the same key: taken (true)
      // if it is a whole record of a member of these groups not yet there.
      bool take_previous_row(const std::string &row)
      {
        try
          {
            const std::vector<std::string> cells = CsvWriter::cells(row);
            unsigned long g0 = 0;
            const auto [end, error] = std::from_chars(cells[0].data(), cells[0].data() + cells[0].size(), g0);
            if (error != std::errc() || g0 >= groups.size())
              return false;
            std::size_t g = 0;
            std::string name;
            EnsembleMember m = member_from_record(cells, thresholds[g0], g, name);
            if (g != g0 || name != groups[g].name || m.index >= groups[g].n_members || have[g][m.index])
              return false;
            have[g][m.index]    = true;
            members[g][m.index] = std::move(m);
            return true;
          }
        catch (const std::invalid_argument &)
          {
            return false; // a row cut short by a kill: its member runs again
          }
      }

      // The runs not there yet, longest first.
      std::vector<std::size_t> todo() const
      {
        std::vector<std::size_t> runs;
        for (const std::size_t run : longest_first(groups))
          {
            const auto [g, m] = group_and_member(groups, run);
            if (!have[g][m])
              runs.push_back(run);
          }
        return runs;
      }

      const std::vector<MemberGroup> &groups;
      std::vector<std::vector<EnsembleMember>> members;
      std::vector<std::vector<bool>> have;
      std::vector<TraceThresholds> thresholds;
    };

    // member_runs.csv (or the settings' file) in the output folder, which
    // rank 0 appends each finished member to; no path: nothing persisted.
    struct MemberFile
    {
      explicit MemberFile(const MemberRunsSettings &settings)
        : stem(settings.dir + "/" + settings.file.substr(0, settings.file.rfind(".csv")))
        , path(settings.dir.empty() ? std::string() : stem + ".csv")
      {}

      // The rows of an earlier start with this key into `table` (a file of
      // another key moved aside), the file anew with those rows only, then
      // open for appending.
      void resume(const std::string &key, const std::vector<std::string> &columns, MemberTable &table,
                  const std::string &progress_prefix)
      {
        std::string kept = "# " + key + "\n" + CsvWriter::line(columns) + "\n";
        const std::vector<std::string> previous = records(read_text_file_if_present(path));
        if (!previous.empty() && previous.front() != "# " + key)
          {
            std::filesystem::rename(path, stem + ".other.csv");
            console() << progress_prefix << path << " holds the members of other settings: not reused, moved to "
                      << stem << ".other.csv; every member is run afresh" << std::endl;
          }
        else
          for (std::size_t k = 2; k < previous.size(); ++k)
            if (table.take_previous_row(previous[k]))
              {
                kept += previous[k] + "\n";
                ++n_kept;
              }
        // The file anew with the complete rows only (atomically: a kill now
        // leaves the old file or the new one); new rows are appended.
        write_file_atomically(path, kept);
        CsvOptions append;
        append.append = true;
        rows.emplace(path, columns, append);
      }

      const std::string stem, path;
      std::optional<CsvWriter> rows;
      std::size_t n_kept = 0;
    };

    std::string stopped_message(const std::size_t n_finished, const std::size_t n_total, const std::string &path)
    {
      return "stopped after " + std::to_string(n_finished) + " of " + std::to_string(n_total) + " member runs" +
             (path.empty() ? std::string()
                           : "; " + path +
                               " holds every finished one: run the same command again into the same folder to "
                               "continue");
    }
  } // namespace

  std::string member_runs_key(const std::vector<MemberGroup> &groups, const std::string &study)
  {
    std::ostringstream key;
    key << study << "; " << build_revision();
    for (std::size_t g = 0; g < groups.size(); ++g)
      {
        const MemberGroup &r = groups[g];
        key << "; group " << g << " '" << r.name << "': scene " << r.scene.name << " content "
            << scene_content_key(r.scene) << ", " << r.model.label() << " (dt " << exact(r.model.time_step)
            << "), end time " << exact(r.scene.time_stepping.end_time) << " s, " << r.n_members
            << " members, perturbation " << exact(r.perturbation);
      }
    std::string text = key.str();
    for (char &c : text)
      if (c == '\n' || c == '\r')
        c = ' ';
    return text;
  }

  std::vector<std::vector<EnsembleMember>> run_member_groups(const std::vector<MemberGroup> &groups,
                                                             const MemberRunsSettings &settings)
  {
    using clock = std::chrono::steady_clock;
    check_groups(groups);
    const MpiSession single(false);
    const MpiSession &mpi = settings.mpi ? *settings.mpi : single;
    const auto work       = [&groups](const std::size_t run) {
      const auto [g, m]           = group_and_member(groups, run);
      const EnsembleMember member = run_member(groups[g].scene, groups[g].model, m, groups[g].perturbation);
      if (member.result.status == RunStatus::interrupted)
        return std::string(); // not a result: run again on the next start
      return CsvWriter::line(member_record(g, groups[g].name, member));
    };
    const auto stop = [] { return interruption_requested(); };
    if (mpi.rank() != 0)
      {
        distribute_cells(
          mpi, {}, work, [](std::size_t, const std::string &, unsigned int) {}, stop);
        return {};
      }

    // Rank 0: what is done already, then the rest.
    const std::size_t n_total = n_runs(groups);
    MemberTable table(groups);
    const std::vector<std::string> columns = member_record_columns();
    const std::string key                  = member_runs_key(groups, settings.study);
    MemberFile file(settings);
    if (settings.n_kept)
      *settings.n_kept = 0;
    if (!file.path.empty())
      file.resume(key, columns, table, settings.progress_prefix);
    const std::size_t n_kept = file.n_kept;
    if (settings.n_kept)
      *settings.n_kept = n_kept;

    const std::vector<std::size_t> todo = table.todo();
    console() << settings.progress_prefix << n_total << " member runs";
    if (n_kept)
      console() << ", " << n_kept << " of them kept from " << file.path;
    console() << "; " << todo.size() << " to run, longest first, on "
              << (mpi.size() > 1 ? std::to_string(mpi.size()) + " MPI ranks" : std::string("the cores of this process"))
              << std::endl;

    std::size_t n_done = 0;
    const auto start   = clock::now();
    distribute_cells(
      mpi, todo, work,
      [&](const std::size_t run, const std::string &text, const unsigned int rank) {
        const auto [g, m]                    = group_and_member(groups, run);
        const std::vector<std::string> cells = CsvWriter::cells(text);
        std::size_t group                    = 0;
        std::string name;
        EnsembleMember member = member_from_record(cells, table.thresholds[g], group, name);
        if (file.rows)
          file.rows->row(cells);
        table.members[g][m] = std::move(member);
        table.have[g][m]    = true;
        ++n_done;
        console() << settings.progress_prefix << "member " << m << (name.empty() ? "" : " of " + name) << " ("
                  << n_done + n_kept << "/" << n_total << (mpi.size() > 1 ? ", rank " + std::to_string(rank) : "")
                  << ", " << std::fixed << std::setprecision(1) << table.members[g][m].wall_seconds << " s, "
                  << std::chrono::duration<double>(clock::now() - start).count() << " s in all)"
                  << std::defaultfloat << ": " << table.members[g][m].analysis.line << std::endl;
      },
      stop, settings.n_threads);
    if (file.rows)
      file.rows->close();
    if (n_done < todo.size())
      throw MemberRunsStopped(stopped_message(n_done + n_kept, n_total, file.path));
    return std::move(table.members);
  }

  MemberGroupRunner member_runs_runner(const MemberRunsSettings &settings)
  {
    return [settings](const std::vector<MemberGroup> &groups) { return run_member_groups(groups, settings); };
  }

  MemberGroupRunner check_rounds_runner(const MemberRunsSettings &settings)
  {
    auto round = std::make_shared<unsigned int>(0);
    return [settings, round](const std::vector<MemberGroup> &groups) {
      MemberRunsSettings s = settings;
      // member_runs.csv → member_runs.check-1.csv, …
      s.file = settings.file.substr(0, settings.file.rfind(".csv")) + ".check-" + std::to_string(++*round) + ".csv";
      return run_member_groups(groups, s);
    };
  }

  std::function<unsigned long(unsigned long)> round_sharer(const MpiSession *mpi)
  {
    if (!mpi)
      return {};
    return [mpi](const unsigned long mask) { return share_round(*mpi, mask); };
  }

  void work_on_check_rounds(const Scene &scene, const std::vector<RefinementPlan> &plans,
                            std::vector<std::size_t> n_done, const unsigned int n_members,
                            const double perturbation, const MemberRunsSettings &settings)
  {
    work_on_convergence_checks(
      scene, plans, std::move(n_done), n_members, perturbation,
      [&settings](const std::vector<MemberGroup> &groups) { run_member_groups(groups, settings); },
      round_sharer(settings.mpi));
  }
} // namespace beamslider
