// The named adaptation cases, see simulation_cases.h.
#include "verification/studies/simulation_cases.h"
#include "fem/fe_beam.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "reduced/beam_backbone.h"
#include "reduced/rom_operator.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::vector<std::string> mueller(const double frequency_hz, const double acceleration, const double start)
    {
      std::ostringstream f, a, x;
      f << "Excitation/Frequency=" << frequency_hz;
      a << "Excitation/Acceleration amplitude=" << acceleration;
      x << "Initial state/Slider position=" << start;
      return {f.str(), a.str(), x.str()};
    }

    std::vector<std::string> signature_move_with(const std::vector<std::string> &more)
    {
      std::vector<std::string> o = mueller(124, 14, 0.3);
      o.insert(o.end(), more.begin(), more.end());
      return o;
    }
  } // namespace

  namespace
  {
    ExpectedFeatures expected_features(const std::string &name);

    std::vector<SimulationCase> with_expectations(std::vector<SimulationCase> cases)
    {
      for (SimulationCase &c : cases)
        c.expected = expected_features(c.name);
      return cases;
    }
  } // namespace

  const std::vector<SimulationCase> &simulation_cases()
  {
    static const std::vector<SimulationCase> cases = with_expectations({
      {"signature-move", "124 Hz, 14 m/s², from x_C/L = 0.3", mueller(124, 14, 0.3), 60.,
       "signature move: toward the clamp at low amplitude, a jump, turn back toward the centre, stop with large "
       "vibration"},
      {"trivial-adaption", "104 Hz, 14 m/s², from 0.3", mueller(104, 14, 0.3), 60.,
       "trivial adaption: no excursion toward the clamp and no jump; the vibration grows as the slider moves"},
      {"relaxation-oscillation", "126 Hz, 10 m/s², from 0.3", mueller(126, 10, 0.3), 120.,
       "relaxation oscillation: the vibration jumps up and falls back recurrently, the slider never settles"},
      {"self-damping", "124 Hz, 6 m/s², from 0.3", mueller(124, 6, 0.3), 60.,
       "self-damping: the vibration is not sustained; the slider ends off resonance at low vibration (our reading of "
       "the case name)"},
      {"trivial-adaption-106", "106 Hz, 10 m/s², from 0.3", mueller(106, 10, 0.3), 60.,
       "trivial adaption (as at 104 Hz)"},
      {"signature-move-106", "106 Hz, 10 m/s², from 0.4", mueller(106, 10, 0.4), 60.,
       "signature move (as at 124 Hz) from a start nearer the centre"},
      {"no-geometric-nonlinearity", "signature-move without the bending–stretching coupling",
       signature_move_with({"Discretisation/Geometric nonlinearity=false"}), 60.,
       "seed Fig. 8b (System 1): the slider moves away from the centre and stays; the vibration grows but does not "
       "jump, no turn-around, irregular response"},
      {"frictionless", "signature-move with μ = 0", signature_move_with({"Contact/Friction coefficient=0"}), 60.,
       "seed Fig. 8c (System 1): the slider oscillates along the beam around the centre, the amplitude modulated at "
       "twice the slider's frequency; no steady position"},
      {"tight-fit", "signature-move with R/h = 1.01", signature_move_with({"Slider/Window height ratio=1.01"}), 60.,
       "seed Fig. 11 (System 1): the slider moves straight toward the centre; no jump to the high branch from near the "
       "centre"},
      {"large-clearance", "signature-move with R/h = 1.2", signature_move_with({"Slider/Window height ratio=1.2"}), 60.,
       "seed Fig. 6 (System 1, unstable adaption): toward the clamp, a jump, then no turn: the slider keeps moving "
       "toward the clamp and the amplitude decreases"},
      {"heavy-slider", "signature-move with slider mass and inertia ×2 and R/h = 1.1",
       signature_move_with({"Slider/Mass factor=2", "Slider/Window height ratio=1.1"}), 60.,
       "seed Fig. 7 (System 1, quasi-stable adaption): the amplitude jumps between high and low level recurrently"},
    });
    return cases;
  }

  namespace
  {
    ExpectedFeatures expected_features(const std::string &name)
    {
      ExpectedFeatures e;
      if (name == "signature-move" || name == "signature-move-106")
        e.toward_clamp = e.jump = e.turn = 1;
      else if (name == "trivial-adaption" || name == "trivial-adaption-106")
        e.toward_clamp = e.jump = 0;
      else if (name == "relaxation-oscillation" || name == "heavy-slider")
        e.recurrent = 1;
      else if (name == "self-damping")
        e.turn = 0;
      else if (name == "no-geometric-nonlinearity")
        {
          e.toward_clamp = 1;
          e.jump = e.turn = 0;
        }
      else if (name == "frictionless")
        e.crosses_centre = 1;
      else if (name == "tight-fit")
        e.toward_clamp = e.jump = 0;
      else if (name == "large-clearance")
        {
          e.toward_clamp = e.jump = 1;
          e.turn                 = 0;
        }
      return e;
    }
  } // namespace

  std::vector<SimulationCase> published_cases()
  {
    constexpr std::size_t n_published = 6; // then the ablations of the seed's System 1
    const std::vector<SimulationCase> &all = simulation_cases();
    return {all.begin(), all.begin() + n_published};
  }

  const SimulationCase &find_case(const std::string &name)
  {
    for (const SimulationCase &c : simulation_cases())
      if (c.name == name)
        return c;
    std::string names;
    for (const SimulationCase &c : simulation_cases())
      names += (names.empty() ? "" : ", ") + c.name;
    throw InputError("--case '" + name + "' is not a known case; the cases are: " + names);
  }

  Scene read_case_scene(const std::string &scene_file, const SimulationCase &c,
                        const std::vector<std::string> &user_overrides, std::vector<std::string> *modified)
  {
    check_overrides_unique(user_overrides);
    auto path_of = [](const std::string &o) { return o.substr(0, o.find('=')); };
    std::vector<std::string> case_overrides = c.overrides;
    std::ostringstream end;
    end << "Time stepping/End time=" << c.end_time;
    case_overrides.push_back(end.str());

    // The user's value replaces the case's; a change of what the case itself
    // sets (other than its end time) is reported, because the run is then no
    // longer the published case.
    std::vector<std::string> overrides;
    for (const auto &o : case_overrides)
      {
        const auto user = std::find_if(user_overrides.begin(), user_overrides.end(),
                                       [&](const std::string &u) { return path_of(u) == path_of(o); });
        if (user == user_overrides.end())
          overrides.push_back(o);
        else if (modified && path_of(o) != "Time stepping/End time")
          modified->push_back(*user + " (the case sets " + o.substr(o.find('=') + 1) + ")");
      }
    overrides.insert(overrides.end(), user_overrides.begin(), user_overrides.end());
    return read_scene(scene_file, overrides);
  }

  CaseVerdict case_verdict(const std::vector<PeriodRecord> &periods, const RunResult &result,
                           const TraceThresholds &thresholds)
  {
    CaseVerdict v = analyse_trace(periods, result.status, thresholds);
    if (result.status != RunStatus::completed)
      {
        std::ostringstream m;
        m << std::setprecision(3) << "; stopped at t = " << result.t_end << " s (" << to_string(result.status) << ")";
        v.line += m.str();
      }
    return v;
  }

  TraceThresholds trace_thresholds(const Scene &scene)
  {
    if (!scene.discretisation.geometric_nonlinearity)
      return TraceThresholds::for_backbone(0.);
    const FEBeam beam(scene);
    const FEModes modes     = compute_bending_modes(beam, 1);
    const ReducedOrderModel rom(make_modal_basis(beam, modes, 1), 0.);
    const double c = single_mode_backbone_coefficient(modes.omega[0], rom.analytic_cubic_terms()[0].value,
                                                      beam.deflection(modes.shapes[0], 0.5 * scene.beam.length),
                                                      scene.beam.thickness);
    return TraceThresholds::for_backbone(c);
  }

  std::string disagreements(const CaseVerdict &v, const ExpectedFeatures &e)
  {
    std::string out;
    auto check = [&out](const int expected, const bool found, const std::string &what) {
      if (expected >= 0 && static_cast<bool>(expected) != found)
        out += (out.empty() ? "" : "; ") + std::string(expected ? "no " : "") + what +
               (expected ? " (published: yes)" : " (published: none)");
    };
    check(e.toward_clamp, v.initial_direction == "toward the clamp", "initial move toward the clamp");
    check(e.jump, v.jumped, "jump");
    check(e.turn, v.turned, "turn-around");
    check(e.recurrent, v.n_upward_jumps > 1, "recurrent jumps");
    check(e.crosses_centre, v.crosses_centre, "slider crossing the centre");
    return out;
  }
} // namespace beamslider
