// The published adaptation cases and the seed's ablations, runnable by name
// (`beamslider simulate mueller2023 --case signature-move`). A case is a list
// of scene overrides in the `--set` syntax, applied by read_scene before the
// user's own --set, so validate_scene checks the combination and the user can
// still change anything.
//
// The six mueller2023 cases are those of doc/scenes.md (Müller, Beck & Krack,
// MSSP 2023; start x_C/L = 0.3 unless noted). The five ablations are applied
// to signature-move; what the seed reports for them (on its System 1, seed
// §3.3 and §4.1) is kept with each case as `published`, to be compared with
// what our model does, never to tune it.
#pragma once

#include "runs/adaptation_run.h"
#include "runs/trace_analysis.h"
#include "scene/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace beamslider
{
  // What the published behaviour says about features a verdict can measure:
  // 1 = reported, 0 = reported absent, -1 = not stated.
  struct ExpectedFeatures
  {
    int toward_clamp   = -1; // the slider first moves away from the centre
    int jump           = -1; // the vibration jumps to a higher level
    int turn           = -1; // the slider turns back toward the centre
    int recurrent      = -1; // more than one upward jump
    int crosses_centre = -1; // the slider passes x = L/2
  };

  struct SimulationCase
  {
    std::string name;
    std::string description;            // what is changed, in words
    std::vector<std::string> overrides; // "Section/Name=value"
    double end_time = 60.;              // [s]
    std::string published;              // the behaviour the literature reports
    ExpectedFeatures expected{}; // filled from the name by simulation_cases()
  };

  // All named cases, mueller2023 cases first, then the ablations.
  const std::vector<SimulationCase> &simulation_cases();

  // The six mueller2023 cases alone (the first of simulation_cases()).
  std::vector<SimulationCase> published_cases();

  // The case of that name; InputError listing the valid names otherwise.
  const SimulationCase &find_case(const std::string &name);

  // The scene file with the case's overrides, then the user's; the end time
  // is the case's (the user's --set "Time stepping/End time" wins). A user
  // override of a parameter the case sets replaces the case's value and is
  // listed in `modified` ("Contact/Friction coefficient=0.5 (the case sets 0)"):
  // such a run is no longer the published case.
  Scene read_case_scene(const std::string &scene_file, const SimulationCase &c,
                        const std::vector<std::string> &user_overrides, std::vector<std::string> *modified = nullptr);

  // What a run did: the one trace analysis (runs/trace_analysis.h) with
  // the thresholds of the run's scene (trace_thresholds), or with the
  // defaults (no upper-branch level) for constructed traces.
  using CaseVerdict = TraceAnalysis;
  CaseVerdict case_verdict(const std::vector<PeriodRecord> &periods, const RunResult &result,
                           const TraceThresholds &thresholds = {});

  // The thresholds for runs of `scene`: the upper-branch level from the
  // scene's mode-1 backbone coefficient (seed Eq. 4 on the scene's FE mode;
  // no level without geometric nonlinearity).
  TraceThresholds trace_thresholds(const Scene &scene);

  // The features of a verdict that contradict the expected ones, in words
  // ("" when none do, or nothing is stated).
  std::string disagreements(const CaseVerdict &verdict, const ExpectedFeatures &expected);

  // One free-slider simulation as `beamslider simulate` runs it (files in
  // verification/cli/command_simulate.cc's header), returning what happened.
  struct SimulationOutcome
  {
    Scene scene;
    ModelSetting setting;
    std::string why;   // --model auto's reasoning
    std::string dir;   // output folder
    RunResult result;
    CaseVerdict verdict;
    std::vector<PeriodRecord> periods; // as written to periods.csv, with the energy bookkeeping
    double wall_seconds = 0;
  };

  // One named case to run as `beamslider simulate <scene> --case <name>` runs
  // it (ROM), into its own folder. The command line provides the runner
  // (verification/cli/command_simulate.cc: run_simulation), which owns the
  // folder, its records and its charts; a study or a report section takes it
  // as a function and never calls the command line itself.
  struct CaseRun
  {
    std::string case_name;
    std::optional<double> end_time; // [s], else the case's
    std::string output_dir;
  };
  using CaseRunner = std::function<SimulationOutcome(const CaseRun &)>;
} // namespace beamslider
