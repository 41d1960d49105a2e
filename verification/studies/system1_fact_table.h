// The seed's System 1 facts as data (system1_fact_table.cc): one row per
// fact, its scenario and the set of checks that judges it.
// system1_facts.cc turns the rows into System1Facts (system1_facts.h) and
// holds the check sets themselves.
#pragma once

#include <cstddef>

namespace beamslider
{
  // The criteria of the facts, each a set of checks on one run's trace
  // analysis; a row's `target` is the set's one number where it has one.
  enum class FactCheckSet
  {
    out_jump_turn_stop_near,        // Fig. 10: the end within 0.03 L of x_C/L = target
    straight_to_the_centre,         // Figs. 11, 13: no jump, no turn, the end ≤ half the start's distance
    straight_to_the_centre_trivial, // Fig. 12: as above, and of class trivial adaption
    jump_no_turn_on_to_the_clamp,   // Fig. 6: the end ≥ target L farther out, the amplitude decaying
    recurrent_jumps,                // Fig. 7: at least two upward jumps, on the beam
    signature_move,                 // Fig. 8a
    out_no_jump_no_turn,            // Fig. 8b: away from the centre, on the beam
    oscillates_about_the_centre     // Fig. 8c: crosses the centre, still moving late
  };

  // One fact: what it is called, what the seed says, its scenario (the
  // --set overrides of frequency, acceleration, start and what the figure
  // changes) and its criterion.
  struct System1FactRow
  {
    const char *id;      // short, for file and column names: "fig10"
    const char *name;    // the criterion's name
    const char *seed;    // what the seed says, in its words (shortened)
    double frequency;    // [Hz]
    double acceleration; // [m/s^2]
    double start;        // x_C/L
    double clearance;    // window height ratio R/h; 0: the scene's
    const char *also;    // one more override, "Section/Name=value" ("": none)
    double end_time;     // [s]
    FactCheckSet checks;
    double target;       // the check set's number (0 where it has none)
  };

  // The facts in the seed's order of figures.
  extern const System1FactRow system1_fact_table[];
  extern const std::size_t n_system1_fact_rows;
} // namespace beamslider
