// The wall time of a run or a stage, as a number (summaries, timing
// columns and checkpoints record it; number_text.h's seconds_since writes
// it as text).
#pragma once

#include <chrono>

namespace beamslider
{
  // Seconds of wall time since `start`.
  inline double elapsed_seconds(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
} // namespace beamslider
