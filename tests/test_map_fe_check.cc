// The sample of map cells the FE checks (verification/studies/
// map_fe_check.h): boundary cells found on a synthetic map whose classes are
// set by hand, the interior signature-move cells, the spread of the sample.
#include "verification/studies/map_fe_check.h"

#include <gtest/gtest.h>

using namespace beamslider;

namespace
{
  // A 4 × 5 map (frequency × level): signature moves where level ≥ 2,
  // no adaptation below.
  std::vector<std::vector<MapMember>> synthetic_map(const MapGrid &grid)
  {
    std::vector<std::vector<MapMember>> cells(grid.n_cells());
    for (std::size_t c = 0; c < cells.size(); ++c)
      {
        MapMember m;
        m.analysis.valid   = true;
        m.analysis.outcome = c % 5 >= 2 ? AdaptationClass::signature_move : AdaptationClass::no_adaptation;
        cells[c]           = {m};
      }
    return cells;
  }
} // namespace

TEST(MapFeCheck, SamplesBoundaryCellsThenInteriorSignatureMoves)
{
  MapGrid grid;
  grid.axes = {{"Excitation/Frequency", "frequency_hz", {110, 115, 120, 125}},
               {"Excitation/Acceleration amplitude", "acceleration_m_s2", {4, 8, 12, 16, 20}}};
  const auto cells = synthetic_map(grid);
  // Every boundary cell: levels 1 and 2 of each frequency (8 cells).
  const std::vector<std::size_t> all = spot_check_cells(grid, cells, 100, 0);
  ASSERT_EQ(all.size(), 8u);
  for (const std::size_t c : all)
    EXPECT_TRUE(c % 5 == 1 || c % 5 == 2) << c;
  // Three of them spread from the first to the last, then two interior
  // signature moves (levels 3 and 4 of every frequency), spread likewise.
  const std::vector<std::size_t> sample = spot_check_cells(grid, cells, 3, 2);
  ASSERT_EQ(sample.size(), 5u);
  EXPECT_EQ(sample[0], all.front());
  EXPECT_EQ(sample[2], all.back());
  for (std::size_t k = 3; k < 5; ++k)
    {
      EXPECT_GE(sample[k] % 5, 3u);
      EXPECT_EQ(cells[sample[k]].front().analysis.outcome, AdaptationClass::signature_move);
    }
  EXPECT_NE(sample[3], sample[4]);
  // A one-axis grid is not a map it can check.
  MapGrid line;
  line.axes = {grid.axes[0]};
  EXPECT_THROW(spot_check_cells(line, std::vector<std::vector<MapMember>>(4), 1, 1), std::invalid_argument);
}
