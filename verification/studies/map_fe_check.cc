// The map's classes checked by the FE, see map_fe_check.h.
#include "verification/studies/map_fe_check.h"

#include "verification/studies/ensemble.h"
#include "verification/studies/fe_rom_study.h"
#include "runtime/parallel_for.h"

#include <algorithm>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    // Every k-th of `from`, n of them, spread from the first to the last.
    std::vector<std::size_t> evenly(const std::vector<std::size_t> &from, const unsigned int n)
    {
      if (from.size() <= n)
        return from;
      std::vector<std::size_t> out;
      for (unsigned int k = 0; k < n; ++k)
        out.push_back(from[n == 1 ? 0 : k * (from.size() - 1) / (n - 1)]);
      return out;
    }
  } // namespace

  std::vector<std::size_t> spot_check_cells(const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells,
                                            const unsigned int n_boundary, const unsigned int n_interior)
  {
    if (grid.axes.size() != 2 || cells.size() != grid.n_cells())
      throw std::invalid_argument("spot_check_cells: a computed map of two axes");
    const std::size_t n1 = grid.axes[1].values.size(), n0 = grid.axes[0].values.size();
    const auto class_of = [&](const std::size_t i, const std::size_t j) {
      const auto &c = cells[i * n1 + j];
      return c.empty() ? AdaptationClass::failed : c.front().analysis.outcome;
    };
    std::vector<std::size_t> boundary, interior;
    for (std::size_t i = 0; i < n0; ++i)
      for (std::size_t j = 0; j < n1; ++j)
        {
          const AdaptationClass here = class_of(i, j);
          if (here == AdaptationClass::failed)
            continue;
          bool differs = false;
          if (i > 0)
            differs = differs || class_of(i - 1, j) != here;
          if (i + 1 < n0)
            differs = differs || class_of(i + 1, j) != here;
          if (j > 0)
            differs = differs || class_of(i, j - 1) != here;
          if (j + 1 < n1)
            differs = differs || class_of(i, j + 1) != here;
          if (differs)
            boundary.push_back(i * n1 + j);
          else if (here == AdaptationClass::signature_move)
            interior.push_back(i * n1 + j);
        }
    std::vector<std::size_t> sample = evenly(boundary, n_boundary);
    for (const std::size_t c : evenly(interior, n_interior))
      sample.push_back(c);
    return sample;
  }

  std::vector<MapSpotCheck> run_map_spot_checks(const std::string &scene_file, const std::vector<std::string> &overrides,
                                                const MapGrid &grid, const std::vector<std::vector<MapMember>> &cells,
                                                const std::vector<std::size_t> &sample, const double end_time)
  {
    std::vector<MapSpotCheck> checks(sample.size());
    // Two runs per cell (the FE at its step and at half of it), longest
    // first: the half steps, then the others.
    const std::size_t n = sample.size();
    parallel_for(2 * n, 0, [&](const std::size_t job) {
      const bool half        = job < n;
      const std::size_t k    = job % n;
      const Scene scene      = map_cell_scene(scene_file, overrides, grid, sample[k], end_time);
      ModelSetting fe        = scene_model(scene, "fe");
      if (half)
        fe.time_step /= 2;
      const EnsembleMember m = run_member(scene, fe, 0, 0);
      MapSpotCheck &c        = checks[k];
      (half ? c.fe_half : c.fe)                                        = m.analysis.outcome;
      (half ? c.fe_half_final_position : c.fe_final_position)          = m.analysis.final_position;
    });
    // Boundary cells by the same rule as the sample's.
    const std::vector<std::size_t> all_boundary = spot_check_cells(grid, cells, grid.n_cells(), 0);
    for (std::size_t k = 0; k < n; ++k)
      {
        MapSpotCheck &c = checks[k];
        c.cell          = sample[k];
        c.values        = grid.cell_values(sample[k]);
        c.rom           = cells[sample[k]].empty() ? AdaptationClass::failed : cells[sample[k]].front().analysis.outcome;
        c.boundary = std::find(all_boundary.begin(), all_boundary.end(), sample[k]) != all_boundary.end();
      }
    return checks;
  }
} // namespace beamslider
