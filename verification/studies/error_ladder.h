// The error ladder (doc/verification.md §6): between the published reduced
// model and the FE reference, a sequence of models that each change one
// thing, every rung run as an ensemble (ensemble.h) to the end state, and
// every rung compared with the reference rung by the two-sample statistics
// of its outcomes. Single traces part after a few dozen periods; what the
// ladder compares are the distributions of the end state (final x_C/L and
// amplitude) and of the jump time.
//
// A rung's distance to the reference is the Wasserstein distance W₁ of the
// final positions (in x_C/L) with its 90 % bootstrap interval; the
// "spread" is what the ensembles' own scatter gives at this size. A rung is
// "indistinguishable" from the reference when the interval's lower end
// does not exceed the spread.
//
// This study computes and returns results; it writes no files. The report
// (verification/report/report_fe_rom.cc) and `simulate --model auto`
// (model_choice.h) format or use them.
#pragma once

#include "scene/scene.h"
#include "verification/studies/convergence_check.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/fe_rom_study.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace beamslider
{
  struct LadderRung
  {
    std::string name;   // e.g. "ROM N=5 (published)"
    std::string change; // what this rung changes against the one before
    ModelSetting model; // its damped_modes keeps the damped set of the rungs beside it
    // A diagnostic rung (a step of the time-step study, not the published
    // model, a converged ROM or the reference; LadderScope::diagnostics)
    // runs half the ladder's members, at least 2: its W₁ interval is wider,
    // and the ladder with diagnostics costs less (rung_members).
    bool diagnostic = false;
    // The rung claims to be converged in N: the ladder checks it against
    // ⌈1.5 N⌉ modes (convergence_check.h).
    bool converged_in_n = false;
    // The rung is run at Δt/2 too (one halving, convergence_check.h): it
    // is on the speed–accuracy front only if it ends alike there. Not
    // converging is a finding about the model, not a failed claim of the
    // ladder (LadderStudy::proven).
    bool checked_in_dt = false;
    bool front_candidate = false; // a model tried for the front only (add_front_candidates)
  };

  // The number of bending modes the scene's FE mesh has: its free w and θ
  // DoFs, counted as compute_bending_modes counts them (64 on 32 elements).
  unsigned int fe_bending_modes(const Scene &scene);

  // The name of an FE rung: "FE Δt/k" by its step against the scene's
  // (ROM's) Δt, with " θ=…" when θ is not ½.
  std::string fe_step_name(double scene_dt, double fe_dt, double theta);

  // The members rung `rung` runs when the ladder runs `members` per rung.
  unsigned int rung_members(const LadderRung &rung, unsigned int members);

  struct LadderRungResult
  {
    LadderRung rung;
    std::vector<EnsembleMember> members;
    OutcomeStatistics final_position, final_amplitude, jump_time; // x_C/L, [h], [s]
    std::map<std::string, unsigned int> outcome_classes;          // class name → members
    // Against the reference rung (n_a = 0 for the reference itself).
    SampleComparison position_to_reference, amplitude_to_reference;
    double wall_seconds_per_member = 0; // mean over the members [s]
    // The stated cost model (fe_rom_study.h), in units of one step of the
    // published ROM, for one member over the ladder's end time.
    double cost_units = 0;
    unsigned int n_failed = 0; // members whose run failed
  };

  struct LadderStudy
  {
    double end_time      = 0; // [s] simulated per member
    unsigned int members = 0;
    std::size_t reference = 0; // index of the reference rung
    std::vector<LadderRungResult> rungs;
    // What each step of the ladder contributes: rung i−1 against rung i on
    // the final position (steps[0] is empty, n_a = 0).
    std::vector<SampleComparison> steps;
    // The evidence for the reference (in Δt) and for the rung converged in
    // N, in the order of ladder_checks. The reference rung holds the
    // reference check's accepted trial (or, not converged, its finest).
    std::vector<ConvergenceCheck> checks;
    std::vector<std::size_t> check_rungs; // the rung of each check (empty: every check is a claim)
    // Whether check c is a claim of the ladder (the reference in Δt, a rung
    // converged in N) rather than a finding about a rung (its Δt check).
    bool is_claim(std::size_t c) const;
    // Whether every claim converged.
    bool proven() const;
    // The check that refines rung i: in Δt, or else in N (whose ⌈1.5 N⌉
    // modes run at a smaller step too); null if it has none.
    const ConvergenceCheck *refinement_check(std::size_t i) const;
  };

  // The speed–accuracy front: the rungs (not the reference) whose members
  // all ran, whose refinement check (in Δt, or else in N), if they have one,
  // converged, and which no such
  // rung beats on both cost (the stated cost units, fe_rom_study.h) and W₁
  // to the reference. In ascending cost.
  std::vector<std::size_t> speed_accuracy_front(const LadderStudy &study);

  // The checks of a ladder: the reference rung in Δt (Δt, Δt/2, … up to
  // reference_max_halvings), the rung converged in N (if any) against
  // ⌈1.5 N⌉ modes. Each plan's trial 0 is that rung's own ensemble.
  struct LadderChecks
  {
    std::vector<RefinementPlan> plans;
    std::vector<std::size_t> rung; // the rung each plan checks
  };
  LadderChecks ladder_checks(const Scene &scene, const std::vector<LadderRung> &rungs, std::size_t reference);

  // Which rungs a ladder has.
  //   quick        the published ROM (N = scene's, Δt = scene's), the
  //                converged-in-N ROMs (N = 10 at Δt/2, N = 20 at Δt/4: the
  //                explicit step's limit 2/ω_N forces the smaller steps),
  //                two candidates of the speed–accuracy front at their
  //                explicit step's limit (N = 15, and 6 modes with 4 static
  //                corrections: doc/verification.md §6) and the reference:
  //                the scene's own FE model (its FE time step and θ; on
  //                mueller2023 θ = 0.51 at Δt/2, which ends where the
  //                midpoint-rule FE converged in Δt ends, doc/findings.md);
  //   front        the verdict of `verify --full`: adds the ROM N = 20 with
  //                the FE's implicit midpoint rule and every candidate of the
  //                front, ROMs of 6, 8, 12 and 15 modes, 5…8 modes with 4
  //                static corrections, 6 + 4 grown by a block of
  //                load-dependent Ritz vectors, and N = 10 and 15 implicit
  //                at Δt with the FE's θ (when it is above ½);
  //   diagnostics  adds to the front's ladder, as diagnostic rungs, the
  //                implicit ROM with every bending mode of the FE mesh at
  //                Δt/4 and the midpoint-rule FE (θ = ½) at Δt/4, Δt/8, Δt/2
  //                and Δt, all damping the scene's N: the plateau the
  //                undamped high modes put the midpoint rule on, shared by
  //                the ROM with all modes. They explain the choice of the
  //                reference and cost as much again as the rest of the full
  //                ladder, so they run only when asked (`verify --full
  //                --diagnostics`, `ladder --diagnostics`);
  //   every        every rung there is, the pool `ladder --rung` picks from.
  // On every scope each explicit ROM rung but the one converged in N runs at
  // Δt/2 too (checked_in_dt).
  enum class LadderScope
  {
    quick,
    diagnostics,
    front,
    every
  };

  // The default ladder for a scene at that scope. The reference is always
  // the last rung.
  std::vector<LadderRung> default_ladder(const Scene &scene, LadderScope scope, std::size_t &reference);

  // Every rung's ensemble as one list of member runs (ensemble.h): rung i
  // is group i, `members` members over [0, end_time], ε = 1e-9.
  std::vector<MemberGroup> ladder_groups(const Scene &scene, const std::vector<LadderRung> &rungs, double end_time,
                                         unsigned int members);
  // The ladder's groups and, after them, trials 1 … first_round_size − 1
  // of every check in check order (the first refinement, and a witness, run
  // beside the rungs, in the same list).
  std::vector<MemberGroup> ladder_groups_with_checks(const Scene &scene, const std::vector<LadderRung> &rungs,
                                                     const LadderChecks &checks, double end_time, unsigned int members);
  // The checks' first trials out of the results of those groups: per
  // check, its rung's members and the trials that ran beside the rungs;
  // `results` keeps the rungs' groups only.
  std::vector<std::vector<std::vector<EnsembleMember>>>
  first_check_trials(std::vector<std::vector<EnsembleMember>> &results, std::size_t n_rungs, const LadderChecks &checks);
  // How many trials of each check the first list ran (for the other ranks).
  std::vector<std::size_t> first_trial_counts(const LadderChecks &checks);

  // Runs every rung as an ensemble of `members` members over [0, end_time]:
  // all members of all rungs, with the first refinement of every check, as
  // one list, longest first (in threads of this process, or by `runner`:
  // spread over MPI ranks and persisted, see verification/studies/member_runs.h);
  // then the checks' further rounds, if any, by `rounds` (default: as the
  // first list) in step with the other ranks by `share`
  // (run_convergence_checks). `before_rung` (optional) announces each rung,
  // in ladder order, before the runs start.
  LadderStudy run_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, std::size_t reference,
                         double end_time, unsigned int members,
                         const std::function<void(const LadderRung &, std::size_t)> &before_rung = {},
                         const MemberGroupRunner &runner = {}, const MemberGroupRunner &rounds = {},
                         const std::function<unsigned long(unsigned long)> &share = {});

  // The study from the members of every rung (members[i]: rung i's):
  // statistics, comparisons with the reference and between neighbours.
  LadderStudy assemble_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, std::size_t reference,
                              double end_time, std::vector<std::vector<EnsembleMember>> members);
  // The same after the checks: the reference rung takes the reference
  // check's accepted trial (model, name and members) before the comparisons.
  LadderStudy assemble_ladder(const Scene &scene, std::vector<LadderRung> rungs, std::size_t reference,
                              double end_time, std::vector<std::vector<EnsembleMember>> members,
                              std::vector<ConvergenceCheck> checks, const LadderChecks &plans);
} // namespace beamslider
