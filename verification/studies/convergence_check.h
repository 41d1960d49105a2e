// A reference that proves itself: wherever beamslider takes a model as the
// reference (the FE in `ensemble --model fe`, the ladder's reference rung,
// the model choice, the report), it runs the same ensemble once more with
// the model refined, and accepts the model only when the refined ensemble
// ends where it ends, within the ensembles' own spread (the ladder's test:
// the 90 % bootstrap interval of W₁ between the final positions starts at
// or below the spread, ensemble.h's compare_samples).
//
//   in Δt  the FE (or any model) at Δt, Δt/2, Δt/4, … up to a stated number
//          of halvings: the accepted step is the first whose half ends where
//          it ends;
//   in N   a ROM that claims to be converged in its modes against ⌈1.5 N⌉
//          modes (at the largest step Δt/2^k its explicit scheme takes):
//          one refinement, since each costs more than the last.
// A check that runs out of refinements is "not converged", with the
// numbers; it never passes silently.
//
// The reference's check in Δt judges the sequence of steps, not one pair:
// an FE contact step converges so slowly in Δt (observed order ~0.3 at one
// region point) that two neighbouring steps can end within the members'
// spread while the end state still drifts by several times that spread.
// So the plan runs one coarser step beside the pair (2Δt, the "witness",
// half the cost of Δt), and a step is accepted only when, from its coarser
// and its finer neighbour,
//   - the pair with its finer neighbour ends alike (as above), and
//   - the observed order p = log₂(|x(2h) − x(h)| / |x(h) − x(h/2)|) of the
//     members' median end state is at least minimum_extrapolation_order,
//     and Richardson's estimate of the step's remaining error,
//     |x(h) − x(h/2)| · 2^p / (2^p − 1), is within the tolerance: the
//     larger of the pair's spread and convergence_resolution.
// Differences all below convergence_resolution are no drift at all. The
// witness is never accepted: it is only evidence.
//
// Members: the medians' differences carry the members' scatter, about
// 1.8 s/√n for n members of standard deviation s (the median's standard
// error 1.25 s/√n, twice); with 8 members that is 0.6 s, so a drift
// shows as an order only where each difference is above roughly the
// spread, and noise makes the ratio of two small differences anything.
// A noisy ratio that falls below the minimum order refuses a step that was
// perhaps converged (one more halving is run, never a wrong acceptance);
// one that rises above it underestimates the error by at most the noise.
//
// Every trial is an ensemble of the same members (start x_C/L + m·ε), so a
// trial's members are reused: the model's own ensemble is trial 0, and the
// commands run trial 1 beside it, in the same list of member runs.
#pragma once

