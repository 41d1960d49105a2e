// The error ladder that `--model auto` decides on
// (verification/studies/model_choice.h), computed on demand and cached in
//   <cache_dir>/ladder-<key>.csv
// where <key> is scene_content_key(scene): a changed scene gets a new key,
// so a stale cache is never read. Its first line names the format, the
// build that wrote it and the FNV-1a checksum of the CSV below it; a cache
// that fails any check (another build or format, a changed byte, a cell
// that is not a number, not exactly one reference row) is computed again
// with a one-line notice, and a cache that cannot be written leaves the
// choice standing with a notice. CSV columns: rung,family,n_modes,static_corrections,ritz_blocks,n_elements,integrator,time_step_s,
//          damped_modes,theta,reference,cost_units,final_x_median,w1,w1_high,
//          refined_alike
#pragma once

#include "scene/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <optional>
#include <string>

namespace beamslider
{
  // The cache file's text for the CSV `csv` (header line and rows): the
  // first line that seals it, then the CSV.
  std::string choice_cache_file_text(const std::string &csv);

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
