// The reduced model's time step allocates no heap memory (issue: speed). A
// counting malloc is switched on for 1000
// steps of the signature-move scene with the slider rattling on the beam
// (contacts active in most steps); any allocation inside a step — an Eigen
// temporary of dynamic size, a std::function, a string — shows up here.
#include "contact/adaptation_run.h"
#include "meshes/scene.h"
#include "verification/studies/fe_rom_study.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>

namespace
{
  std::atomic<bool> counting{false};
  std::atomic<unsigned long> allocations{0};
} // namespace

// Eigen allocates with malloc directly (aligned_malloc), not through
// operator new, so the counter sits one level lower: glibc lets an
// executable interpose malloc, calloc and realloc (operator new calls malloc).
extern "C"
{
  void *__libc_malloc(std::size_t);
  void *__libc_calloc(std::size_t, std::size_t);
  void *__libc_realloc(void *, std::size_t);

  void *malloc(std::size_t size)
  {
    if (counting.load(std::memory_order_relaxed))
      allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_malloc(size);
  }
  void *calloc(std::size_t n, std::size_t size)
  {
    if (counting.load(std::memory_order_relaxed))
      allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_calloc(n, size);
  }
  void *realloc(void *p, std::size_t size)
  {
    if (counting.load(std::memory_order_relaxed))
      allocations.fetch_add(1, std::memory_order_relaxed);
    return __libc_realloc(p, size);
  }
}

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

  MoreauStepper &stepper = run.stepper();
  unsigned long with_contact = 0;
  allocations = 0;
  counting    = true;
  for (int k = 0; k < 1000; ++k)
    with_contact += stepper.step().n_active > 0;
  counting = false;
  std::cout << "ROM step: " << allocations.load() / 1000. << " heap allocations per step, " << with_contact
            << " of 1000 steps with contact" << std::endl;
  EXPECT_GT(with_contact, 100u) << "the slider must be in contact for the count to mean anything";
  EXPECT_EQ(allocations.load(), 0u);
}
