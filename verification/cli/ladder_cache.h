// The error ladder that `--model auto` decides on
// (verification/studies/model_choice.h), computed on demand and cached in
//   <cache_dir>/ladder-<key>.csv
// where <key> is scene_content_key(scene): a changed scene gets a new key,
// so a stale cache is never read.
// Columns: rung,family,n_modes,static_corrections,ritz_blocks,n_elements,integrator,time_step_s,
//          damped_modes,theta,reference,cost_units,final_x_median,w1,w1_high,
//          refined_alike
#pragma once

#include "meshes/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <optional>
#include <string>

namespace beamslider
{
  // Where the commands keep the cache: beside the scene's reports,
  // reports/<scene>/model_choice.
  std::string choice_cache_dir(const Scene &scene);

  // Reads the cached ladder for `scene` from `cache_dir`, or runs the quick
  // ladder (its progress on the console) and writes the cache; then picks
  // by cheapest_within at `tolerance`, or without one at
  // default_choice_tolerance. The numbers it decided on go to `why`.
  // Throws InputError for a solid scene (it has no beam ladder) and, on
  // n_ranks > 1, when the cache is missing: every rank would run the ladder.
  ModelSetting choose_model(const Scene &scene, std::optional<double> tolerance, const std::string &cache_dir,
                            std::string &why, unsigned int n_ranks = 1);
} // namespace beamslider
