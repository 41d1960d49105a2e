// Persisted, distributed member runs, see member_runs.h.
#include "verification/studies/member_runs.h"

#include "numerics/stop_request.h"
#include "runtime/build_info.h"
#include "numerics/elapsed.h"
#include "verification/studies/model_choice.h"
#include "verification/studies/simulation_cases.h"

#include <charconv>
#include <chrono>
#include <iomanip>
#include <memory>
#include <sstream>

namespace beamslider
{
  namespace
  {
    // One member run, its record packed into one text (what travels
    // between ranks); "" for a run that was interrupted.
    using CellWork = std::function<std::string(std::size_t)>;

    // A record as one text: each cell as its length, ':' and its bytes.
    std::string packed(const std::vector<std::string> &cells)
    {
      std::string text;
      for (const std::string &cell : cells)
        text += std::to_string(cell.size()) + ':' + cell;
      return text;
    }

    std::vector<std::string> unpacked(const std::string &text)
    {
      std::vector<std::string> cells;
      for (std::size_t at = 0; at < text.size();)
        {
          const std::size_t colon = text.find(':', at);
          const std::size_t size  = std::stoul(text.substr(at, colon - at));
          cells.push_back(text.substr(colon + 1, size));
          at = colon + 1 + size;
        }
      return cells;
    }

    // A key on one line, breaks as spaces (a scene's name may hold one; scene/printable.h's one_line escapes them instead, which would change the keys of existing files).
    std::string key_on_one_line(std::string text)
    {
      for (char &c : text)
        if (c == '\n' || c == '\r')
          c = ' ';
      return text;
    }

    std::string exact(const double x)
    {
      char buffer[32];
      const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, x);
      return error == std::errc() ? std::string(buffer, end) : std::string("?");
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
          s.initial.slider_position_over_L += (g.first_member + g.n_members - 1) * g.perturbation;
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

