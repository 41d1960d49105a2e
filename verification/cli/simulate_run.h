// The state of one `simulate` run and its checkpoint record, shared by the
// command (command_simulate.cc) and its checkpoints (simulate_checkpoint.cc).
#pragma once

#include "io/checkpoint.h"
#include "io/csv_writer.h"
#include "runs/adaptation_run.h"
#include "verification/cli/commands.h"
#include "verification/studies/fe_rom_study.h"
#include "verification/studies/simulation_cases.h"

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace beamslider
{
  namespace internal
  {
    // What a checkpoint must say besides the run's state: how the run was
    // asked for (so that --resume rebuilds the same model), where its files
    // end, and the period records the verdict needs.
    struct RunDescription
    {
      std::string scene_file; // absolute
      std::uint64_t scene_hash = 0;
      std::vector<std::string> overrides;
      std::string case_name;
      ModelSetting setting;
      double end_time = 0;
      std::string why;
      // What defines the run (format 3): the command, the model and the
      // scene as parameters.prm holds it, and its digest.
      std::string identity, scene_text;
      std::uint64_t identity_digest = 0;
      std::uint64_t trace_bytes = 0, period_bytes = 0; // file sizes at the checkpoint
      // FNV-1a of those bytes (format 3): a resume checks that the files it
      // continues are the ones the checkpoint's run wrote.
      std::uint64_t trace_digest = 0, period_digest = 0;
      std::uint64_t n_steps     = 0;
      double wall_seconds       = 0;
      std::vector<PeriodRecord> periods;
    };

    // The length and FNV-1a digest of a file's first bytes, extended to its
    // end as the run writes it: at each checkpoint only the new bytes are
    // read.
    struct FileDigest
    {
      std::uint64_t bytes = 0;
      std::uint64_t hash  = fnv1a("");
    };

    // The state of one `simulate` run, shared by its stages: the options
    // (with --resume, those of the checkpoint's run), the checkpoint it
    // continues, the scene, what defines the run, and what it has written.
    struct SimulationRun
    {
      CommonOptions common;
      SimulateOptions options;
      bool resuming = false;
      std::optional<CheckpointReader> checkpoint; // --resume: read up to the run's state
      RunDescription saved;                       // --resume: the checkpoint's run
      std::string scene_file;                     // absolute
      const SimulationCase *the_case = nullptr;
      std::vector<std::string> modified; // the case's own parameters the user changed
      // What defines this run, as its checkpoints record it: the scene as
      // parameters.prm holds it, and (for the digest) without its end time.
      std::string command_label, scene_text, timeless_scene_text;
      FileDigest trace_digest, period_digest; // of the files' bytes up to the last checkpoint
      std::chrono::steady_clock::time_point start; // of the time stepping
      SimulationOutcome outcome; // the scene, model, folder, result and period records
    };

    // trace.csv and periods.csv of a run (command_simulate.cc).
    struct RunCsvFiles
    {
      RunCsvFiles(const std::string &dir, const bool append);
      CsvWriter trace, periods;
    };

    // The run's identity, what a resumed run must share with the run it
    // continues (simulate_checkpoint.cc).
    std::string run_identity(const std::string &command, const ModelSetting &setting, const std::string &scene_text);

    // The checkpoint's run to resume (the stages of simulate_checkpoint.cc).
    void load_checkpoint_to_resume(SimulationRun &r);
    void check_checkpoint_is_folders_run(const SimulationRun &r);
    void restore_checkpointed_run(SimulationRun &r, AdaptationRun &run);

    // checkpoint.bin of the run so far (simulate_checkpoint.cc).
    void write_checkpoint(SimulationRun &r, const AdaptationRun &run, RunCsvFiles &files, const std::uint64_t n_steps);
  } // namespace internal
} // namespace beamslider
