// `--model auto`: the cheapest model whose ensemble end state lies within a
// tolerance of the FE reference's and that ends alike at half its step,
// decided on the error ladder of the scene (error_ladder.h, the quick
// ladder: 4 members over 25 s), never on a wall-clock time. That model is on
// the ladder's speed–accuracy front unless a cheaper one has the smaller W₁
// but the wider interval.
//
// The ladder is run here and its rows returned; the command line keeps them
// in a cache keyed by scene_content_key (verification/cli/ladder_cache.h),
// so that the choice on a known scene runs nothing.
#pragma once

#include "scene/scene.h"
#include "verification/studies/error_ladder.h"
#include "verification/studies/fe_rom_study.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  // The quick ladder the choice is decided on: members per rung, and the
  // window [s] (the end state of the published cases is reached by ~25 s).
  constexpr unsigned int choice_ladder_members = 4;
  constexpr double choice_ladder_end_time      = 25.;

  // A hexadecimal 64-bit FNV-1a hash of the scene's physical content: what
  // the ladder's outcome depends on (beam, supports, slider, contact,
  // damping, excitation, start position, mesh, N, Δt, the FE's Δt and θ; not
  // the name, end time or output rate), so a changed scene gets a new key.
  std::string scene_content_key(const Scene &scene);

  struct LadderChoiceRow
  {
    std::string rung;
    ModelSetting model;
    bool reference               = false;
    double cost_units            = 0; // one member over the ladder's window
    double final_x_median        = 0;
    // To the reference; for the reference, its own: to the refinement its
    // convergence check ran beside the accepted step (0 if none).
    double w1 = 0, w1_high = 0;
    bool refined_alike = true; // its refinement check (Δt/2, or N) ended alike, or it has none
  };

  // The rows of a ladder's rungs.
  std::vector<LadderChoiceRow> choice_rows(const LadderStudy &study);

  // The smallest tolerance the choice grants when none is given [x_C/L]:
  // the bar of a reduced model that lands where the FE lands (the front's,
  // doc/verification.md §6).
  constexpr double choice_tolerance_floor = 0.005;
  // The tolerance when none is given: the upper end of the reference's own
  // W₁ interval to its refinement (how well the reference knows its end
  // state), at least choice_tolerance_floor.
  double default_choice_tolerance(const std::vector<LadderChoiceRow> &rows);

  // Whether a reduced model's row lands where the reference lands: it ended
  // alike refined and its W₁ interval to the reference ends at or below
  // `tolerance` (in x_C/L). The rule of the choice and of the report's
  // budget paragraph alike.
  bool lands_within(const LadderChoiceRow &row, double tolerance);

  // The cheapest row (by cost_units) that lands_within `tolerance`; the
  // reference always qualifies.
  const LadderChoiceRow &cheapest_within(const std::vector<LadderChoiceRow> &rows, double tolerance);

  // The quick ladder of `scene` run: a row per rung, and the verdicts of
  // its convergence checks. `before_rung` (optional) as run_ladder's.
  struct ChoiceLadder
  {
    std::vector<LadderChoiceRow> rows;
    std::vector<std::string> check_verdicts;
  };
  ChoiceLadder run_choice_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, std::size_t reference,
                                 const std::function<void(const LadderRung &, std::size_t)> &before_rung = {});

  // The pick among the ladder's rows by cheapest_within, the model set for
  // `scene` (the FE reference on the scene's mesh), and the numbers it was
  // decided on, a line each.
  struct ModelChoice
  {
    ModelSetting model;
    std::string why;
  };
  ModelChoice choose_from_ladder(const Scene &scene, const std::vector<LadderChoiceRow> &rows, double tolerance);
  // The same with the tolerance default_choice_tolerance gives.
  ModelChoice choose_from_ladder(const Scene &scene, const std::vector<LadderChoiceRow> &rows);
} // namespace beamslider
