// The allocation counter, see heap_counter.h.
#include "verification/benchmarks/heap_counter.h"

#include <atomic>
#include <cstddef>

namespace
{
  std::atomic<bool> counting{false};
  std::atomic<unsigned long> allocations{0};

  void count()
  {
    if (counting.load(std::memory_order_relaxed))
      allocations.fetch_add(1, std::memory_order_relaxed);
  }
} // namespace

extern "C"
{
  void *__libc_malloc(std::size_t);
  void *__libc_calloc(std::size_t, std::size_t);
  void *__libc_realloc(void *, std::size_t);

  void *malloc(std::size_t size)
  {
    count();
    return __libc_malloc(size);
  }
  void *calloc(std::size_t n, std::size_t size)
  {
    count();
    return __libc_calloc(n, size);
  }
  void *realloc(void *p, std::size_t size)
  {
    count();
    return __libc_realloc(p, size);
  }
}

namespace beamslider::heap_counter
{
  void start()
  {
    allocations = 0;
    counting    = true;
  }

  unsigned long stop()
  {
    counting = false;
    return allocations.load();
  }
} // namespace beamslider::heap_counter
