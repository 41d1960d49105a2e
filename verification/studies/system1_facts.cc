// The seed's System 1 facts and the identification by maps; see
// system1_facts.h for what a fact, a criterion and a score are.
#include "numerics/elapsed.h"
#include "verification/studies/system1_facts.h"
#include "verification/studies/system1_fact_table.h"

#include "numerics/stop_request.h"
#include "scene/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string number(const double x, const int digits = 3)
    {
      std::ostringstream s;
      s << std::fixed << std::setprecision(digits) << x;
      return s.str();
    }

    // "--set" text of a scenario.
    std::string set(const std::string &parameter, const double value)
    {
      std::ostringstream s;
      s << parameter << "=" << value;
      return s.str();
    }

    const std::string frequency    = "Excitation/Frequency";
    const std::string acceleration = "Excitation/Acceleration amplitude";
    const std::string start        = "Initial state/Slider position";
    const std::string clearance    = "Slider/Window height ratio";

    // Shared conditions, each on the analysis of one run.
    FactCheck direction_check(const TraceAnalysis &a, const std::string &wanted)
    {
      return flag_check("first moves " + wanted, a.initial_direction == wanted,
                        a.initial_direction + " (" + number(a.initial_drift_over_L) + " L by " +
                          number(a.direction_until, 1) + " s)");
    }
    FactCheck jump_check(const TraceAnalysis &a, const bool wanted)
    {
      return flag_check(wanted ? "jumps to the upper branch" : "does not jump", a.jumped == wanted,
                        a.jumped ? "jump at " + number(a.jump_time, 1) + " s" : "no jump");
    }
    FactCheck turn_check(const TraceAnalysis &a, const bool wanted)
    {
      return flag_check(wanted ? "turns back toward the centre" : "does not turn", a.turned == wanted,
                        a.turned ? "turns at x_C/L = " + number(a.turn_position) : "no turn");
    }
    // The end farther from the centre than the start, by `by` (the
    // distance from the centre, so in either half).
    FactCheck moves_out_check(const TraceAnalysis &a, const double start_over_L, const double by)
    {
      const double out = std::abs(a.final_position - 0.5) - std::abs(start_over_L - 0.5);
      return bound_check("keeps moving toward the clamp: ends ≥ " + number(by, 2) + " L farther out than it started",
                         out, by, false, by);
    }
    // The end at most `share` of the start's distance from the centre.
    FactCheck moves_in_check(const TraceAnalysis &a, const double start_over_L, const double share)
    {
      const double ratio = std::abs(a.final_position - 0.5) / std::max(1e-12, std::abs(start_over_L - 0.5));
      return bound_check("moves to the centre: ends within " + number(share, 2) +
                           " of its start's distance from the centre",
                         ratio, share, true, 1. - share);
    }
    FactCheck completed_check(const TraceAnalysis &a)
    {
      return flag_check("stays on the beam (no support reached, no failure)",
                        a.outcome != AdaptationClass::reached_support && a.outcome != AdaptationClass::failed &&
                          a.outcome != AdaptationClass::too_short,
                        to_string(a.outcome));
    }
    FactCheck outcome_check(const TraceAnalysis &a, const AdaptationClass wanted)
    {
      return flag_check("class " + to_string(wanted), a.outcome == wanted,
                        to_string(a.outcome) + ", ends at " + number(a.final_amplitude, 2) + " h");
    }

    // The check sets of system1_fact_table.h, each on the analysis of one
    // run started at x_C/L = x0, with the row's target.
    using CheckSetFunction = std::vector<FactCheck> (*)(const TraceAnalysis &, double x0, double target);

    // Figs. 10 and its mirror: away from the centre, a jump, a turn, and the
    // end within 0.03 L of `end_over_L`.
    std::vector<FactCheck> out_jump_turn_stop_near(const TraceAnalysis &a, double, const double end_over_L)
    {
      return {direction_check(a, "toward the clamp"), jump_check(a, true), turn_check(a, true),
              position_check("stops near x_C/L = " + number(end_over_L, 2), a.final_position, end_over_L, 0.03)};
    }
    // Figs. 11, 12 and 13: toward the centre from the start, no jump, no turn,
    // and the end at most half the start's distance from the centre.
    std::vector<FactCheck> straight_to_the_centre(const TraceAnalysis &a, const double x0, double)
    {
      return {direction_check(a, "toward the centre"), jump_check(a, false), turn_check(a, false),
              moves_in_check(a, x0, 0.5)};
    }
    // Fig. 12: the same on the upper branch all along.
    std::vector<FactCheck> straight_to_the_centre_trivial(const TraceAnalysis &a, const double x0, const double target)
    {
      std::vector<FactCheck> checks = straight_to_the_centre(a, x0, target);
      checks.push_back(outcome_check(a, AdaptationClass::trivial_adaption));
      return checks;
    }
    // Fig. 6: a jump, no turn, on toward the clamp by at least `by` while the
    // amplitude decays.
    std::vector<FactCheck> jump_no_turn_on_to_the_clamp(const TraceAnalysis &a, const double x0, const double by)
    {
      return {direction_check(a, "toward the clamp"), jump_check(a, true), turn_check(a, false),
              moves_out_check(a, x0, by),
              bound_check("the amplitude decays after the jump: ends below half the largest envelope",
                          a.max_envelope > 0 ? a.final_amplitude / a.max_envelope : 1., 0.5, true, 0.5)};
    }
    // Fig. 7: jumps up again and again, and stays on the beam.
    std::vector<FactCheck> recurrent_jumps(const TraceAnalysis &a, double, double)
    {
      FactCheck recurrent = bound_check("jumps up at least twice", a.n_upward_jumps, 2., false, 2.);
      recurrent.met       = a.n_upward_jumps >= 2;
      recurrent.value     = std::to_string(a.n_upward_jumps) + " upward jump(s)";
      return {recurrent, completed_check(a)};
    }
    // Fig. 8a.
    std::vector<FactCheck> signature_move(const TraceAnalysis &a, double, double)
    {
      return {direction_check(a, "toward the clamp"), jump_check(a, true), turn_check(a, true),
              outcome_check(a, AdaptationClass::signature_move)};
    }
    // Fig. 8b: away from the centre and stays, no jump, no turn.
    std::vector<FactCheck> out_no_jump_no_turn(const TraceAnalysis &a, double, double)
    {
      return {direction_check(a, "toward the clamp"), jump_check(a, false), turn_check(a, false),
              completed_check(a)};
    }
    // Fig. 8c: oscillating, not passing through once: still moving in the
    // last fifth of the run (its adaptation time, when it comes to rest for
    // good, lies there).
    std::vector<FactCheck> oscillates_about_the_centre(const TraceAnalysis &a, double, double)
    {
      return {flag_check("crosses the centre", a.crosses_centre, a.crosses_centre ? "crosses" : "does not cross"),
              flag_check("keeps moving: no rest before the last fifth of the run",
                         a.adaptation_time >= 0.8 * a.end_time,
                         "comes to rest at " + number(a.adaptation_time, 1) + " s of " + number(a.end_time, 1) + " s"),
              completed_check(a)};
    }

    CheckSetFunction check_set_function(const FactCheckSet set)
    {
      switch (set)
        {
          case FactCheckSet::out_jump_turn_stop_near:
            return out_jump_turn_stop_near;
          case FactCheckSet::straight_to_the_centre:
            return straight_to_the_centre;
          case FactCheckSet::straight_to_the_centre_trivial:
            return straight_to_the_centre_trivial;
          case FactCheckSet::jump_no_turn_on_to_the_clamp:
            return jump_no_turn_on_to_the_clamp;
          case FactCheckSet::recurrent_jumps:
            return recurrent_jumps;
          case FactCheckSet::signature_move:
            return signature_move;
          case FactCheckSet::out_no_jump_no_turn:
            return out_no_jump_no_turn;
          case FactCheckSet::oscillates_about_the_centre:
            return oscillates_about_the_centre;
        }
      throw std::logic_error("unknown check set of a System 1 fact");
    }

    // The --set overrides of a row's scenario: frequency, acceleration,
    // start, then what the figure changes.
    std::vector<std::string> scenario_overrides(const System1FactRow &row)
    {
      std::vector<std::string> overrides = {set(frequency, row.frequency), set(acceleration, row.acceleration),
                                            set(start, row.start)};
      if (row.clearance > 0) // 0: the scene's
        overrides.push_back(set(clearance, row.clearance));
      if (*row.also != '\0')
        overrides.push_back(row.also);
      return overrides;
    }

    std::vector<System1Fact> make_facts()
    {
      std::vector<System1Fact> facts;
      for (std::size_t i = 0; i < n_system1_fact_rows; ++i)
        {
          const System1FactRow &row = system1_fact_table[i];
          System1Fact f;
          f.id        = row.id;
          f.name      = row.name;
          f.seed      = row.seed;
          f.overrides = scenario_overrides(row);
          f.end_time  = row.end_time;
          f.checks    = [checks = check_set_function(row.checks), target = row.target](const TraceAnalysis &a,
                                                                                        const double x0) {
            return checks(a, x0, target);
          };
          facts.push_back(f);
        }
      return facts;
    }
  } // namespace

  FactCheck flag_check(const std::string &what, const bool met, const std::string &value)
  {
    return {what, met, met ? 1. : 0., value};
  }

  FactCheck position_check(const std::string &what, const double x, const double target, const double tolerance)
  {
    const double miss = std::abs(x - target);
    const double score = std::clamp(1. - (miss - tolerance) / (2. * tolerance), 0., 1.);
    return {what, miss <= tolerance, score, "ends at x_C/L = " + number(x)};
  }

  FactCheck bound_check(const std::string &what, const double x, const double bound, const bool below,
                        const double scale)
  {
    const double beyond = below ? x - bound : bound - x; // > 0: not met
    const double score  = std::clamp(1. - beyond / scale, 0., 1.);
    return {what, beyond <= 0., beyond <= 0. ? 1. : score, number(x)};
  }

  FactVerdict System1Fact::judge(const TraceAnalysis &analysis, const double start_position) const
  {
    FactVerdict v;
    if (!analysis.valid)
      {
        v.checks = {flag_check("a run long enough to judge", false, to_string(analysis.outcome))};
      }
    else
      v.checks = checks(analysis, start_position);
    v.pass = true;
    double sum = 0;
    std::ostringstream reason;
    for (const FactCheck &c : v.checks)
      {
        v.pass = v.pass && c.met;
        sum += c.score;
        reason << (&c == &v.checks.front() ? "" : "; ") << (c.met ? "" : "NOT ") << c.what << " (" << c.value << ")";
      }
    v.score  = v.checks.empty() ? 0. : sum / v.checks.size();
    v.reason = reason.str();
    return v;
  }

  std::vector<std::string> System1Fact::fixed_parameters() const
  {
    std::vector<std::string> p;
    for (const std::string &o : overrides)
      p.push_back(o.substr(0, o.find('=')));
    return p;
  }

  double System1Fact::start_over_L() const
  {
    for (const std::string &o : overrides)
      if (o.rfind(start + "=", 0) == 0)
        return std::stod(o.substr(start.size() + 1));
    throw std::logic_error("fact " + id + " has no start position");
  }

  const std::vector<System1Fact> &system1_facts()
  {
    static const std::vector<System1Fact> facts = make_facts();
    return facts;
  }

  const System1Fact &system1_fact(const std::string &id)
  {
    std::string known;
    for (const System1Fact &f : system1_facts())
      {
        if (f.id == id)
          return f;
        known += (known.empty() ? "" : ", ") + f.id;
      }
    throw InputError("unknown System 1 fact '" + id + "'; the facts are: " + known);
  }

  std::vector<const System1Fact *> select_system1_facts(const std::vector<std::string> &ids)
  {
    std::vector<const System1Fact *> facts;
    if (ids.empty())
      for (const System1Fact &f : system1_facts())
        facts.push_back(&f);
    else
      for (const std::string &id : ids)
        facts.push_back(&system1_fact(id));
    return facts;
  }

  FactMap system1_fact_map(const System1Fact &fact, const MapGrid &unknowns, const std::vector<std::string> &overrides)
  {
    const std::vector<std::string> fixed = fact.fixed_parameters();
    const auto is_fixed = [&fixed](const std::string &parameter) {
      return std::find(fixed.begin(), fixed.end(), parameter) != fixed.end();
    };
    FactMap map;
    for (std::size_t k = 0; k < unknowns.axes.size(); ++k)
      if (!is_fixed(unknowns.axes[k].parameter))
        {
          map.grid.axes.push_back(unknowns.axes[k]);
          map.unknown_of_axis.push_back(k);
        }
    if (map.grid.axes.empty()) // a map needs an axis: the start, one value
      map.grid.axes.push_back({start, "start_x_over_L", {fact.start_over_L()}});
    // The scenario's overrides come after the user's, so the scenario holds.
    for (const std::string &o : overrides)
      if (!is_fixed(o.substr(0, o.find('='))))
        map.overrides.push_back(o);
    map.overrides.insert(map.overrides.end(), fact.overrides.begin(), fact.overrides.end());
    return map;
  }

  double IdentificationResult::total(const std::size_t candidate) const
  {
    double t = 0;
    for (const double s : scores[candidate])
      t += s;
    return t;
  }

  IdentificationResult identify_system1(
    const std::string &scene_file, const std::vector<std::string> &overrides, const MapGrid &unknowns,
    const std::vector<std::string> &fact_ids, const MapSettings &settings, bool &complete,
    const std::function<void(const System1Fact &, const MapGrid &, const std::vector<std::vector<MapMember>> &)>
      &on_fact)
  {
    const std::vector<const System1Fact *> facts = select_system1_facts(fact_ids);

    IdentificationResult result;
    result.unknowns = unknowns;
    const std::size_t n_candidates = unknowns.n_cells();
    for (const System1Fact *f : facts)
      result.fact_ids.push_back(f->id);
    result.scores.assign(n_candidates, std::vector<double>(facts.size(), 0.));
    result.passes.assign(n_candidates, std::vector<unsigned int>(facts.size(), 0));
    result.reasons.assign(n_candidates, std::vector<std::string>(facts.size(), "not run (interrupted)"));
    result.judged.assign(n_candidates, std::vector<bool>(facts.size(), false));
    complete = true;

    for (std::size_t i = 0; i < facts.size(); ++i)
      {
        const System1Fact &fact = *facts[i];
        const FactMap map         = system1_fact_map(fact, unknowns, overrides);
        const std::vector<std::size_t> &kept = map.unknown_of_axis;
        MapSettings fact_settings = settings;
        fact_settings.end_time    = fact.end_time;

        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<std::vector<MapMember>> cells =
          run_map_cells(scene_file, map.overrides, map.grid, fact_settings);
        result.wall_seconds.push_back(elapsed_seconds(t0));
        if (on_fact)
          on_fact(fact, map.grid, cells);

        // Each candidate takes the cell of the fact's map with its values.
        for (std::size_t c = 0; c < n_candidates; ++c)
          {
            const std::vector<double> values = unknowns.cell_values(c);
            std::size_t cell = 0;
            for (std::size_t k = 0; k < kept.size(); ++k)
              {
                const std::vector<double> &axis = unknowns.axes[kept[k]].values;
                const std::size_t j =
                  std::find(axis.begin(), axis.end(), values[kept[k]]) - axis.begin();
                cell = cell * axis.size() + j;
              }
            const std::vector<MapMember> &members = cells[cell];
            if (members.empty())
              {
                complete = false;
                continue;
              }
            result.judged[c][i] = true;
            double sum = 0;
            for (const MapMember &m : members)
              {
                const FactVerdict v = fact.judge(m.analysis, fact.start_over_L() + m.perturbation);
                sum += v.score;
                result.passes[c][i] += v.pass;
                if (m.index == 0)
                  result.reasons[c][i] = v.reason;
              }
            result.scores[c][i] = sum / members.size();
          }
        if (interruption_requested())
          {
            complete = false;
            break;
          }
      }
    for (std::size_t c = 1; c < n_candidates; ++c)
      if (result.total(c) > result.total(result.best) + 1e-12)
        result.best = c;
    return result;
  }
} // namespace beamslider
