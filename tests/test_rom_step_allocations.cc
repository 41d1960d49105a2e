// The reduced model's time step allocates no heap memory (issue: speed). A
// counting malloc (verification/benchmarks/heap_counter.h) is switched on for
// 0.1 s (5000 steps) of the signature-move scene with the slider rattling on
// the beam (contacts active in most steps); any allocation inside a step or
// at a period's end — an Eigen temporary of dynamic size, a std::function, a
// string — shows up here. The trace is not written (no output stream).
#include "runs/adaptation_run.h"
#include "scene/scene.h"
#include "verification/benchmarks/heap_counter.h"
#include "verification/studies/fe_rom_study.h"

#include <gtest/gtest.h>

#include <iostream>

using namespace beamslider;

TEST(RomStep, AllocatesNothingOnTheHeap)
{
  Scene scene = read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm");
  ModelSetting setting;
  setting.n_modes   = scene.discretisation.n_modes;
  setting.time_step = scene.time_stepping.time_step;
  auto beam         = make_beam_model(scene, setting);
  RunOptions options        = RunOptions::from_scene(scene);
  options.progress_interval = 1e300;
  AdaptationRun run(scene, *beam, options);
  // Warm up into the rattling regime (the scratch reaches its sizes).
  ASSERT_EQ(run.run_until(0.5).status, RunStatus::completed);

  // 0.1 s more: 5000 steps and a dozen excitation periods, so that what the
  // run does per period (energy balance, period record) is counted too.
  heap_counter::start();
  const RunResult result          = run.run_until(0.6);
  const unsigned long allocations = heap_counter::stop();
  ASSERT_EQ(result.status, RunStatus::completed);
  std::cout << "ROM run: " << allocations << " heap allocations in " << result.n_steps << " steps, "
            << result.n_contact_steps << " of them with contact" << std::endl;
  EXPECT_GT(result.n_contact_steps, result.n_steps / 10) << "the slider must be in contact for the count to mean anything";
  EXPECT_EQ(allocations, 0u);
}
