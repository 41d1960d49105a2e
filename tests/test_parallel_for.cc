// verification/studies/parallel_for.h: every item runs exactly once on any
// number of threads, and an item that throws ends the loop with that
// exception in the caller (all threads joined) instead of std::terminate.
#include "verification/studies/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

using namespace beamslider;

TEST(ParallelFor, EveryItemRunsExactlyOnce)
{
  for (const unsigned int threads : {0u, 1u, 2u, 7u})
    for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(100)})
      {
        std::vector<std::atomic<int>> calls(n);
        parallel_for(n, threads, [&](const std::size_t i) { ++calls[i]; });
        for (std::size_t i = 0; i < n; ++i)
          EXPECT_EQ(calls[i].load(), 1) << "item " << i << " of " << n << " on " << threads << " threads";
      }
}

TEST(ParallelFor, AThrowingItemReachesTheCallerAndStopsFurtherItems)
{
  // Item 3 throws; on 1, 2 and 4 threads the exception (with its message)
  // must arrive here, and items not yet started when it was thrown must not
  // start: with ascending hand-out, at most one item per other thread begins
  // after it.
  for (const unsigned int threads : {1u, 2u, 4u})
    {
      const std::size_t n = 1000;
      std::atomic<std::size_t> started{0};
      try
        {
          parallel_for(n, threads, [&](const std::size_t i) {
            ++started;
            if (i == 3)
              throw std::runtime_error("item 3 failed");
          });
          ADD_FAILURE() << "no exception on " << threads << " threads";
        }
      catch (const std::runtime_error &e)
        {
          EXPECT_STREQ(e.what(), "item 3 failed");
        }
      EXPECT_LT(started.load(), n) << threads << " threads went on after the failure";
    }
}

TEST(ParallelFor, TheMainThreadsFailureJoinsTheOthers)
{
  // Whichever of the two threads takes item 0 throws while the other is busy
  // with a slow item. Before parallel_for caught it, a throw on the calling
  // thread destroyed the other, still joinable, thread ("terminate called
  // without an active exception"), and a throw on the other ended the
  // program at once.
  std::atomic<int> finished{0};
  EXPECT_THROW(parallel_for(8, 2,
                            [&](const std::size_t i) {
                              if (i == 0)
                                throw std::invalid_argument("bad item");
                              volatile double x = 0;
                              for (int k = 0; k < 200000; ++k)
                                x = x + 1e-9 * k;
                              ++finished;
                            }),
               std::invalid_argument);
  EXPECT_LE(finished.load(), 7);
}