#include "scene/scene.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/fe_rom_study.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  // How a model is refined, and how often at most.
  struct RefinementPlan
  {
    std::string name;      // e.g. "FE reference in Δt"
    std::string parameter; // "Δt" | "N"
    // The models in the order they run: models[0] is the model under test,
    // then its refinements (and, judged by order, the witness 2Δt third).
    std::vector<ModelSetting> models;
    // Judged by the sequence of steps (observed order and extrapolated
    // remaining error, above) instead of by one pair.
    bool judged_by_order = false;
  };

  // Halvings of the model's step: models Δt, Δt/2, …, Δt/2^max_halvings,
  // judged by pairs (the front's check of a rung at Δt/2).
  RefinementPlan step_refinements(const std::string &name, const ModelSetting &model, unsigned int max_halvings);

  // The reference's plan, judged by order: Δt, Δt/2, then the witness 2Δt,
  // then Δt/4, …, Δt/2^max_halvings (max_halvings ≥ 1).
  RefinementPlan step_sequence(const std::string &name, const ModelSetting &model, unsigned int max_halvings);

  // Below this observed order in Δt the extrapolated error is not trusted
  // (2^p/(2^p − 1) > 3.4 times the last difference): "not converged".
  constexpr double minimum_extrapolation_order = 0.5;

  // The ROM at its own step if its explicit scheme takes it, else at the
  // largest Δt/2^k within the limit 2/ω_max on `scene` (read off the model;
  // the implicit ROM and the FE as they are).
  ModelSetting at_stable_step(const Scene &scene, ModelSetting model);

  // The ROM with ⌈1.5 N⌉ modes, at the largest step Δt/2^k (k ≥ 0) within
  // the explicit scheme's limit 2/ω_max on `scene` (the implicit ROM keeps
  // Δt).
  ModelSetting more_modes(const Scene &scene, const ModelSetting &rom);
  RefinementPlan mode_refinements(const std::string &name, const Scene &scene, const ModelSetting &rom);

  // Differences of the end position below this are taken as none, whatever
  // the spread [x_C/L]: early in a run, before the rattling has spread the
  // members, the spread is ~0 and the interval test alone would call a
  // shift of 1e-6 L a difference. A thousandth of the beam is below every
  // end-state difference the report draws a conclusion from.
  constexpr double convergence_resolution = 1e-3;

  // The halvings of the FE step a reference check tries at most: the FE
  // at Δt, Δt/2 and Δt/4 (a member at Δt/4 costs four at Δt), with the
  // witness 2Δt beside them.
  constexpr unsigned int reference_max_halvings = 2;

  struct ConvergenceTrial
  {
    ModelSetting model;
    std::vector<EnsembleMember> members;
    OutcomeStatistics final_position, final_amplitude; // x_C/L, [h]
    double wall_seconds_per_member = 0;
    // This trial against the next refinement (n_a = 0 for the last trial).
    SampleComparison position_to_next, amplitude_to_next;
    bool witness = false; // the coarser step of a plan judged by order
    // Judged by order, from its coarser and finer neighbours (NaN where not
    // estimated): the observed order in Δt, Richardson's remaining error of
    // this trial's median end state and the tolerance it is held to [x_C/L].
    double observed_order = std::nan(""), remaining_error = std::nan(""), tolerance = std::nan("");
  };

  struct ConvergenceCheck
  {
    std::string name, parameter;
    std::vector<ConvergenceTrial> trials; // coarsest first
    bool decided   = false; // converged, or no refinement left
    bool converged = false;
    std::size_t accepted = 0; // converged: the trial whose refinement ends where it ends
    // The trial a study should use: the accepted one, or the finest tried.
    const ConvergenceTrial &reference() const;
    // One sentence with the numbers: where it converged, or that it did not.
    std::string verdict() const;
  };

  // Whether two trials end alike: the W₁ interval of their final positions
  // starts at or below the spread, or ends below convergence_resolution.
  bool ends_alike(const SampleComparison &c);

  // Judges the trials run so far (each with its members, in the plan's
  // order) against `plan`: trial k is accepted when trial k+1 ends alike
  // (ends_alike) and, judged by order, its drift estimate is within the
  // tolerance (above); with none accepted and no refinement left the check
  // is decided, not converged. The check's trials are sorted coarsest first.
  ConvergenceCheck judge_convergence(const RefinementPlan &plan, std::vector<std::vector<EnsembleMember>> trial_members);

  // How many trials of `plan` its first round runs: the model and its
  // first refinement, and the witness of a plan judged by order. A study
  // that runs the model itself runs trials 1 … first_round_size − 1 beside
  // it (ladder_groups_with_checks), so that no round waits for the witness.
  std::size_t first_round_size(const RefinementPlan &plan);

  // The member groups of the trials `first` … `last` of a plan, as the
  // ensemble of `n_members` members over `scene`'s end time would run them;
  // named "<plan name>: <model label>".
  std::vector<MemberGroup> trial_groups(const Scene &scene, const RefinementPlan &plan, std::size_t first,
                                        std::size_t last, unsigned int n_members, double perturbation);

  // Runs the checks of `plans` to their decisions. `done[i]` holds the
  // members of the trials of plan i that have run already (trials 0, 1, …;
  // at least none); every round runs, in one list of member runs (`runner`,
  // or threads), the trials each undecided check needs next: up to trial 1
  // at once (the pair), then one refinement at a time. Before each round,
  // `share(mask)` is called with the bit set for every check that goes on
  // (0 when all are decided): under MPI the command broadcasts it from rank
  // 0 so that the other ranks run the same rounds (work_on_convergence_checks).
  std::vector<ConvergenceCheck>
  run_convergence_checks(const Scene &scene, const std::vector<RefinementPlan> &plans,
                         std::vector<std::vector<std::vector<EnsembleMember>>> done, unsigned int n_members,
                         double perturbation, const MemberGroupRunner &runner = {},
                         const std::function<unsigned long(unsigned long)> &share = {});

  // The same with a scene per plan (`scenes[i]` for plans[i], end time
  // set): checks at several operating points in one list.
  std::vector<ConvergenceCheck>
  run_convergence_checks(const std::vector<Scene> &scenes, const std::vector<RefinementPlan> &plans,
                         std::vector<std::vector<std::vector<EnsembleMember>>> done, unsigned int n_members,
                         double perturbation, const MemberGroupRunner &runner = {},
                         const std::function<unsigned long(unsigned long)> &share = {});

  // The other MPI ranks' part: the same rounds, told by `share` (which
  // returns rank 0's mask), each computing what rank 0 hands out by `work`.
  // `n_done[i]`: how many trials of plan i ran before, as on rank 0.
  void work_on_convergence_checks(const Scene &scene, const std::vector<RefinementPlan> &plans,
                                  std::vector<std::size_t> n_done, unsigned int n_members, double perturbation,
                                  const std::function<void(const std::vector<MemberGroup> &)> &work,
                                  const std::function<unsigned long(unsigned long)> &share);
  void work_on_convergence_checks(const std::vector<Scene> &scenes, const std::vector<RefinementPlan> &plans,
                                  std::vector<std::size_t> n_done, unsigned int n_members, double perturbation,
                                  const std::function<void(const std::vector<MemberGroup> &)> &work,
                                  const std::function<unsigned long(unsigned long)> &share);
} // namespace beamslider
