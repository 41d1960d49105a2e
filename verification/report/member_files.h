// The files of member runs (verification/studies/member_runs.h): each
// finished member of an ensemble, a ladder or the region is appended at
// once (a checked, flushed row) to `member_runs.csv` in the output folder,
// so that a command that is stopped (Ctrl-C, kill -9) and started again the
// same way into the same folder runs only the members not yet there.
//
// member_runs.csv:
//   # <key>   what was asked, and by which build (member_runs_key): the
//             study, beamslider's version and source revision, the scene's
//             content key (model_choice.h), end time, ε, members, and every
//             group's name, model and exact time step
//   group,rung,member,…,n_periods,periods   one row per finished member
// A file with another key is not reused: it is moved aside to
// member_runs.other.csv and the members are run afresh (and the progress
// says so). A row cut short by a kill is dropped and its member run again.
// A convergence check's later rounds keep their members apart, round r in
// member_runs.check-r.csv, so that each round resumes on its own.
#pragma once

#include "verification/studies/member_runs.h"

#include <functional>
#include <memory>
#include <string>

namespace beamslider
{
  // The stores of `file` in `dir` (round 0) and of its rounds r > 0
  // (member_runs.csv → member_runs.check-r.csv); `dir` "": nothing persisted.
  // A file moved aside is said on `on_progress`, after `progress_prefix`.
  std::function<MemberRecordStore(unsigned int round)>
  member_files(const std::string &dir, const std::string &file, const std::string &progress_prefix,
               const std::function<void(const std::string &line)> &on_progress);

  // Counts the check rounds whose store `settings` opens from now on: the
  // highest round r, read once the study ended (0: none beyond the first).
  std::shared_ptr<const unsigned int> count_check_rounds(MemberRunsSettings &settings);

  // After a study that ended (not one that was stopped): the check files of
  // rounds it did not reach are an earlier run's, which went further. Removes
  // `file`'s rounds above `rounds_used` from `dir` (member_runs.check-r.csv
  // for r > rounds_used), so that the folder holds this run's files alone.
  void remove_unreached_check_files(const std::string &dir, const std::string &file, unsigned int rounds_used);

  // The store of FE members shared across studies and reports
  // (MemberRunsSettings::cached, remember): one file a member,
  // `dir`/<scene>/fe_members/<FNV-1a of its key, hex>.csv, holding
  //   # beamslider member, key: <member_cache_key>
  //   <the member record's columns>
  //   <its record>
  // A file whose key line or columns are not exactly these, or that cannot
  // be read, is not used; the member runs and its file is written anew
  // (whole, renamed into place). A file that cannot be written only costs
  // the reuse. ROM members cost little and are not kept.
  void share_fe_members(MemberRunsSettings &settings, const std::string &dir = "reports");

  // What the shared stores of this process have done since it started:
  // members taken from them and members kept in them (for run.txt).
  struct SharedMemberCounts
  {
    std::size_t reused = 0, kept = 0;
    std::string folder; // the last store's folder used
  };
  SharedMemberCounts shared_member_counts();

  // The settings of member runs persisted in `dir`/`file` (see above), with
  // their progress on the console.
  MemberRunsSettings member_files_settings(const std::string &dir, const std::string &study, const MpiSession *mpi,
                                           const std::string &progress_prefix,
                                           const std::string &file = "member_runs.csv");
} // namespace beamslider
