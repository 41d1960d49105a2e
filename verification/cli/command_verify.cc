// `beamslider verify`: the verification report on one scene. Under
// `mpirun -n P` rank 0 writes the report and the other ranks compute the
// members of the error ladder (section 5) with it; the ladder's members are
// kept in the report folder (member_runs.csv), so that a verify stopped and
// started again into the same folder does not run them again.
//
// Section 8 (the solid strip: deal.II, PETSc and SLEPc, one core) needs
// nothing of sections 1–7. A verify of one process therefore starts it at
// once in a second process (this executable, `verify --section 8` with an
// argument vector, writing into the same folder) and appends its text when
// the report reaches it: the two cores share the serial sections 1–4 and the
// solid instead of taking them one after the other. A thread would not do:
// Debian's PETSc is not thread-safe.
#include "io/interruption.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "scene/scene.h"
#include "runtime/child_process.h"
#include "verification/cli/commands.h"
#include "numerics/elapsed.h"
#include "verification/studies/member_runs.h"
#include "runtime/build_info.h"
#include "runtime/mpi_cells.h"
#include "verification/report/report_ladder.h"
#include "verification/report/report_region.h"
#include "verification/report/report.h"
#include "io/console.h"

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

namespace beamslider
{
  namespace
  {
    bool selected(const VerifyOptions &options, const unsigned int section)
    {
      return options.sections.empty() ||
             std::find(options.sections.begin(), options.sections.end(), section) != options.sections.end();
    }

    // A section run by a second process: its argument vector, the file its
    // text goes to, and the process's outcome with its wall time. That time
    // is measured by the thread that waits for the process, not by the
    // TimerOutput of the others: a deal.II Timer reduces its lap over MPI
    // when it stops, and MPI (started by sections 1–7's eigensolvers, with
    // MPI_THREAD_SERIALIZED) must not be called from a second thread.
    struct SectionProcess
    {
      std::vector<std::string> argv;
      std::string part_file;
      std::future<std::pair<ChildResult, double>> outcome; // the result, wall time [s]
    };

    const std::vector<std::string> &section_titles()
    {
      static const std::vector<std::string> titles = {"Linear frequencies",    "Cubic modal coefficients",
                                                      "Backbone curves",       "Slider contact dynamics",
                                                      "FE against ROM",        "Operating range",
                                                      "The seed's System 1 facts", "The beam against the continuum"};
      return titles;
    }

    // Section k's (from 0) name in the report's table of wall times, and
    // its key in the TimerOutput that measures them.
    std::string section_name(const std::size_t k)
    {
      return std::to_string(k + 1) + ". " + section_titles()[k];
    }

    // This program's path, for the child processes verify starts ("" and
    // `ec` set when the system does not say).
    std::string this_program(std::error_code &ec)
    {
      return std::filesystem::read_symlink("/proc/self/exe", ec).string();
    }

    // Section 6's strong scaling: `beamslider map` as this program, alone
    // and under mpirun, each a child process started with an argument vector.
    TimedMap time_map_program(const unsigned int ranks, const std::vector<std::string> &arguments,
                              const std::string &output)
    {
      std::error_code ec;
      const std::string self = this_program(ec);
      if (ec)
        return {0, "the path of this executable is unknown (" + ec.message() + ")"};
      std::vector<std::string> argv;
      if (ranks > 1)
        argv = {"mpirun", "-np", std::to_string(ranks)};
      argv.push_back(self);
      argv.insert(argv.end(), arguments.begin(), arguments.end());
      argv.insert(argv.end(), {"--output", output});
      const auto start = std::chrono::steady_clock::now();
      // Under `mpirun -n K beamslider verify` this process is an MPI launch's
      // rank: its children must not inherit that launch.
      const ChildResult result = run_child(argv, ChildEnvironment::without_mpi_launch);
      const double wall        = elapsed_seconds(start);
      if (!result.succeeded())
        return {wall, result.error + (ranks > 1 ? " (is Open MPI's mpirun on PATH? As root it needs "
                                                  "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1)"
                                                : "")};
      return {wall, ""};
    }

