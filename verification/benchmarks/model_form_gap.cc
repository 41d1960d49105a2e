// Which difference between the reduced model converged in N and the FE beam
// moves the adaptation's end state (issue 76 item 3): the same ensemble with
// one difference switched at a time, each printed with its end state
// (median [min, max] of x_C/L), class counts and wall time.
//
//   model_form_gap SCENE.prm [--set Section/Name=value ...] [--members K]
//                  [--end-time T] [--only NAME ...]
//
// The variants (names for --only):
//   fe          the scene's FE model (θ and Δt from the scene)
//   fe-dt/2     the same at half and a quarter of its step: the impacts'
//   fe-dt/4     beam mass falls like √Δt (physics.md §7)
//   fe-noaxial  the FE with no axial inertia (the ROM's quasi-static membrane)
//   rom30       the ROM with 30 modes at its explicit step (all 30 damped)
//   rom30-d     the same damping only the scene's N, as the FE does
//   rom30-imp   the same, stepped as the FE is (implicit, the FE's θ and Δt)
//   romall-imp  every bending mode of the FE mesh, stepped as the FE is,
//               damping the scene's N: the FE's linear dynamics without
//               its axial inertia and with the cubic (STEP-exact) membrane
//   romall-imp-dt/2, rom30-imp-dt/4   the two implicit ROMs at Δt/2, Δt/4
//   rom30-theta, rom30-mid   rom30 stepped implicitly at its own step, with
//               the FE's θ and with θ = ½: the scheme's numerical damping
//   fe-mid-dt/4, fe-mid-dt/8  the FE with θ = ½ at Δt/4 and Δt/8
// Each variant differs from its neighbour above by one thing, so the moves
// between neighbours attribute the gap. Not a test: minutes per variant.
#include "scene/scene.h"
#include "runs/trace_analysis.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/error_ladder.h"
#include "verification/studies/fe_rom_study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using namespace beamslider;

  struct Variant
  {
    std::string name;
    ModelSetting model;
  };

  std::vector<Variant> variants(const Scene &scene)
  {
    const ModelSetting fe = scene_model(scene, "fe");
    const unsigned int N0 = scene.discretisation.n_modes;
    std::vector<Variant> v;
    v.push_back({"fe", fe});
    for (const auto &[name, k] : {std::pair("fe-dt/2", 2.), std::pair("fe-dt/4", 4.)})
      {
        ModelSetting m = fe;
        m.time_step /= k;
        v.push_back({name, m});
      }
    ModelSetting no_axial  = fe;
    no_axial.axial_inertia = false;
    v.push_back({"fe-noaxial", no_axial});

    ModelSetting rom30 = scene_model(scene, "rom");
    rom30.n_modes      = 30;
    rom30.time_step    = scene.time_stepping.time_step / 8; // below 2/ω₃₀
    v.push_back({"rom30", rom30});
    const ModelSetting region_n30 = rom30; // as the region runs N = 30
    rom30.damped_modes = N0;
    v.push_back({"rom30-d", rom30});
    rom30.integrator = "implicit";
    rom30.theta      = fe.theta;
    rom30.time_step  = fe.time_step;
    v.push_back({"rom30-imp", rom30});
    ModelSetting all = rom30;
    all.n_modes      = fe_bending_modes(scene);
    v.push_back({"romall-imp", all});
    // The two implicit ROMs refined in Δt: whether each follows the FE at
    // the same step, or the explicit ROM.
    all.time_step /= 2;
    v.push_back({"romall-imp-dt/2", all});
    rom30.time_step /= 4;
    v.push_back({"rom30-imp-dt/4", rom30});
    // N = 30 at its explicit step with every mode damped (the region's
    // N = 30) stepped implicitly: with the FE's θ, and with θ = ½ (the
    // midpoint rule, no numerical damping).
    ModelSetting scheme = region_n30;
    scheme.integrator   = "implicit";
    scheme.theta        = fe.theta;
    v.push_back({"rom30-theta", scheme});
    scheme.theta = 0.5;
    v.push_back({"rom30-mid", scheme});
    // The FE with the midpoint rule at Δt/4 and Δt/8: the θ = ½ limit.
    for (const auto &[name, k] : {std::pair("fe-mid-dt/4", 4.), std::pair("fe-mid-dt/8", 8.)})
      {
        ModelSetting m = fe;
        m.theta        = 0.5;
        m.time_step /= k;
        v.push_back({name, m});
      }
    return v;
  }

  std::string class_counts(const std::vector<EnsembleMember> &members)
  {
    std::map<std::string, int> counts;
    for (const EnsembleMember &m : members)
      ++counts[m.analysis.valid ? to_string(m.analysis.outcome) : to_string(m.result.status)];
    std::ostringstream s;
    for (const auto &[name, n] : counts)
      s << (s.tellp() > 0 ? ", " : "") << name << " × " << n;
    return s.str();
  }
} // namespace

int main(int argc, char **argv)
{
  std::vector<std::string> overrides, only;
  std::string scene_file;
  unsigned int members = 4;
  double end_time      = 40;
  for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (a == "--set" && i + 1 < argc)
        overrides.push_back(argv[++i]);
      else if (a == "--only" && i + 1 < argc)
        only.push_back(argv[++i]);
      else if (a == "--members" && i + 1 < argc)
        members = std::stoul(argv[++i]);
      else if (a == "--end-time" && i + 1 < argc)
        end_time = std::stod(argv[++i]);
      else if (scene_file.empty() && a.rfind("--", 0) != 0)
        scene_file = a;
      else
        {
          std::cerr << "usage: model_form_gap SCENE.prm [--set S/N=v ...] [--members K] [--end-time T] [--only NAME ...]\n";
          return 2;
        }
    }
  if (scene_file.empty())
    {
      std::cerr << "model_form_gap: give a scene file (.prm)\n";
      return 2;
    }
  try
    {
      Scene scene            = read_scene(scene_file, overrides);
      scene.time_stepping.end_time = end_time;
      std::printf("%-11s %-34s %-30s %-34s %s\n", "variant", "model", "final x_C/L median [min, max]", "classes",
                  "wall s");
      for (const Variant &v : variants(scene))
        {
          if (!only.empty() && std::find(only.begin(), only.end(), v.name) == only.end())
            continue;
          const auto start = std::chrono::steady_clock::now();
          EnsembleSettings settings;
          settings.model     = v.model;
          settings.n_members = members;
          const std::vector<EnsembleMember> m = run_ensemble(scene, settings);
          const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          const OutcomeStatistics s = statistics("final", outcome_samples(m).final_position);
          std::printf("%-11s %-34s %.4f [%.4f, %.4f] (n %zu)   %-34s %.0f\n", v.name.c_str(), v.model.label().c_str(),
                      s.median, s.min, s.max, s.n, class_counts(m).c_str(), wall);
          std::fflush(stdout);
        }
    }
  catch (const std::exception &e)
    {
      std::cerr << "model_form_gap: " << e.what() << '\n';
      return 1;
    }
  return 0;
}