      // A record kept earlier under the same key: taken (true) if it is a
      // whole record of a member of these groups not yet there.
      bool take_previous_record(const std::vector<std::string> &cells)
      {
        try
          {
            unsigned long g0 = 0;
            const auto [end, error] = std::from_chars(cells[0].data(), cells[0].data() + cells[0].size(), g0);
            if (error != std::errc() || g0 >= groups.size())
              return false;
            std::size_t g = 0;
            std::string name;
            EnsembleMember m = member_from_record(cells, thresholds[g0], g, name);
            if (g != g0 || name != groups[g].name || m.index < groups[g].first_member)
              return false;
            const unsigned int k = m.index - groups[g].first_member;
            if (k >= groups[g].n_members || have[g][k])
              return false;
            have[g][k]    = true;
            members[g][k] = std::move(m);
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

    std::string stopped_message(const std::size_t n_finished, const std::size_t n_total, const std::string &store)
    {
      return "stopped after " + std::to_string(n_finished) + " of " + std::to_string(n_total) + " member runs" +
             (store.empty() ? std::string()
                            : "; " + store +
                                " holds every finished one: run the same command again into the same folder to "
                                "continue");
    }

    // Rank 0's progress lines, to the settings' on_progress.
    struct MemberProgress
    {
      void line(const std::string &text) const
      {
        if (settings.on_progress)
          settings.on_progress(settings.progress_prefix + text);
      }

      // "N member runs, K of them kept from …; T to run, longest first, on …"
      void start(const std::size_t n_total, const std::size_t n_kept, const std::string &store,
                 const std::size_t n_todo, const std::size_t n_cached) const
      {
        std::ostringstream text;
        text << n_total << " member runs";
        if (n_kept)
          text << ", " << n_kept << " of them kept from " << store;
        if (n_cached)
          text << ", " << n_cached << " taken from the shared store of members run before with the same scene, "
               << "settings and build";
        text << "; " << n_todo << " to run, longest first, on "
             << (n_ranks > 1 ? std::to_string(n_ranks) + " MPI ranks" : std::string("the cores of this process"));
        line(text.str());
      }

      // One finished member: its place in the count, its wall time and the
      // time since the start, and its trace analysis.
      void finished(const std::size_t m, const std::string &name, const std::size_t n_finished,
                    const std::size_t n_total, const unsigned int rank, const EnsembleMember &member) const
      {
        std::ostringstream text;
        text << "member " << m << (name.empty() ? "" : " of " + name) << " (" << n_finished << "/" << n_total
             << (n_ranks > 1 ? ", rank " + std::to_string(rank) : "") << ", " << std::fixed << std::setprecision(1)
             << member.wall_seconds << " s, "
             << elapsed_seconds(start_time) << " s in all)"
             << std::defaultfloat << ": " << member.analysis.line;
        line(text.str());
      }

      const MemberRunsSettings &settings;
      const unsigned int n_ranks;
      const std::chrono::steady_clock::time_point start_time = std::chrono::steady_clock::now();
    };

    // The store's records of an earlier start with this key into `table`; the
    // number taken.
    std::size_t resume(MemberRecordStore &store, const std::string &key, MemberTable &table)
    {
      std::size_t n_kept = 0;
      if (store.open)
        store.open(key, member_record_columns(), [&](const std::vector<std::string> &record) {
          const bool taken = table.take_previous_record(record);
          n_kept += taken;
          return taken;
        });
      return n_kept;
    }

    // Rank 0's part: what is done already, then the rest, over the ranks
    // or threads; round r's members kept in the settings' records(r).
    std::vector<std::vector<EnsembleMember>> run_on_manager(const std::vector<MemberGroup> &groups,
                                                            const MemberRunsSettings &settings,
                                                            const MpiSession &mpi, const CellWork &work,
                                                            const unsigned int round)
    {
      const std::size_t n_total = n_runs(groups);
      MemberTable table(groups);
      MemberRecordStore store = settings.records ? settings.records(round) : MemberRecordStore();
      if (settings.n_kept)
        *settings.n_kept = 0;
      const std::size_t n_kept = resume(store, member_runs_key(groups, settings.study), table);
      if (settings.n_kept)
        *settings.n_kept = n_kept;

      // The shared store's members next (each also into this study's own).
      std::size_t n_cached = 0;
      if (settings.cached)
        for (const std::size_t run : table.todo())
          {
            const auto [g, m] = group_and_member(groups, run);
            std::optional<std::vector<std::string>> record = settings.cached(groups[g], member_cache_key(groups[g], groups[g].first_member + m));
            if (!record || record->size() != member_record_columns().size())
              continue;
            (*record)[0] = std::to_string(g); // this study's group and its name
            (*record)[1] = groups[g].name;
            if (!table.take_previous_record(*record))
              continue;
            if (store.append)
              store.append(*record);
            ++n_cached;
          }

      const std::vector<std::size_t> todo = table.todo();
      const MemberProgress progress{settings, mpi.size()};
      progress.start(n_total, n_kept, store.name, todo.size(), n_cached);
      std::size_t n_done = 0;
      distribute_cells(
        mpi, todo, work,
        [&](const std::size_t run, const std::string &text, const unsigned int rank) {
          const auto [g, m]                    = group_and_member(groups, run);
          const std::vector<std::string> cells = unpacked(text);
          std::size_t group                    = 0;
          std::string name;
          EnsembleMember member = member_from_record(cells, table.thresholds[g], group, name);
          if (store.append)
            store.append(cells);
          if (settings.remember)
            settings.remember(groups[g], member_cache_key(groups[g], groups[g].first_member + m), cells);
          table.members[g][m] = std::move(member);
          table.have[g][m]    = true;
          ++n_done;
          progress.finished(table.members[g][m].index, name, n_done + n_kept, n_total, rank, table.members[g][m]);
        },
        [] { return interruption_requested(); }, settings.n_threads);
      if (store.close)
        store.close();
      if (n_done < todo.size())
        throw MemberRunsStopped(stopped_message(n_done + n_kept, n_total, store.name));
      return std::move(table.members);
    }

    // run_member_groups with round `round`'s store (0: the members, r > 0
    // a convergence check's later round r).
    std::vector<std::vector<EnsembleMember>> run_round(const std::vector<MemberGroup> &groups,
                                                       const MemberRunsSettings &settings, const unsigned int round)
    {
      check_groups(groups);
      const MpiSession single(false);
      const MpiSession &mpi = settings.mpi ? *settings.mpi : single;
      const CellWork work   = [&groups](const std::size_t run) {
        const auto [g, m]           = group_and_member(groups, run);
        const EnsembleMember member = run_member(groups[g], m);
        if (member.result.status == RunStatus::interrupted)
          return std::string(); // not a result: run again on the next start
        return packed(member_record(g, groups[g].name, member));
      };
      if (mpi.rank() == 0)
        return run_on_manager(groups, settings, mpi, work, round);
      distribute_cells(
        mpi, {}, work, [](std::size_t, const std::string &, unsigned int) {},
        [] { return interruption_requested(); });
      return {};
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
        if (r.first_member > 0) // absent for the first members: the key of a study that grows none is as before
          key << ", from member " << r.first_member;
      }
    return key_on_one_line(key.str());
  }

  std::string member_cache_key(const MemberGroup &group, const unsigned int member)
  {
    const ModelSetting &s = group.model;
    std::ostringstream key;
    key << build_revision() << " (" << build_info().built_for << ") executable " << executable_identity()
        << "; scene " << group.scene.name << " content " << scene_content_key(group.scene)
        << "; model " << s.family << " elements " << s.n_elements << " modes " << s.n_modes << " corrections "
        << s.n_static_corrections << " ritz " << s.ritz_blocks << " coefficients " << s.coefficients
        << " integrator " << s.integrator << " axial inertia " << s.axial_inertia << " damped " << s.damped_modes
        << " dt " << exact(s.time_step) << " theta " << exact(s.theta) << " offset " << exact(s.slider_offset_over_L)
        << "; end time " << exact(group.scene.time_stepping.end_time) << " perturbation " << exact(group.perturbation)
        << "; member " << member;
    return key_on_one_line(key.str());
  }

  std::vector<std::vector<EnsembleMember>> run_member_groups(const std::vector<MemberGroup> &groups,
                                                             const MemberRunsSettings &settings)
  {
    return run_round(groups, settings, 0);
  }

  MemberGroupRunner member_runs_runner(const MemberRunsSettings &settings)
  {
    return [settings](const std::vector<MemberGroup> &groups) { return run_member_groups(groups, settings); };
  }

  MemberGroupRunner check_rounds_runner(const MemberRunsSettings &settings)
  {
    auto round = std::make_shared<unsigned int>(0);
    return [settings, round](const std::vector<MemberGroup> &groups) {
      return run_round(groups, settings, ++*round);
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