    // Starts `beamslider verify --section <section>` into `dir` with the
    // scene and options of this run; nullptr when this executable's path is
    // unknown (the section then runs in this process).
    std::unique_ptr<SectionProcess> start_section_process(const unsigned int section, const Report &report,
                                                          const VerifyOptions &options)
    {
      std::error_code ec;
      const std::string self = this_program(ec);
      if (ec)
        return nullptr;
      // Absolute paths: a relative one that starts with '-' would read as an option.
      const std::string dir = std::filesystem::absolute(report.dir, ec).string();
      const std::string scene_file = std::filesystem::absolute(report.scene_file, ec).string();
      if (ec)
        return nullptr;
      auto process       = std::make_unique<SectionProcess>();
      process->part_file = dir + "/.section" + std::to_string(section) + ".part.md";
      process->argv      = {self, "verify", scene_file};
      for (const std::string &o : report.overrides)
        process->argv.insert(process->argv.end(), {"--set", o});
      process->argv.insert(process->argv.end(), {"--output", dir, "--section", std::to_string(section),
                                                 "--part-file", process->part_file});
      if (options.full)
        process->argv.push_back("--full");
      if (is_quiet())
        process->argv.push_back("--quiet");
      process->outcome = std::async(std::launch::async, [argv = process->argv] {
        const auto start         = std::chrono::steady_clock::now();
        const ChildResult result = run_child(argv, ChildEnvironment::without_mpi_launch);
        return std::make_pair(result, elapsed_seconds(start));
      });
      return process;
    }

    // Waits for the section's process and returns its text; throws when it
    // failed (its own messages are on standard error above).
    std::string finish_section_process(SectionProcess &process, double &wall_seconds)
    {
      const auto [result, seconds] = process.outcome.get();
      wall_seconds                 = seconds;
      if (!result.succeeded())
        {
          std::string command;
          for (const std::string &a : process.argv)
            command += (command.empty() ? "" : " ") + a;
          throw std::runtime_error("the report's section run in a second process (" + command + ") failed: " +
                                   result.error);
        }
      std::string text;
      try
        {
          text = read_text_file(process.part_file);
        }
      catch (const FileReadError &e)
        {
          throw OutputError(std::string(e.what()) + " (the text of a section run in a second process)");
        }
      std::filesystem::remove(process.part_file);
      return text;
    }

    // The report on rank 0, shared by its stages: the sections in order
    // (each appends to report.text), the second process running one of them,
    // and the wall time of each section run here (deal.II's TimerOutput, one
    // subsection per section).
    struct VerifyRun
    {
      explicit VerifyRun(const VerifyOptions &options)
        : options(options)
      {}
      const VerifyOptions &options;
      Report report;
      CaseRunner run_case; // section 4's
      std::vector<std::function<void()>> sections;
      dealii::ConditionalOStream no_summary{std::cout, false}; // the report prints the times
      dealii::TimerOutput timer{no_summary, dealii::TimerOutput::never, dealii::TimerOutput::wall_times};
      std::vector<std::size_t> sections_run; // indices, in order
      std::unique_ptr<SectionProcess> solid_process; // section 8 beside the others
      double beside_seconds = 0;                     // its wall time
      bool beside = false; // a section ran in the second process
    };

    // The other ranks' share of the report: the ladder's members, in the
    // order rank 0 runs them: the region and the published cases (full
    // report), the ladder.
    void work_on_ladder_members(const Scene &scene, const CommonOptions &common, const VerifyOptions &options)
    {
      if (options.full)
        {
          work_on_region_members(scene, RegionRunSettings());
          work_on_case_members(published_case_sites(resolve_scene_path(common.scene_file), common.overrides),
                               RegionRunSettings());
        }
      const ReportLadder ladder = report_ladder(scene, options.full, options.diagnostics);
      work_on_ladder(scene, ladder.rungs, ladder.reference, ladder.settings);
    }

