// Counts heap allocations (malloc, calloc, realloc) while switched on: the
// evidence for "the ROM step allocates nothing" in the allocation test and
// the allocations-per-step figure of the benchmarks.
//
// Linking heap_counter.cc into an executable interposes malloc, calloc and
// realloc for the whole process (glibc lets the executable define them and
// forward to __libc_malloc & co.). Eigen allocates with malloc directly, not
// through operator new, which is why the counter sits at this level;
// operator new calls malloc and is counted as well. Off, it costs one
// relaxed atomic load per allocation.
#pragma once

namespace beamslider::heap_counter
{
  // Zero the count and count from now on.
  void start();
  // Stop counting; returns the allocations since start().
  unsigned long stop();
} // namespace beamslider::heap_counter
