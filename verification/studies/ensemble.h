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
// (contact/trace_analysis.h) with the scene's thresholds.
#pragma once

#include "contact/adaptation_run.h"
#include "contact/trace_analysis.h"
#include "meshes/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <functional>
#include <optional>
#include <string>
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

  // Runs the members (models built one after another, runs in parallel
  // threads); `on_member` (optional) is called, serialised, as each finishes.
  std::vector<EnsembleMember> run_ensemble(const Scene &scene, const EnsembleSettings &settings,
                                           const std::function<void(const EnsembleMember &)> &on_member = {});

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
  // amplitude [h] (all).
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