    // Section 4's cases, each as `simulate <scene> --case <name>` runs it.
    CaseRunner simulate_case_runner(const Report &report, const Scene &scene)
    {
      return [&report, &scene](const CaseRun &c) {
        CommonOptions case_common;
        case_common.scene_file = report.scene_file.empty() ? scene.name : report.scene_file;
        case_common.overrides  = report.overrides;
        case_common.output_dir = c.output_dir;
        SimulateOptions simulate;
        simulate.model     = "rom";
        simulate.case_name = c.case_name;
        simulate.end_time  = c.end_time;
        return run_simulation(case_common, simulate, false);
      };
    }

    // The sections in order; --section picks some (a section alone takes
    // what it needs from the scene, none reads another's results).
    std::vector<std::function<void()>> report_sections(VerifyRun &v, const Scene &scene)
    {
      return {[&v, &scene] { add_frequency_section(v.report, scene); },
              [&v, &scene] { add_coefficient_section(v.report, scene, v.options.full); },
              [&v, &scene] { add_backbone_section(v.report, scene, v.options.full); },
              [&v, &scene] { add_contact_section(v.report, scene, v.options.full, v.run_case); },
              [&v, &scene] { add_fe_rom_section(v.report, scene, v.options.full); },
              [&v, &scene] { add_map_section(v.report, scene, v.options.full, time_map_program); },
              [&v, &scene] { add_system1_section(v.report, scene, v.options.full); },
              [&v, &scene] { add_solid_section(v.report, scene, v.options.full); }};
    }

    // A part of another verify: only the sections' text, flushed after
    // each; that verify writes the header, the run record and the rest.
    int run_part_sections(VerifyRun &v)
    {
      if (v.options.sections.empty())
        throw InputError("--part-file (internal: a part of another verify) needs the sections it runs (--section)");
      for (const unsigned int k : v.options.sections)
        {
          v.sections[k - 1]();
          write_text_file(v.options.part_file, v.report.text.str());
        }
      return 0;
    }

    void write_report_header(Report &report, const Scene &scene, const VerifyOptions &options)
    {
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
    }

    void flush_report(const Report &report) { write_text_file(report.dir + "/report.md", report.text.str()); }

    // Between sections, an interruption (Ctrl-C) ends the report with what
    // is complete; the studies inside a section stop at their next step.
    bool end_if_interrupted(Report &report)
    {
      if (!interruption_requested())
        return false;
      report.text << "\n---\n**Interrupted** (signal " << interruption_signal()
                  << "): the sections above are complete, the rest was not run.\n";
      flush_report(report);
      return true;
    }

    // The selected sections in order, section 8 from the second process if
    // it runs there. Each appends to report.md and is flushed to disk before
    // the next starts, so a failure late in the report keeps the earlier
    // ones. False when interrupted: the report then says so and ends.
    bool run_sections(VerifyRun &v)
    {
      Report &report = v.report;
      for (std::size_t k = 0; k < v.sections.size(); ++k)
        {
          if (!selected(v.options, k + 1))
            continue;
          try
            {
              if (k + 1 == 8 && v.solid_process)
                {
                  report.text << finish_section_process(*v.solid_process, v.beside_seconds);
                  v.beside = true;
                }
              else
                {
                  const dealii::TimerOutput::Scope wall_time(v.timer, section_name(k));
                  v.sections[k]();
                }
            }
          catch (const MemberRunsStopped &e)
            {
              // The ladder stopped with a signal: its finished members are kept.
              report.text << "\n_The error ladder " << e.what() << "._\n";
            }
          catch (const Interrupted &e)
            {
              // A solver inside the section stopped (a Newton iteration, the
              // eigensolver, a continuation): what it wrote above is partial.
              report.text << "\n---\n**Interrupted** (signal " << e.signal() << ") in section " << k + 1
                          << ", which is incomplete above; the rest was not run.\n";
              flush_report(report);
              return false;
            }
          v.sections_run.push_back(k);
          flush_report(report);
          if (end_if_interrupted(report))
            return false;
        }
      return true;
    }

