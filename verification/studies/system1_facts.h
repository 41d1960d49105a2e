// The seed's qualitative facts about its System 1 (Müller & Krack, seed
// §3.3, §4.1–4.2, Figs. 6–8 and 10–13), each a named criterion on one
// adaptation run, and the identification of System 1's unknown parameters
// (meshes/system1.prm) by maps over them (operating_map.h).
//
// The seed's Table 1 is missing from our copy: friction, restitution, the
// slider's centre-of-mass offset, window width, rotary inertia and the modal
// damping of System 1 are unknown. What the seed does state is how System 1
// behaves in a handful of scenarios (a frequency, a base acceleration, a
// start position, sometimes a changed clearance or slider mass). A fact here
// is one such scenario together with a criterion that reads the run's trace
// analysis (runs/trace_analysis.h) and returns
//   - pass/fail: every condition of the fact is met;
//   - a score in [0, 1]: the mean of the conditions' partial scores (1 met,
//     0 not; a position condition falls linearly from 1 at its tolerance to 0
//     at three tolerances), so that a candidate that gets most of a fact
//     right ranks above one that gets none of it;
//   - a reason in words: each condition, met or not, with the number.
// The criteria are written from the seed's text, never from our runs: a fact
// no candidate reproduces is a result, not a reason to loosen its criterion.
//
// Positions: the seed describes the right half of the beam (x_C/L > 0.5, the
// clamp at x_C/L = 1); TraceAnalysis judges directions by the distance from
// the centre, so a fact holds in either half. The facts keep the seed's half.
#pragma once

#include "runs/trace_analysis.h"
#include "verification/studies/operating_map.h"

#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  // One condition of a fact, judged.
  struct FactCheck
  {
    std::string what;  // "jumps", "ends within 0.03 of x_C/L = 0.57"
    bool met     = false;
    double score = 0;  // in [0, 1]
    std::string value; // what the run did, "ends at 0.612"
  };

  struct FactVerdict
  {
    bool pass    = false;
    double score = 0; // mean of the checks' scores, in [0, 1]
    std::string reason;
    std::vector<FactCheck> checks;
  };

  struct System1Fact
  {
    std::string id;   // short, for file and column names: "fig10"
    std::string name; // the criterion's name: "Fig. 10: toward the clamp, jump, turn, stop near 0.57"
    std::string seed; // what the seed says, in its words (shortened)
    // The scenario: --set overrides on the scene (frequency, acceleration,
    // start, and what the figure changes) and the simulated time.
    std::vector<std::string> overrides;
    double end_time = 60; // [s]
    // The criterion: the analysis of one run started at x_C/L = start.
    std::function<std::vector<FactCheck>(const TraceAnalysis &, double start)> checks;

    FactVerdict judge(const TraceAnalysis &analysis, double start) const;
    // The scene parameters the scenario fixes ("Contact/Friction coefficient"
    // for the frictionless ablation): an unknown among them is no axis of
    // this fact's map.
    std::vector<std::string> fixed_parameters() const;
    double start_over_L() const; // from the overrides
  };

  // The facts, in the seed's order of figures.
  const std::vector<System1Fact> &system1_facts();
  // One fact by id; InputError naming the known ids otherwise.
  const System1Fact &system1_fact(const std::string &id);
  // The facts of these ids, in the order given; every fact if `ids` is empty.
  std::vector<const System1Fact *> select_system1_facts(const std::vector<std::string> &ids);

  // One fact's map in an identification: the unknowns' axes the fact does not
  // fix (or, if it fixes all, its start as a one-value axis: a map needs an
  // axis), and the --set list of its runs: the user's overrides except those
  // the scenario fixes, then the scenario's (run_map_cells and
  // map_cell_scene add the axis values and the end time).
  struct FactMap
  {
    MapGrid grid;
    std::vector<std::size_t> unknown_of_axis; // for each grid axis, its index among the unknowns (none for the start)
    std::vector<std::string> overrides;
  };
  FactMap system1_fact_map(const System1Fact &fact, const MapGrid &unknowns, const std::vector<std::string> &overrides);

  // Partial scores, shared by the criteria and their tests.
  FactCheck flag_check(const std::string &what, bool met, const std::string &value);
  // |x - target| ≤ tolerance: met, score 1; falls to 0 at 3 × tolerance.
  FactCheck position_check(const std::string &what, double x, double target, double tolerance);
  // x ≥ bound (or ≤ with `below`): met; the score falls to 0 `scale` beyond.
  FactCheck bound_check(const std::string &what, double x, double bound, bool below, double scale);

  // The identification: the unknowns' grid, one map per fact over the axes
  // the fact does not fix, each candidate (a cell of the full grid) scored by
  // the sum of its facts' scores (mean over the members).
  struct IdentificationResult
  {
    MapGrid unknowns;                 // the full candidate grid
    std::vector<std::string> fact_ids;
    // [candidate][fact]
    std::vector<std::vector<double>> scores;
    std::vector<std::vector<unsigned int>> passes; // members that pass
    std::vector<std::vector<std::string>> reasons; // member 0's reason
    // False where the fact's map did not reach the candidate (interrupted):
    // its score there is 0 by default, not a verdict.
    std::vector<std::vector<bool>> judged;
    std::vector<double> wall_seconds;              // per fact map
    std::size_t best = 0;                          // the candidate with the largest total
    double total(std::size_t candidate) const;
  };

  // Runs the facts' maps; `on_fact(fact, members)` (optional) receives each
  // fact's grid and members when its map is done (to write its map.csv).
  // Empty `fact_ids` means every fact. Interrupted (Ctrl-C): the facts not
  // run have score 0 and the result says so through `complete`.
  IdentificationResult identify_system1(
    const std::string &scene_file, const std::vector<std::string> &overrides, const MapGrid &unknowns,
    const std::vector<std::string> &fact_ids, const MapSettings &settings, bool &complete,
    const std::function<void(const System1Fact &, const MapGrid &, const std::vector<std::vector<MapMember>> &)>
      &on_fact = {});
} // namespace beamslider
