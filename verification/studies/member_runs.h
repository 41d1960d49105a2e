// The member runs of ensembles and ladders (verification/studies/ensemble.h,
// error_ladder.h) handed out by the manager–worker scheme of mpi_cells.h:
// longest first, over the MPI ranks under mpirun, else over threads of the
// one process. Each finished member is handed at once to the caller's store
// (MemberRecordStore: verification/report/member_files.h keeps it as a row of
// member_runs.csv), so that a command that is stopped (Ctrl-C, kill -9) and
// started again the same way runs only the members not yet there; its
// results are those of an uninterrupted run, bit for bit (every member, new
// or read back, goes through the same record, ensemble.h's member_record).
//
// A record is the cells of member_record, kept under a key: what was asked,
// and by which build (member_runs_key). The store hands back the records
// kept under that key; one that is not a whole record of a member of these
// groups (a row cut short by a kill) is dropped and its member run again.
// Nothing here writes or prints: progress lines go to the settings'
// on_progress.
#pragma once

#include "runtime/mpi_cells.h"
#include "verification/studies/convergence_check.h"
#include "verification/studies/ensemble.h"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // Where the finished members of one run_member_groups are kept.
  struct MemberRecordStore
  {
    // Where the records are, for the progress and stop messages.
    std::string name;
    // Opens the records of `key` (cells of `columns`): hands each record
    // kept earlier under that key to `take`, keeps those it accepts and
    // drops the others (records of another key are set aside), then takes
    // appends.
    std::function<void(const std::string &key, const std::vector<std::string> &columns,
                       const std::function<bool(const std::vector<std::string> &record)> &take)>
      open;
    // Persists one finished member's record at once (throws if it cannot).
    std::function<void(const std::vector<std::string> &record)> append;
    // No more rows (throws if the last ones could not be written).
    std::function<void()> close;
  };

  struct MemberRunsSettings
  {
    // The store of the members (round 0) and of a convergence check's
    // later rounds r = 1, 2, … (check_rounds_runner), which keep their
    // members apart so that each round resumes on its own. Empty: nothing
    // persisted.
    std::function<MemberRecordStore(unsigned int round)> records;
    std::string study;               // "ladder", "ensemble": part of the key
    const MpiSession *mpi = nullptr; // nullptr: this process alone
    unsigned int n_threads = 0;      // without MPI: threads (0: one per core)
    std::string progress_prefix;     // before each progress line
    // Each progress line (prefix included, without '\n'); empty: none.
    std::function<void(const std::string &line)> on_progress;
    std::size_t *n_kept = nullptr;   // if given: set to the members read back (not those of `cached`)
    // A store of single members shared by every study that runs the same
    // member, whatever its group's name or study (the FE references the
    // region, the published cases and the ladder of a report have in
    // common, and a later report's): `cached` gives the record kept under a
    // member's own key (member_cache_key) or nothing, `remember` keeps a
    // finished member's record. Either may decline a group (the file store
    // keeps FE members only). Empty: none.
    std::function<std::optional<std::vector<std::string>>(const MemberGroup &group, const std::string &key)> cached;
    std::function<void(const MemberGroup &group, const std::string &key, const std::vector<std::string> &record)>
      remember;
  };

  // A stop (Ctrl-C, SIGTERM) before every member was done; the finished ones
  // are in the store. what() says how many and how to continue.
  class MemberRunsStopped : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // Every rank calls it with the same groups. On rank 0 (and without MPI):
  // every member, members[group][m], read back or computed; throws
  // MemberRunsStopped if stopped first. On the other ranks: computes the
  // members rank 0 hands out and returns nothing.
  std::vector<std::vector<EnsembleMember>> run_member_groups(const std::vector<MemberGroup> &groups,
                                                             const MemberRunsSettings &settings);

  // run_member_groups as a runner for run_ensemble / run_ladder (rank 0).
  MemberGroupRunner member_runs_runner(const MemberRunsSettings &settings);

  // The later rounds of convergence checks (convergence_check.h) as a
  // runner on rank 0: round r (1, 2, …) persists its members into the
  // settings' records(r), so that a stopped check resumes round by round.
  MemberGroupRunner check_rounds_runner(const MemberRunsSettings &settings);
  // The broadcast of the rounds' mask from rank 0 (share_round), for
  // run_convergence_checks; without MPI the mask itself.
  std::function<unsigned long(unsigned long)> round_sharer(const MpiSession *mpi);
  // The other ranks' part of those rounds (work_on_convergence_checks with
  // run_member_groups).
  void work_on_check_rounds(const Scene &scene, const std::vector<RefinementPlan> &plans,
                            std::vector<std::size_t> n_done, unsigned int n_members, double perturbation,
                            const MemberRunsSettings &settings);

  // The key of the members' record for these groups: the study,
  // beamslider's version and source revision, and every group's name,
  // scene (with its content key, model_choice.h), model and exact time
  // step, end time, members and perturbation; one line.
  std::string member_runs_key(const std::vector<MemberGroup> &groups, const std::string &study);
  // The key of one member of `group` in a shared store: beamslider's
  // version, source revision and the executable's identity (its size and
  // modification time: a rebuild is another build), the scene's name and
  // content key, every field of the model setting with exact numbers, the
  // end time, ε and the member's index. Not the group's name or the study:
  // the same member asked by two studies is one.
  std::string member_cache_key(const MemberGroup &group, unsigned int member);
} // namespace beamslider