    // How this report was made: enough to reproduce it and to read its
    // wall times (run.txt beside it has the exact command line).
    void add_how_made(VerifyRun &v, const unsigned int n_ranks, const double seconds)
    {
      const VerifyOptions &options = v.options;
      Report &report               = v.report;
      report.text << "---\n## How this report was made\n\n"
                  << "- build: " << build_revision() << " (run.txt: the exact command line; parameters.prm: the scene)\n"
                  << "- machine: " << machine_description() << "; " << n_ranks << " MPI rank(s)"
                  << (n_ranks > 1 ? "" : ", the ensembles' members over the cores") << "\n"
                  << "- studies: "
                  << (!options.full ? "quick" : options.diagnostics ? "full with the ladder's diagnostic rungs (`--full --diagnostics`)" : "full (`--full`)")
                  << "\n\n"
                  << "| section | wall time [s] |\n|---|---|\n";
      const std::map<std::string, double> wall_times = v.timer.get_summary_data(dealii::TimerOutput::total_wall_time);
      for (const std::size_t k : v.sections_run)
        {
          const bool beside = k + 1 == 8 && v.beside;
          report.text << "| " << section_name(k) << " | "
                      << fixed(beside ? v.beside_seconds : wall_times.at(section_name(k)), 0)
                      << (beside ? " (beside 1–7)" : "") << " |\n";
        }
      report.text << "| total | " << fixed(seconds, 0) << " |\n";
      if (v.beside)
        report.text << "\nSection 8 ran in a second process beside sections 1–7 (its wall time is its own, from the start "
                       "of the report); the total is the report's.\n";
    }
  } // namespace

  int run_verify(const CommonOptions &common, const VerifyOptions &options)
  {
    MpiSession mpi(launched_by_mpi_launcher());
    const Scene scene = read_scene(resolve_scene_path(common.scene_file), common.overrides);
    const bool ladder_section = selected(options, 5);
    if (mpi.rank() != 0)
      {
        if (ladder_section)
          work_on_ladder_members(scene, common, options);
        return 0;
      }
    // If rank 0 ends before the ladder or its checks' rounds (an error, a
    // stop), the other ranks, waiting for its members, are told to stop.
    const WorkerRelease release(mpi, ladder_section ? (options.full ? 3 : 1) : 0); // region, cases, ladder
    VerifyRun v(options);
    Report &report = v.report;
    if (!options.part_file.empty())
      report.dir = common.output_dir; // the whole verify's folder, which holds its run record
    else
      report.dir = prepare_output_dir(common, scene, "");
    report.scene_file = resolve_scene_path(common.scene_file);
    report.overrides  = common.overrides;
    report.ladder_diagnostics = options.diagnostics;
    const auto start = std::chrono::steady_clock::now();
    v.run_case = simulate_case_runner(report, scene);
    v.sections = report_sections(v, scene);
    if (!options.part_file.empty())
      return run_part_sections(v);
    // Section 8 beside the others, in a second process (see the top).
    if (mpi.size() == 1 && selected(options, 8) && options.sections.size() != 1)
      v.solid_process = start_section_process(8, report, options);

    console() << "beamslider verify: scene '" << scene.name << "', report in " << report.dir
              << (options.full ? " (full studies)" : " (quick studies; --full for the long ones)") << std::endl;
    write_report_header(report, scene, options);
    if (!run_sections(v))
      return interruption_exit_code();

    const double seconds = elapsed_seconds(start);
    add_how_made(v, mpi.size(), seconds);
    flush_report(report);
    // fixed(): a section may leave the console stream at a low precision.
    console() << "Wrote " << report.dir << "/report.md (" << fixed(seconds, 0) << " s)" << std::endl;
    return 0;
  }
} // namespace beamslider
