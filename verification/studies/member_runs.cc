// Persisted, distributed member runs, see member_runs.h.
#include "verification/studies/member_runs.h"

#include "contact/csv_writer.h"
#include "contact/interruption.h"
#include "contact/output_file.h"
#include "verification/studies/build_info.h"
#include "verification/studies/console.h"
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
    std::vector<std::vector<EnsembleMember>> members(groups.size());
    std::vector<std::vector<bool>> have(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g)
      {
        members[g].resize(groups[g].n_members);
        have[g].assign(groups[g].n_members, false);
      }
    std::vector<TraceThresholds> thresholds;
    for (const MemberGroup &g : groups)
      thresholds.push_back(trace_thresholds(g.scene));
    const std::vector<std::string> columns = member_record_columns();
    const std::string key                  = member_runs_key(groups, settings.study);
    std::optional<CsvWriter> rows;
    std::size_t n_kept = 0;
    if (settings.n_kept)
      *settings.n_kept = 0;
    const std::string stem = settings.dir + "/" + settings.file.substr(0, settings.file.rfind(".csv"));
    const std::string path = settings.dir.empty() ? std::string() : stem + ".csv";
    if (!path.empty())
      {
        std::string kept = "# " + key + "\n" + CsvWriter::line(columns) + "\n";
        const std::vector<std::string> previous = records(read_text_file_if_present(path));
        if (!previous.empty() && previous.front() != "# " + key)
          {
            std::filesystem::rename(path, stem + ".other.csv");
            console() << settings.progress_prefix << path
                      << " holds the members of other settings: not reused, moved to " << stem << ".other.csv; "
                         "every member is run afresh"
                      << std::endl;
          }
        else
          for (std::size_t k = 2; k < previous.size(); ++k)
            try
              {
                const std::vector<std::string> cells = CsvWriter::cells(previous[k]);
                unsigned long g0 = 0;
                const auto [end, error] = std::from_chars(cells[0].data(), cells[0].data() + cells[0].size(), g0);
                if (error != std::errc() || g0 >= groups.size())
                  continue;
                std::size_t g = 0;
                std::string name;
                EnsembleMember m = member_from_record(cells, thresholds[g0], g, name);
                if (g != g0 || name != groups[g].name || m.index >= groups[g].n_members || have[g][m.index])
                  continue;
                have[g][m.index] = true;
                members[g][m.index] = std::move(m);
                kept += previous[k] + "\n";
                ++n_kept;
              }
            catch (const std::invalid_argument &)
              {
                // a row cut short by a kill: its member runs again
              }
        // The file anew with the complete rows only (atomically: a kill now
        // leaves the old file or the new one); new rows are appended.
        write_file_atomically(path, kept);
        CsvOptions append;
        append.append = true;
        rows.emplace(path, columns, append);
      }

    if (settings.n_kept)
      *settings.n_kept = n_kept;
    std::vector<std::size_t> todo;
    for (const std::size_t run : longest_first(groups))
      {
        const auto [g, m] = group_and_member(groups, run);
        if (!have[g][m])
          todo.push_back(run);
      }
    console() << settings.progress_prefix << n_total << " member runs";
    if (n_kept)
      console() << ", " << n_kept << " of them kept from " << path;
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
        EnsembleMember member = member_from_record(cells, thresholds[g], group, name);
        if (rows)
          rows->row(cells);
        members[g][m] = std::move(member);
        have[g][m]    = true;
        ++n_done;
        console() << settings.progress_prefix << "member " << m << (name.empty() ? "" : " of " + name) << " ("
                  << n_done + n_kept << "/" << n_total << (mpi.size() > 1 ? ", rank " + std::to_string(rank) : "")
                  << ", " << std::fixed << std::setprecision(1) << members[g][m].wall_seconds << " s, "
                  << std::chrono::duration<double>(clock::now() - start).count() << " s in all)"
                  << std::defaultfloat << ": " << members[g][m].analysis.line << std::endl;
      },
      stop, settings.n_threads);
    if (rows)
      rows->close();
    if (n_done < todo.size())
      throw MemberRunsStopped("stopped after " + std::to_string(n_done + n_kept) + " of " + std::to_string(n_total) +
                              " member runs" +
                              (path.empty() ? std::string()
                                            : "; " + path +
                                                " holds every finished one: run the same command again into the "
                                                "same folder to continue"));
    return members;
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
