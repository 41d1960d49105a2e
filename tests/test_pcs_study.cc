// Tests of the prescribed-position study's observer (verification/studies/
// pcs_sweep.h): the study writes nothing, so what its callers keep on disk
// while it runs (verification/report/pcs_files.h) is only what the observer
// hands them. A short ROM sweep of mueller2023 with a free run.
#include "verification/studies/pcs_sweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace beamslider;

// The observer hears first of the start (with the resonance curve and the
// planned count), then of every point and free period the study returns,
// each once, then of the free run's end once; the progress lines name both
// branches' last positions.
TEST(PcsStudy, TheObserverSeesWhatTheStudyReturns)
{
  const Scene scene = read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm");
  PcsStudySettings settings;
  settings.sweep              = PcsSweepSettings::for_scene(scene);
  settings.sweep.low_over_L   = 0.30;
  settings.sweep.high_over_L  = 0.32;
  settings.sweep.step_over_L  = 0.01;
  settings.sweep.settle_time  = 0.05;
  settings.sweep.average_time = 0.05;
  settings.free_time          = 0.2;

  bool started = false, point_before_start = false;
  std::size_t resonance_points = 0, planned = 0;
  std::vector<PcsPoint> points;
  std::vector<PeriodRecord> periods;
  unsigned int free_run_ends = 0;
  std::vector<std::string> progress;
  PcsSweepObserver observer;
  observer.on_start = [&](const PcsStudy &s) {
    started          = true;
    resonance_points = s.resonance.size();
    planned          = s.positions_planned;
  };
  observer.on_point = [&](const PcsPoint &p) {
    point_before_start |= !started;
    points.push_back(p);
  };
  observer.on_free_period  = [&](const PeriodRecord &r) { periods.push_back(r); };
  observer.on_free_run_end = [&](const RunResult &) { ++free_run_ends; };
  observer.on_progress     = [&](const std::string &line) { progress.push_back(line); };

  const PcsStudy study = run_pcs_sweep(scene, settings, observer);

  ASSERT_TRUE(started);
  EXPECT_FALSE(point_before_start);
  EXPECT_EQ(resonance_points, study.resonance.size());
  EXPECT_EQ(resonance_points, 201u) << "mueller2023 has the geometric nonlinearity";
  EXPECT_EQ(planned, 3u);
  EXPECT_EQ(study.positions_planned, 3u);
  EXPECT_TRUE(study.with_free_run);
  ASSERT_EQ(study.up.points.size(), 3u);
  ASSERT_EQ(study.down.points.size(), 3u);
  ASSERT_EQ(points.size(), 6u);
  for (const PcsBranch *branch : {&study.up, &study.down})
    {
      std::vector<PcsPoint> heard;
      for (const PcsPoint &p : points)
        if (p.direction == branch->direction)
          heard.push_back(p);
      ASSERT_EQ(heard.size(), branch->points.size());
      for (std::size_t i = 0; i < heard.size(); ++i)
        {
          EXPECT_EQ(heard[i].x_over_L, branch->points[i].x_over_L);
          EXPECT_EQ(heard[i].amplitude_over_h, branch->points[i].amplitude_over_h);
          EXPECT_EQ(heard[i].mean_fx, branch->points[i].mean_fx);
        }
    }
  ASSERT_FALSE(study.free_periods.empty());
  ASSERT_EQ(periods.size(), study.free_periods.size());
  for (std::size_t i = 0; i < periods.size(); ++i)
    EXPECT_EQ(periods[i].amplitude_over_h, study.free_periods[i].amplitude_over_h);
  EXPECT_EQ(free_run_ends, 1u);
  for (const std::string direction : {"up", "down"})
    EXPECT_TRUE(std::any_of(progress.begin(), progress.end(), [&](const std::string &line) {
      return line.rfind("  sweep " + direction + ": 3/3 positions, x_C/L = ", 0) == 0;
    })) << direction;
}
