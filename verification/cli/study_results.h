// The results of the studies that can be computed in one call and written
// in another (commands.h, StudyHandover): what `ensemble`, `ladder`,
// `sweep` and `map` compute before they write, as the Python module's study objects
// hold them (python/study_bindings.cc).
#pragma once

#include "scene/scene.h"
#include "verification/studies/convergence_check.h"
#include "verification/studies/error_ladder.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/operating_map.h"
#include "verification/studies/pcs_sweep.h"
#include "verification/report/report_ladder.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace beamslider
{
  // One ensemble (command_ensemble.cc): the scene and settings, the
  // members, the FE's check in Δt, and the cost.
  struct EnsembleRun
  {
    Scene scene;
    EnsembleSettings settings;
    std::string dir; // "" until written
    std::vector<EnsembleMember> members;
    std::optional<ConvergenceCheck> check; // the FE's, unless --unchecked
    std::optional<OutcomeSamples> against; // --against: the other ensemble's outcomes
    std::size_t n_kept  = 0; // members read back from member_runs.csv
    double wall_seconds = 0;
    std::string model_choice; // --model auto: the numbers the model was picked on
  };

  // One error ladder (command_ladder.cc): its rungs and settings, and what
  // they gave.
  struct LadderRun
  {
    Scene scene;
    std::vector<LadderRung> rungs;
    LadderRunSettings settings;
    LadderStudy study;
    double wall_seconds = 0;
  };

  // One prescribed-position sweep (command_sweep.cc).
  struct SweepRun
  {
    Scene scene;
    PcsStudySettings settings;
    PcsStudy study;
  };

  // One map (command_map.cc): its grid and each cell's rows of map.csv
  // (map_files.h's format_map_rows) with the wall time of the cell.
  struct MapCells
  {
    Scene base; // the scene file with the overrides
    MapGrid grid;
    std::vector<std::string> rows; // rows[c]: cell c's lines of map.csv
    std::vector<double> wall_seconds; // per cell
    double work_seconds = 0;       // all cells
  };
} // namespace beamslider
