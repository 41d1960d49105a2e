// The wall time of a run or a stage, as a number: every layer's one clock
// reading (result structs, timing columns and checkpoints record it; the
// report's seconds_since writes it as text). Tables of named stages use
// deal.II's TimerOutput where deal.II is linked (verify's section times).
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
