// `beamslider branches` end to end on a short range: the attached model's
// orbits it continues are the ones shooting finds at each position from the
// linear steady state (an independent path to the same orbit), the probes
// cover the range, and bad input is refused before any run.
#include "reduced/attached_slider_model.h"
#include "scene/scene.h"
#include "tests/cli_runner.h"
#include "verification/studies/fe_rom_study.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

using namespace beamslider;
using namespace beamslider::testing;

TEST(CliBranches, ContinuedOrbitsAreTheOnesShootingFindsAtEachPosition)
{
  const auto dir   = fresh_folder("branches");
  const CliRun run = run_beamslider({"branches", "mueller2023", "--from", "0.3", "--to", "0.34", "--probe-step",
                                     "0.02", "--settle-periods", "10", "--quiet", "--output", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto probes = read_csv_cells(dir / "attractor.csv");
  ASSERT_EQ(probes.size(), 4u); // header and 0.30, 0.32, 0.34
  const auto rows = read_csv_cells(dir / "branches.csv");
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(rows[0][0], "x_over_L");

  // The scene's ROM and its attached model, as the command builds them.
  const Scene scene           = read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm");
  const ReducedOrderModel rom = make_reduced_model(scene, scene_model(scene, "rom"));
  const AttachedSliderModel model(rom, scene.slider_mass(), scene.slider_inertia(), scene.contact.gravity,
                                  BaseExcitation::from_scene(scene.excitation), scene.beam.thickness);
  for (const std::size_t i : {std::size_t(1), rows.size() / 2, rows.size() - 1})
    {
      const double x = std::stod(rows[i][0]), amplitude = std::stod(rows[i][1]);
      EXPECT_GE(x, 0.3 - 1e-12);
      EXPECT_LE(x, 0.34 + 0.01); // the last point may step past the end
      ShootingSettings s;
      const Eigen::VectorXd y0 = model.linear_response(x);
      s.scale                  = model.scale(y0);
      s.tolerance              = 1e-9;
      const ShootingOutcome out = shoot(model, y0, x, s);
      ASSERT_TRUE(out.converged) << out.reason;
      EXPECT_NEAR(amplitude, out.point.observables[0], 1e-5 * amplitude) << "x_C/L = " << x;
      EXPECT_EQ(rows[i][3], out.point.stable() ? "1" : "0");
    }
}

TEST(CliBranches, RefusesBadInputBeforeAnyRun)
{
  const auto dir = fresh_folder("branches_errors");
  const CliRun reversed =
    run_beamslider({"branches", "mueller2023", "--from", "0.4", "--to", "0.3", "--output", dir.string()});
  EXPECT_EQ(reversed.exit_code, 2);
  EXPECT_NE(reversed.err.find("high x_C/L"), std::string::npos) << reversed.err;
  const CliRun off_beam = run_beamslider({"branches", "mueller2023", "--from", "0.01", "--output", dir.string()});
  EXPECT_EQ(off_beam.exit_code, 2);
  EXPECT_NE(off_beam.err.find("low x_C/L = 0.01"), std::string::npos) << off_beam.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "branches.csv"));
}
