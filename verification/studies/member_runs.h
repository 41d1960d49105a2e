// The member runs of ensembles and ladders (verification/studies/ensemble.h,
// error_ladder.h) handed out by the manager–worker scheme of mpi_cells.h:
// longest first, over the MPI ranks under mpirun, else over threads of the
// one process. Each finished member is appended at once (a checked, flushed
// row) to `member_runs.csv` in the output folder, so that a command that is
// stopped (Ctrl-C, kill -9) and started again the same way into the same
// folder runs only the members not yet there; its results are those of an
// uninterrupted run, bit for bit (every member, new or read back, goes
// through the same record, ensemble.h's member_record).
//
// member_runs.csv:
//   # <key>   what was asked, and by which build: the study, beamslider's
//             version and source revision, the scene's content key
//             (model_choice.h), end time, ε, members, and every group's
//             name, model and exact time step
//   group,rung,member,…,n_periods,periods   one row per finished member
// A file with another key is not reused: it is moved aside to
// member_runs.other.csv and the members are run afresh (and the console
// says so). A row cut short by a kill is dropped and its member run again.
#pragma once

#include "verification/studies/mpi_cells.h"
#include "verification/studies/convergence_check.h"
#include "verification/studies/ensemble.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  struct MemberRunsSettings
  {
    std::string dir;                 // folder of member_runs.csv ("": nothing persisted)
    // The record's name in `dir`: a convergence check's later rounds keep
    // their members apart (member_runs.check-1.csv, …), so that each round
    // resumes on its own.
    std::string file = "member_runs.csv";
    std::string study;               // "ladder", "ensemble": part of the key
    const MpiSession *mpi = nullptr; // nullptr: this process alone
    unsigned int n_threads = 0;      // without MPI: threads (0: one per core)
    std::string progress_prefix;     // before each progress line
    std::size_t *n_kept = nullptr;   // if given: set to the members read back
  };

  // A stop (Ctrl-C, SIGTERM) before every member was done; the finished ones
  // are in member_runs.csv. what() says how many and how to continue.
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
  // runner on rank 0: round r (1, 2, …) persists its members into
  // member_runs.check-r.csv, so that a stopped check resumes round by round.
  MemberGroupRunner check_rounds_runner(const MemberRunsSettings &settings);
  // The broadcast of the rounds' mask from rank 0 (share_round), for
  // run_convergence_checks; without MPI the mask itself.
  std::function<unsigned long(unsigned long)> round_sharer(const MpiSession *mpi);
  // The other ranks' part of those rounds (work_on_convergence_checks with
  // run_member_groups).
  void work_on_check_rounds(const Scene &scene, const std::vector<RefinementPlan> &plans,
                            std::vector<std::size_t> n_done, unsigned int n_members, double perturbation,
                            const MemberRunsSettings &settings);

  // The key line of member_runs.csv for these groups (without the "# ").
  std::string member_runs_key(const std::vector<MemberGroup> &groups, const std::string &study);
} // namespace beamslider
