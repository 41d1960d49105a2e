// `beamslider ladder`: the error ladder of report section 5 on its own. Each
// rung is a model setting run as an ensemble; every rung is compared with
// the reference (the scene's FE model) and with the rung before it. Writes
// member_runs.csv (each member as it finishes), ladder.csv,
// ladder_members.csv, ladder_steps.csv, ladder.png and summary.md
// (the same tables and verdict as the report). Under `mpirun -n P` the
// members run on P ranks; stopped and started again the same way into the
// same folder, it runs only the members not yet in member_runs.csv
// (verification/studies/member_runs.h).
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/study_results.h"
#include "numerics/elapsed.h"
#include "verification/studies/number_text.h"
#include "verification/studies/member_runs.h"
#include "verification/report/report_ladder.h"
#include "io/console.h"
#include "verification/studies/error_ladder.h"

#include "io/interruption.h"
#include "io/output_file.h"

#include <iostream>

#include <sstream>

namespace beamslider
{
  namespace
  {
    // The rungs asked for by name, in ladder order, with the reference.
    std::vector<LadderRung> pick_rungs(const std::vector<LadderRung> &full, const std::size_t full_reference,
                                       const std::vector<std::string> &names, std::size_t &reference)
    {
      for (const std::string &name : names)
        {
          bool known = false;
          for (const LadderRung &r : full)
            known = known || r.name == name;
          if (!known)
            {
              std::string list;
              for (const LadderRung &r : full)
                list += (list.empty() ? "'" : ", '") + r.name + "'";
              throw InputError("--rung '" + name + "' is not a rung of this scene's ladder; the rungs are " + list);
            }
        }
      std::vector<LadderRung> picked;
      for (std::size_t i = 0; i < full.size(); ++i)
        {
          bool wanted = i == full_reference;
          for (const std::string &name : names)
            wanted = wanted || full[i].name == name;
          if (!wanted)
            continue;
          if (i == full_reference)
            reference = picked.size();
          picked.push_back(full[i]);
          picked.back().diagnostic = false; // rungs picked by name run --members each
        }
      return picked;
    }
  } // namespace

  int run_ladder_command(const CommonOptions &common, const LadderOptions &options, StudyHandover *handover)
  {
    // Under mpirun every rank runs this; only rank 0 writes and prints.
    MpiSession mpi(launched_by_mpi_launcher());
    const Scene scene = read_command_scene(common, "");
    // --diagnostics implies the full ladder; rungs picked by name
    // come from every rung there is.
    const bool full = options.full || options.diagnostics || !options.rungs.empty();
    const LadderScope scope = !options.rungs.empty() ? LadderScope::every : ladder_scope(full, options.diagnostics);
    std::size_t reference         = 0;
    std::vector<LadderRung> rungs = default_ladder(scene, scope, reference);
    if (!options.rungs.empty())
      rungs = pick_rungs(rungs, reference, options.rungs, reference);

    // Rungs picked by name keep the quick length unless --full is given.
    LadderRunSettings settings = ladder_run_settings(options.full || options.diagnostics);
    settings.members           = options.members.value_or(settings.members);
    settings.end_time          = options.end_time.value_or(settings.end_time);
    settings.quick_ladder      = !full;
    settings.progress_prefix   = "ladder: ";
    if (mpi.rank() != 0)
      {
        work_on_ladder(scene, rungs, reference, settings);
        return 0;
      }
    const WorkerRelease release(mpi); // the other ranks stop with this one, however it ends
    const bool write_kept = handover && handover->mode == StudyHandover::Mode::write;
    if (write_kept)
      require_same_scene(std::any_cast<const LadderRun &>(handover->result).scene, scene, "ladder");
    const std::string dir = handover && !write_kept ? std::string() : prepare_output_dir(common, scene, "ladder");

    std::ostringstream md;
    md << "# Error ladder of scene `" << scene.name << "`\n\n"
       << "Written by `beamslider ladder`" << (options.diagnostics ? " --diagnostics" : options.full ? " --full" : "") << ": " << rungs.size() << " rungs × "
       << settings.members << " members over " << settings.end_time << " s. The same study as report section 5.1–5.2 "
       << "(doc/verification.md §6).\n\n";
    bool proven = true;
    try
      {
        if (write_kept)
          {
            // The ladder computed before, from the same options (python/study_bindings.cc).
            const LadderRun &kept = std::any_cast<const LadderRun &>(handover->result);
            proven                = kept.study.proven();
            md << write_and_describe_ladder(dir, scene, rungs, kept.study, settings, 0,
                                            fixed(kept.wall_seconds, 0) + " s");
          }
        else if (handover)
          {
            const auto start  = std::chrono::steady_clock::now();
            std::size_t n_kept = 0;
            LadderRun run{scene, rungs, settings, run_ladder_study("", scene, rungs, reference, settings, n_kept), 0};
            run.wall_seconds = elapsed_seconds(start);
            handover->result = std::move(run);
            return 0;
          }
        else
          md << run_and_describe_ladder(dir, scene, rungs, reference, settings, &proven);
      }
    catch (const MemberRunsStopped &e)
      {
        std::cerr << "ladder: " << e.what() << std::endl;
        return interruption_exit_code();
      }
    write_text_file(dir + "/summary.md", md.str());
    console() << "wrote " << dir << "/summary.md, ladder.csv, ladder_members.csv, ladder_steps.csv, ladder.png"
              << std::endl;
    if (!proven)
      {
        std::cerr << "ladder: a convergence check did not converge; the results are written and marked (" << dir
                  << "/summary.md, convergence.csv)" << std::endl;
        return not_converged_exit_code;
      }
    return 0;
  }
} // namespace beamslider
