// Ensembles: the same run K times, the members differing only by a tiny,
// reproducible perturbation of the initial slider position (member m starts
// at x_C/L + m·ε). The rattling slider makes single traces chaotic — runs
// that differ in round-off part after a few dozen periods, the jump time
// moves by seconds — while the outcomes (jump, turn, end state) are
// attractors of the slow dynamics. A model is therefore judged by the
// distribution of its outcomes over the members, and two models by a
// two-sample comparison of those distributions (compare_samples).
//
// Outcomes per member come from the one trace analysis
// (runs/trace_analysis.h) with the scene's thresholds.
#pragma once

#include "runs/adaptation_run.h"
#include "runs/trace_analysis.h"
#include "scene/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace beamslider
{
  struct EnsembleSettings
  {
    ModelSetting model;         // family, modes or elements, Δt
    unsigned int n_members = 8; // K
    double perturbation = 1e-9; // ε, shift of x_C/L per member index [-]
    unsigned int n_threads = 0; // 0: the machine's cores
  };

  struct EnsembleMember
  {
    unsigned int index  = 0;
    double perturbation = 0; // m·ε [-]
    RunResult result;
    TraceAnalysis analysis;
    std::vector<PeriodRecord> periods;
    double wall_seconds = 0; // model set-up + run
  };

  // One member as a unit of work: `scene` (its end time is the member's)
  // with the model's time step, started at x_C/L + index·perturbation. The
  // same arguments give the same member on any thread or MPI rank. Safe to
  // call from several threads (the model set-up, whose eigensolver is not
  // thread-safe, runs one at a time).
  EnsembleMember run_member(const Scene &scene, const ModelSetting &model, unsigned int index, double perturbation);

  // The members of several ensembles (the rungs of a ladder, or one
  // ensemble) as one list of runs.
  struct MemberGroup
  {
    std::string name;       // the rung's name ("" for a lone ensemble)
    Scene scene;            // end time set; the time step is the model's
    ModelSetting model;
    unsigned int n_members = 0;
    double perturbation    = 0; // ε [-]
    // Member m of the group is member first_member + m of its ensemble
    // (start x_C/L + (first_member + m)·ε): more members of an ensemble
    // that ran members 0 … first_member − 1 before.
    unsigned int first_member = 0;
  };
  // Member m of a group (counting from 0 in the group): member
  // group.first_member + m of its ensemble.
  EnsembleMember run_member(const MemberGroup &group, unsigned int m);
  // Member m of group g is run number offset(g) + m of the list (m counts
  // from 0 in every group; its member index is first_member + m).
  std::size_t n_runs(const std::vector<MemberGroup> &groups);
  std::pair<std::size_t, unsigned int> group_and_member(const std::vector<MemberGroup> &groups, std::size_t run);
  // The runs longest first by the stated cost model (cost_per_simulated_second
  // × end time; fe_rom_study.h), ties in list order: handed out in this
  // order, runs of very different cost keep every worker busy to the end.
  std::vector<std::size_t> longest_first(const std::vector<MemberGroup> &groups);

  // A finished member as the cells of one CSV row and back, bit for bit
  // (doubles in their shortest round-trip form): the status and figures of
  // the run, and each period's index, start, end, mean x_C/L and amplitude,
  // each period ended by ';'
  // (what the trace analysis and the output files read; the energy budget
  // of the periods is not kept). The analysis is recomputed from them with
  // the scene's thresholds. Every member of a persisted study goes through
  // this record, the one just computed as much as the one read back, so that
  // a resumed study gives the numbers of an uninterrupted one.
  std::vector<std::string> member_record_columns();
  std::vector<std::string> member_record(std::size_t group, const std::string &group_name, const EnsembleMember &m);
  // Throws std::invalid_argument for a row that is not a complete record (a
  // line cut short by a kill).
  EnsembleMember member_from_record(const std::vector<std::string> &cells, const TraceThresholds &thresholds,
                                    std::size_t &group, std::string &group_name);

  // Runs every member of every group and returns members[group][m]. The
  // default runs them in threads of this process; a command that persists
  // members or spreads them over MPI ranks passes its own.
  using MemberGroupRunner =
    std::function<std::vector<std::vector<EnsembleMember>>(const std::vector<MemberGroup> &groups)>;
  // In `n_threads` threads (0: one per core), longest first; `on_member`
  // (optional) is called, serialised, as each finishes.
  std::vector<std::vector<EnsembleMember>>
  run_groups_in_threads(const std::vector<MemberGroup> &groups, unsigned int n_threads = 0,
                        const std::function<void(std::size_t, const EnsembleMember &)> &on_member = {});

  // The members of one ensemble (in threads, or by `runner`); `on_member`
  // (optional, threads only) is called, serialised, as each finishes.
  std::vector<EnsembleMember> run_ensemble(const Scene &scene, const EnsembleSettings &settings,
                                           const std::function<void(const EnsembleMember &)> &on_member = {},
                                           const MemberGroupRunner &runner = {});

  // Order statistics of one outcome over the members where it exists.
  struct OutcomeStatistics
  {
    std::string name;
    std::size_t n = 0; // members with the event (all for end states)
    double median = 0, q1 = 0, q3 = 0, min = 0, max = 0;
  };
  // Quantile q of the sample by linear interpolation between order
  // statistics (Hyndman & Fan type 7); the sample need not be sorted.
  double quantile(std::vector<double> sample, double q);
  OutcomeStatistics statistics(const std::string &name, const std::vector<double> &sample);

  // The outcomes of the members as samples: jump time [s] (members that
  // jumped), turn position x_C/L (members that turned), final x_C/L and
  // amplitude [h] (all). A member that failed (diverged, its solver failed:
  // no result, ends_in_a_result) or has too few periods to analyse gives
  // none: where a run broke down is not an end state.
  struct OutcomeSamples
  {
    std::vector<double> jump_time, turn_position, final_position, final_amplitude;
  };
  OutcomeSamples outcome_samples(const std::vector<EnsembleMember> &members);

  // Two-sample comparison of one outcome between ensembles A and B:
  //   shift        median(B) − median(A);
  //   wasserstein  W₁ = ∫|F_A − F_B| dx, the mean distance mass must move
  //                (for B = A + s exactly |s|), in the outcome's unit;
  //   ks           Kolmogorov–Smirnov D = sup|F_A − F_B| ∈ [0, 1];
  //   interval     a 90 % bootstrap percentile interval of W₁ (resampling
  //                each ensemble with replacement, fixed seed);
  //   spread       W₁ between the two halves of A and of B (the larger): what
  //                the ensembles' own scatter gives at this size.
  // "Indistinguishable at this ensemble size" when the interval's lower end
  // does not exceed the spread.
  struct SampleComparison
  {
    std::size_t n_a = 0, n_b = 0;
    double shift = 0, wasserstein = 0, ks = 0, interval_low = 0, interval_high = 0, spread = 0;
    bool distinguishable = false;
  };
  double wasserstein_1(std::vector<double> a, std::vector<double> b);
  double kolmogorov_smirnov(std::vector<double> a, std::vector<double> b);
  SampleComparison compare_samples(const std::vector<double> &a, const std::vector<double> &b,
                                   unsigned int n_bootstrap = 2000, unsigned int seed = 1);
} // namespace beamslider
