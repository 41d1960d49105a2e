#include "io/output_file.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "scene/source_directory.h"
#include "verification/cli/commands.h"
#include "verification/report/member_files.h"
#include "verification/studies/simulation.h"
#include "runtime/build_info.h"
#include "verification/studies/simulation_cases.h"

#include <ctime>
#include <map>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace beamslider
{
  namespace fs = std::filesystem;

  std::string resolve_scene_path(const std::string &scene)
  {
    if (fs::exists(scene))
      return scene;
    for (const std::string &candidate : {source_directory() + "/meshes/" + scene,
                                        source_directory() + "/meshes/" + scene + ".prm"})
      if (fs::exists(candidate))
        return candidate;
    throw InputError("Scene '" + scene + "' not found (looked for the path as given and in " +
                     source_directory() + "/meshes/)");
  }

  namespace
  {
    std::vector<std::string> &command_line()
    {
      static std::vector<std::string> words;
      return words;
    }

    // A word of the command line as a POSIX shell would need it written to
    // give the same word back (only for display in run.txt: nothing here
    // ever runs it).
    std::string shell_quoted(const std::string &word)
    {
      if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                                                  "_-+=/.,:@%") == std::string::npos)
        return word;
      std::string quoted = "'";
      for (const char c : word)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
      return quoted + "'";
    }

    // The parsed command and its options, for command.prm (no command until
    // main() records it); formatted only when a folder is written.
    struct RecordedCommand
    {
      std::string name;
      std::vector<CommandSetting> settings;
    };
    RecordedCommand &recorded_command()
    {
      static RecordedCommand command;
      return command;
    }

    // The result files a command writes into its folder, besides
    // parameters.prm, command.prm and run.txt ('*' stands for any text). A
    // new run removes them before it starts, so that none is left from
    // another run beside the new command.prm, however the new one ends.
    // Not here, because a re-run of the same command reuses them after its
    // own check: member_runs.csv (its key, member_runs.h; one of other
    // settings is moved aside to member_runs.other.csv, kept). A resumed
    // simulate removes nothing (its checkpoint says what it continues).
    // map keeps map.csv, map_settings.txt and timing.csv (a restart of the
    // same map continues them); verify keeps its folder as it is (a report's
    // sections, the studies' subfolders).
    const std::vector<std::string> &result_files(const std::string &command)
    {
      static const std::vector<std::string> none;
      static const std::map<std::string, std::vector<std::string>> files = {
        {"simulate",
         {"trace.csv", "periods.csv", "trace.png", "summary.md", "checkpoint.bin", "animation*.pvd", "frames.csv",
          "beam_*.vtu", "slider_*.vtp", "contacts_*.vtp"}},
        {"animate",
         {"trace.csv", "frames.csv", "frames.png", "animation*.pvd", "beam_*.vtu", "slider_*.vtp", "contacts_*.vtp",
          "solid.pvd", "solid_*.pvtu", "solid_*.vtu"}},
        {"ensemble",
         {"members.csv", "member_periods.csv", "statistics.csv", "comparison.csv", "ensemble.png", "summary.md"}},
        {"ladder",
         {"ladder.csv", "ladder_members.csv", "ladder_steps.csv", "ladder.png", "summary.md"}},
        {"modes", {"modes.csv", "line_modes.csv", "modes.vtu", "modes.pvtu", "modes_*.vtu", "summary.md"}},
        {"statics", {"statics.csv", "statics.vtu", "statics.pvtu", "statics_*.vtu", "summary.md"}},
        {"coefficients", {"coefficients.csv", "quadratic_coefficients.csv", "summary.md"}},
        {"backbone", {"backbone.csv", "eq4.csv", "backbone.png", "summary.md"}},
        {"branches", {"branches.csv", "attractor.csv", "branch_events.csv", "branches.png", "summary.md"}},
        {"map",
         {"summary.md", "published_cases.csv", "map_outcome_*.png", "map_final_position_*.png",
          "map_late_amplitude_*.png", "map_line_*.png"}},
        {"identify", {"facts.csv", "identification.csv", "verdicts.csv", "summary.md"}},
        {"sweep",
         {"pcs.csv", "runs.csv", "resonance.csv", "free_periods.csv", "pcs.png", "comparison.csv", "crossings.csv",
          "pcs_compare.png", "summary.md"}}};
      const auto found = files.find(command.substr(0, command.find('/')));
      return found == files.end() ? none : found->second;
    }

    bool matches(const std::string &name, const std::string &pattern)
    {
      const auto star = pattern.find('*');
      if (star == std::string::npos)
        return name == pattern;
      const std::string head = pattern.substr(0, star), tail = pattern.substr(star + 1);
      return name.size() >= head.size() + tail.size() && name.compare(0, head.size(), head) == 0 &&
             name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
    }

    // Removes the previous run's results (files or links, never folders).
    void remove_previous_results(const fs::path &dir, const std::string &command)
    {
      const std::vector<std::string> &patterns = result_files(command);
      if (patterns.empty())
        return;
      std::error_code ec;
      std::vector<fs::path> stale;
      for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
        {
          const std::string name = it->path().filename().string();
          const fs::file_type type = it->symlink_status(ec).type();
          if (type == fs::file_type::directory)
            continue;
          for (const std::string &pattern : patterns)
            if (matches(name, pattern))
              {
                stale.push_back(it->path());
                break;
              }
        }
      if (ec)
        throw OutputError("output folder '" + dir.string() + "' cannot be read: " + ec.message());
      for (const fs::path &file : stale)
        if (!fs::remove(file, ec) && ec)
          throw OutputError("result file '" + file.string() + "' of an earlier run cannot be removed: " + ec.message());
    }

    // The time now as run.txt records it (ISO 8601, UTC).
    std::string utc_now()
    {
      const std::time_t now = std::time(nullptr);
      char when[32];
      std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
      return when;
    }

    void write_run_record(const std::string &dir, const Scene &scene, const RunRecord record)
    {
      const RecordedCommand &command = recorded_command();
      // A resumed run continues the run command.prm describes: it stays
      // (parameters.prm is the same scene but for a longer end time).
      if (record == RunRecord::replace && !command.name.empty())
        write_text_file(dir + "/command.prm",
                        "# The options of this beamslider command with their effective values (given on the command "
                        "line or default); the scene is in parameters.prm.\n" +
                          command_settings_text(command.name, command.settings));
      write_text_file(dir + "/parameters.prm",
                      "# The scene '" + scene.name + "' as this run used it (after --set and --case), written by "
                      "beamslider. Repeat the run with the command line in run.txt and this file as the scene.\n" +
                        scene_file_text(scene));
      std::ostringstream run;
      const std::string when = utc_now();
      std::error_code ec;
      run << "command:   ";
      for (std::size_t i = 0; i < command_line().size(); ++i)
        run << (i ? " " : "") << shell_quoted(command_line()[i]);
      run << "\nworking directory: " << fs::current_path(ec).string() << "\nstarted:   " << when
          << "\nversion:   beamslider " << build_info().version << "\nrevision:  " << build_info().revision
          << " (git describe of the source tree when the build was configured)\n"
          << "built for: " << build_info().built_for
          << " (results depend on the instruction set in their last bits; CMake option BEAMSLIDER_NATIVE)\n"
          << "scene:     parameters.prm (the scene '" << scene.name << "' with its overrides)\n";
      if (!command.name.empty())
        run << "options:   command.prm (every option of the command, given or default)\n";
      const bool append = record == RunRecord::append && fs::exists(dir + "/run.txt", ec);
      OutputFile file(dir + "/run.txt", append);
      file.stream() << (append ? "\n" : "") << run.str(); // records apart by a blank line
      file.close();
    }
  } // namespace

  bool record_run_end(const int status, const std::string &messages, std::ostream &errors)
  {
    std::ostringstream how;
    how << "ended:     " << utc_now() << ", ";
    const std::string first = messages.substr(0, messages.find('\n'));
    if (status == 0)
      how << "completed (exit 0)";
    else if (status == not_converged_exit_code)
      how << "completed, not converged (exit 3)" << (first.empty() ? "" : ": " + one_line(first))
          << "\n           every result is written; a reference did not prove its convergence (summary.md says "
             "which and by how much)";
    else
      {
        // Only `simulate` continues from a checkpoint; the studies take up
        // their finished members or cells when run again into the folder.
        const bool resumable = command_line().size() > 1 && command_line()[1] == "simulate";
        how << (status >= 128 ? "interrupted" : status == 2 ? "refused" : "failed") << " (exit " << status << ")"
            << (first.empty() ? "" : ": " + one_line(first))
            << "\n           the results in this folder are partial (run the command again"
            << (resumable ? ", or --resume it from its checkpoint" : "") << ")";
      }
    // Members this process took from, or kept in, the store it shares with
    // other studies and reports (member_files.h).
    const SharedMemberCounts shared = shared_member_counts();
    if (shared.reused + shared.kept > 0)
      how << "\nshared:    " << shared.reused << " FE members taken from " << shared.folder
          << " (run before with the same scene content, settings and build; not run again), " << shared.kept
          << " run now and kept there";
    bool written = true;
    for (const std::string &dir : held_output_folders())
      {
        std::error_code ec;
        if (!fs::exists(fs::path(dir) / "run.txt", ec))
          continue; // a folder locked but never prepared
        try
          {
            OutputFile file(dir + "/run.txt", FileMode::append);
            file.stream() << how.str() << '\n';
            file.close();
          }
        catch (const OutputError &e)
          {
            errors << "error: results not written: " << one_line(e.what()) << std::endl;
            written = false;
          }
      }
    return written;
  }

  void record_command_line(const int argc, const char *const *argv)
  {
    command_line().assign(argv, argv + argc);
  }

  void record_command_settings(const std::string &command, const std::vector<CommandSetting> &settings)
  {
    recorded_command() = {command, settings};
  }

  std::string output_dir_path(const CommonOptions &common, const Scene &scene, const std::string &command)
  {
    const fs::path dir = !common.output_dir.empty() ? fs::path(common.output_dir)
                         : command.empty()           ? fs::path("reports") / scene.name
                                                     : fs::path("reports") / scene.name / command;
    return dir.string();
  }

  std::string prepare_output_dir(const CommonOptions &common, const Scene &scene, const std::string &command,
                                 const RunRecord record)
  {
    const fs::path dir = output_dir_path(common, scene, command);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
      throw OutputError("output folder '" + dir.string() + "' cannot be created: " + ec.message());
    if (!fs::is_directory(dir, ec))
      throw OutputError("output folder '" + dir.string() + "' is not a folder");
    // One run per folder: held before anything in it is touched.
    lock_output_folder(dir.string());
    if (record == RunRecord::replace)
      remove_previous_results(dir, command);
    write_run_record(dir.string(), scene, record);
    return dir.string();
  }

  Scene read_command_scene(const CommonOptions &common, const std::string &case_name,
                           std::vector<std::string> *modified)
  {
    const std::string file = resolve_scene_path(common.scene_file);
    if (case_name.empty())
      return read_scene(file, common.overrides);
    return read_case_scene(file, find_case(case_name), common.overrides, modified);
  }

  void require_mesh_for_modes(const unsigned int n_elements, const unsigned int n_modes, const std::string &option)
  {
    if (n_elements < n_modes + 1)
      throw InputError(option + " " + std::to_string(n_modes) + " needs a mesh of at least " +
                       std::to_string(n_modes + 1) + " elements; 'Discretisation/Number of elements' (or --elements) is " +
                       std::to_string(n_elements));
  }

  void StudyHandover::refuse(const StudyHandover *handover, const std::string &command)
  {
    if (handover)
      throw InputError("the command '" + command +
                       "' cannot hand its result over in memory; only ensemble, ladder, sweep and map can");
  }

  void require_same_scene(const Scene &kept, const Scene &now, const std::string &command)
  {
    if (const auto differ = first_differing_lines(scene_file_text(now), scene_file_text(kept)))
      throw InputError(command + ": the scene now reads differently from the one the result was computed with ('" +
                       differ->second + "' is now '" + differ->first + "'); compute it again");
  }

} // namespace beamslider
