// `simulate --model auto`: the cheapest model whose ensemble end state lies
// within a tolerance of the FE reference's, decided on the error ladder of
// the scene (error_ladder.h, the quick ladder: 4 members over 25 s), never
// on a wall-clock time.
//
// The ladder is computed on demand and cached in
//   <cache_dir>/ladder-<key>.csv
// where <key> is a hash of everything in the scene that the ladder's
// outcome depends on (beam, supports, slider, contact, damping, excitation,
// start position, mesh, N, Δt, the FE's Δt and θ; not the name, end time or
// output rate). A
// changed scene gets a new key, so a stale cache is never read.
// Columns: rung,family,n_modes,n_elements,integrator,time_step_s,
//          damped_modes,theta,reference,cost_units,final_x_median,w1,w1_high
#pragma once

#include "meshes/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <string>
#include <vector>

namespace beamslider
{
  // A hexadecimal 64-bit FNV-1a hash of the scene's physical content.
  std::string scene_content_key(const Scene &scene);

  struct LadderChoiceRow
  {
    std::string rung;
    ModelSetting model;
    bool reference               = false;
    double cost_units            = 0; // one member over the ladder's window
    double final_x_median        = 0;
    double w1 = 0, w1_high = 0;       // to the reference; 0 for the reference
  };

  // The cheapest row (by cost_units) whose W₁ interval to the reference ends
  // at or below `tolerance` (in x_C/L); the reference always qualifies.
  const LadderChoiceRow &cheapest_within(const std::vector<LadderChoiceRow> &rows, double tolerance);

  // Reads the cached ladder for `scene` from `cache_dir`, or runs the quick
  // ladder and writes the cache; then picks by cheapest_within. The
  // numbers it decided on go to `why`.
  ModelSetting choose_model(const Scene &scene, double tolerance, const std::string &cache_dir, std::string &why);
} // namespace beamslider
