// The error ladder as report section 5.1–5.2 and the `beamslider ladder`
// command show it: run_and_describe_ladder runs the rungs, writes the files
// and returns the Markdown. The members of all rungs run as one list, longest
// first, over the MPI ranks under mpirun, else over the cores
// (verification/studies/member_runs.h); each finished member is appended to
// member_runs.csv at once, so that a ladder stopped (Ctrl-C, kill -9) and
// started again into the same folder runs only the members not there yet and
// ends with the same files. The tables are written when every member is done:
//   member_runs.csv     every finished member (the resume record)
//   ladder.csv          one row per rung (index = place in the ladder):
//                       settings, cost, outcome statistics, W₁ to the reference
//   ladder_members.csv  one row per rung and member (the trace analysis)
//   ladder_steps.csv    each step of the ladder: rung i−1 against rung i
//   ladder.png          final x_C/L of every member per rung; speed against
//                       accuracy (cost against W₁ with its interval)
// Columns are listed in doc/verification.md §6.
#pragma once

#include "io/csv_writer.h"
#include "verification/studies/error_ladder.h"

#include <string>
#include <vector>

namespace beamslider
{
  class LadderFiles
  {
  public:
    // Creates ladder.csv and ladder_members.csv in `dir` with their headers.
    explicit LadderFiles(const std::string &dir);

    // The rows of one finished rung; `index` is its place in the ladder.
    void add_rung(const LadderRungResult &rung, std::size_t index, bool is_reference);

    // ladder_steps.csv of a finished ladder.
    void write_steps(const LadderStudy &study) const;

  private:
    std::string dir_;
    CsvWriter rungs_, members_;
  };

  struct LadderRunSettings
  {
    double end_time      = 25.; // [s] simulated per member
    unsigned int members = 4;
    // The rungs are the quick ladder: the text says what `verify --full` adds.
    bool quick_ladder = false;
    // Heading numbers: "5." gives "### 5.1 …" and "### 5.2 …" (the report),
    // "" gives "## …" (a summary of its own).
    std::string numbering;
    std::string progress_prefix; // before each progress line on the console
    // Where FE members are shared with other studies and reports
    // (member_files.h, share_fe_members); "": not shared.
    std::string shared_members_root;
  };

  // Runs `rungs` (reference: rungs[reference]) as ensembles into `dir`
  // (member_runs.csv, LadderFiles and ladder.png) and returns the Markdown:
  // the headline table of every rung against the reference, the evidence of
// the reference's convergence checks (convergence.csv), the verdict on
  // the end state, and what each step of the ladder contributes (computed
  // from this run). Throws MemberRunsStopped (member_runs.h) when stopped
  // before every member is done. Under MPI this is rank 0's part.
  // `proven` (optional) is set to whether every convergence check converged.
  std::string run_and_describe_ladder(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                                      std::size_t reference, const LadderRunSettings &settings,
                                      bool *proven = nullptr);

  // Its two halves, for a ladder computed in one call and written in
  // another (the command's StudyHandover): the members run (member_runs.csv
  // in `dir`; "" persists nothing), with the progress on the console; and
  // the files of that study into `dir` with the Markdown, `took` the wall
  // time as the text says it.
  LadderStudy run_ladder_study(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                               std::size_t reference, const LadderRunSettings &settings, std::size_t &n_kept);
  std::string write_and_describe_ladder(const std::string &dir, const Scene &scene, const std::vector<LadderRung> &rungs,
                                        const LadderStudy &study, const LadderRunSettings &settings,
                                        std::size_t n_kept, const std::string &took);

  // The other MPI ranks' part of run_and_describe_ladder (same arguments
  // but the folder): compute the members rank 0 hands out.
  void work_on_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, std::size_t reference,
                      const LadderRunSettings &settings);

  // Which rungs: the quick ladder unless `full`; its diagnostic rungs too
  // when `diagnostics` (which needs `full`).
  LadderScope ladder_scope(bool full, bool diagnostics);

  // Members and simulated time per member: 8 over 40 s for the full-length
  // ladder (`--full`), 4 over 25 s otherwise.
  LadderRunSettings ladder_run_settings(bool full_length);

  // The ladder of report section 5: quick (4 rungs, 4 members over 25 s),
  // full (`verify --full`: 5 rungs, 8 members over 40 s) or full with the
  // diagnostic rungs (`verify --full --diagnostics`).
  struct ReportLadder
  {
    std::vector<LadderRung> rungs;
    std::size_t reference = 0;
    LadderRunSettings settings;
  };
  ReportLadder report_ladder(const Scene &scene, bool full, bool diagnostics);
} // namespace beamslider
