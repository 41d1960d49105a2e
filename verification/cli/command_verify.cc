// `beamslider verify`: the verification report on one scene. Under
// `mpirun -n P` rank 0 writes the report and the other ranks compute the
// members of the error ladder (section 5) with it; the ladder's members are
// kept in the report folder (member_runs.csv), so that a verify stopped and
// started again into the same folder does not run them again.
#include "contact/interruption.h"
#include "contact/output_file.h"
#include "meshes/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/member_runs.h"
#include "verification/cli/mpi_cells.h"
#include "verification/report/report_ladder.h"
#include "verification/report/report.h"
#include "verification/studies/console.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <fstream>
#include <iostream>

namespace beamslider
{
  int run_verify(const CommonOptions &common, const VerifyOptions &options)
  {
    MpiSession mpi(launched_by_mpi_launcher());
    const Scene scene = read_scene(resolve_scene_path(common.scene_file), common.overrides);
    const bool ladder_section =
      options.sections.empty() || std::find(options.sections.begin(), options.sections.end(), 5u) != options.sections.end();
    if (mpi.rank() != 0)
      {
        // The other ranks' share of the report: the ladder's members.
        if (ladder_section)
          {
            const ReportLadder ladder = report_ladder(scene, options.full, options.diagnostics);
            work_on_ladder(scene, ladder.rungs, ladder.settings);
          }
        return 0;
      }
    // If rank 0 ends before the ladder (an error, a stop), the other ranks,
    // waiting for its members, are told to stop.
    struct ReleaseWorkers
    {
      const MpiSession &mpi;
      bool waiting;
      ~ReleaseWorkers()
      {
        if (waiting && mpi.n_distributions() == 0)
          release_workers(mpi);
      }
    } release{mpi, ladder_section};
    Report report;
    report.dir        = prepare_output_dir(common, scene, "");
    report.scene_file = resolve_scene_path(common.scene_file);
    report.overrides  = common.overrides;
    report.ladder_diagnostics = options.diagnostics;
    const auto start = std::chrono::steady_clock::now();
    console() << "beamslider verify: scene '" << scene.name << "', report in " << report.dir
              << (options.full ? " (full studies)" : " (quick studies; --full for the long ones)") << std::endl;

    report.text << "# beamslider verification report: scene `" << scene.name << "`\n\n"
                << "Written by `beamslider verify`. Every number below is computed by this run; CSV files with the same data "
                   "sit beside this file.\n\n";
    if (!options.sections.empty())
      {
        std::string list;
        for (const unsigned int k : options.sections)
          list += (list.empty() ? "" : ", ") + std::to_string(k);
        report.text << "_Only section(s) " << list << " (`--section`); the others were not run._\n\n";
      }
    // Each section appends to report.md and is flushed to disk before the
    // next starts, so a failure late in the report keeps the earlier ones.
    auto flush = [&report] { write_text_file(report.dir + "/report.md", report.text.str()); };
    // Between sections, an interruption (Ctrl-C) ends the report with what
    // is complete; the studies inside a section stop at their next step.
    auto interrupted = [&] {
      if (!interruption_requested())
        return false;
      report.text << "\n---\n**Interrupted** (signal " << interruption_signal()
                  << "): the sections above are complete, the rest was not run.\n";
      flush();
      return true;
    };
    // The sections in order; --section picks some (a section alone takes
    // what it needs from the scene, none reads another's results).
    const std::vector<std::string> titles = {"Linear frequencies",    "Cubic modal coefficients",
                                             "Backbone curves",       "Slider contact dynamics",
                                             "FE against ROM",        "Operating range",
                                             "The seed's System 1 facts", "The beam against the continuum"};
    std::vector<std::pair<std::size_t, double>> section_seconds; // section index, wall time [s]
    const std::vector<std::function<void()>> sections = {
      [&] { add_frequency_section(report, scene); },
      [&] { add_coefficient_section(report, scene, options.full); },
      [&] { add_backbone_section(report, scene, options.full); },
      [&] { add_contact_section(report, scene, options.full); },
      [&] { add_fe_rom_section(report, scene, options.full); },
      [&] { add_map_section(report, scene, options.full); },
      [&] { add_system1_section(report, scene, options.full); },
      [&] { add_solid_section(report, scene, options.full); }};
    for (std::size_t k = 0; k < sections.size(); ++k)
      {
        if (!options.sections.empty() &&
            std::find(options.sections.begin(), options.sections.end(), k + 1) == options.sections.end())
          continue;
        const auto section_start = std::chrono::steady_clock::now();
        try
          {
            sections[k]();
          }
        catch (const MemberRunsStopped &e)
          {
            // The ladder stopped with a signal: its finished members are kept.
            report.text << "\n_The error ladder " << e.what() << "._\n";
          }
        section_seconds.emplace_back(
          k, std::chrono::duration<double>(std::chrono::steady_clock::now() - section_start).count());
        flush();
        if (interrupted())
          return interruption_exit_code();
      }

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // How this report was made: enough to reproduce it and to read its
    // wall times (run.txt beside it has the exact command line).
    report.text << "---\n## How this report was made\n\n"
                << "- build: " << build_revision() << " (run.txt: the exact command line; parameters.prm: the scene)\n"
                << "- machine: " << machine_description() << "; " << mpi.size() << " MPI rank(s)"
                << (mpi.size() > 1 ? "" : ", the ensembles' members over the cores") << "\n"
                << "- studies: "
                << (!options.full ? "quick" : options.diagnostics ? "full with the ladder's diagnostic rungs (`--full --diagnostics`)" : "full (`--full`)")
                << "\n\n"
                << "| section | wall time [s] |\n|---|---|\n";
    for (const auto &[k, s] : section_seconds)
      report.text << "| " << k + 1 << ". " << titles[k] << " | " << fixed(s, 0) << " |\n";
    report.text << "| total | " << fixed(seconds, 0) << " |\n";
    flush();
    // fixed(): a section may leave the console stream at a low precision.
    console() << "Wrote " << report.dir << "/report.md (" << fixed(seconds, 0) << " s)" << std::endl;
    return 0;
  }
} // namespace beamslider
