// runtime/parallel_for.h: every item runs exactly once on any
// number of threads, items start in ascending order, no more run at once
// than asked for, and an item that throws ends the loop with that exception
// in the caller (all threads joined, every started item finished) instead
// of std::terminate.
#include "runtime/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
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

namespace
{
  // The items in the order their bodies started.
  class StartRecord
  {
  public:
    void start(const std::size_t i)
    {
      const std::lock_guard<std::mutex> lock(mutex);
      order.push_back(i);
    }
    std::vector<std::size_t> order;

  private:
    std::mutex mutex;
  };

  void some_work(const std::size_t amount)
  {
    volatile double x = 0;
    for (std::size_t k = 0; k < amount; ++k)
      x = x + 1e-9 * k;
  }
} // namespace

TEST(ParallelFor, ItemsStartInAscendingOrder)
{
  // On one thread the order is exact.
  StartRecord one;
  parallel_for(50, 1, [&](const std::size_t i) { one.start(i); });
  for (std::size_t k = 0; k < one.order.size(); ++k)
    EXPECT_EQ(one.order[k], k);

  // On w threads, item j is handed out after every item i < j; of those,
  // only the at most w - 1 that the other threads hold and have not yet
  // started can start after j. (Items handed out in any other order, e.g.
  // in blocks per thread, break this for some j.)
  for (const unsigned int threads : {2u, 3u})
    {
      const std::size_t n = 200;
      StartRecord several;
      parallel_for(n, threads, [&](const std::size_t i) {
        several.start(i);
        some_work(1000 * (i % 7));
      });
      ASSERT_EQ(several.order.size(), n);
      std::vector<std::size_t> position(n);
      for (std::size_t k = 0; k < n; ++k)
        position[several.order[k]] = k;
      for (std::size_t j = 0; j < n; ++j)
        {
          std::size_t earlier_items_started_later = 0;
          for (std::size_t i = 0; i < j; ++i)
            earlier_items_started_later += position[i] > position[j];
          EXPECT_LE(earlier_items_started_later, threads - 1) << "item " << j << " on " << threads << " threads";
        }
    }
}

TEST(ParallelFor, NoMoreItemsRunAtOnceThanThreads)
{
  for (const unsigned int threads : {1u, 2u})
    {
      std::atomic<int> running{0}, most{0};
      parallel_for(100, threads, [&](std::size_t) {
        const int now = ++running;
        for (int seen = most.load(); now > seen && !most.compare_exchange_weak(seen, now);)
          ;
        some_work(20000);
        --running;
      });
      EXPECT_LE(most.load(), static_cast<int>(threads));
    }
}

TEST(ParallelFor, AThrowingItemReachesTheCallerAndStopsFurtherItems)
{
  // Item 3 throws. On one thread the order is fixed: items 0-3 run, the
  // exception arrives here, and no later item starts.
  {
    std::vector<int> started;
    try
      {
        parallel_for(1000, 1, [&](const std::size_t i) {
          started.push_back(static_cast<int>(i));
          if (i == 3)
            throw std::runtime_error("item 3 failed");
        });
        ADD_FAILURE() << "no exception on one thread";
      }
    catch (const std::runtime_error &e)
      {
        EXPECT_STREQ(e.what(), "item 3 failed");
      }
    EXPECT_EQ(started, (std::vector<int>{0, 1, 2, 3}));
  }
  // On several threads, how many items the other threads start while the
  // throwing one unwinds depends on the scheduler (once, with the other core
  // busy, the second thread ran all 1000 items in that time). So only what
  // holds under every schedule is asserted there: the exception arrives
  // with its message, no item runs twice, and every item that started had
  // finished when it arrived (none still runs in the caller's back).
  for (const unsigned int threads : {2u, 4u})
    {
      const std::size_t n = 1000;
      std::vector<std::atomic<int>> calls(n);
      std::atomic<int> started{0}, finished{0};
      try
        {
          parallel_for(n, threads, [&](const std::size_t i) {
            ++started;
            ++calls[i];
            if (i == 3)
              {
                ++finished;
                throw std::runtime_error("item 3 failed");
              }
            some_work(20000);
            ++finished;
          });
          ADD_FAILURE() << "no exception on " << threads << " threads";
        }
      catch (const std::runtime_error &e)
        {
          EXPECT_STREQ(e.what(), "item 3 failed");
          EXPECT_EQ(finished.load(), started.load()) << "an item still ran when the exception arrived";
        }
      for (std::size_t i = 0; i < n; ++i)
        EXPECT_LE(calls[i].load(), 1) << "item " << i << " on " << threads << " threads";
      EXPECT_EQ(calls[3].load(), 1);
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
