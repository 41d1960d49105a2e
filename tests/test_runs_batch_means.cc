// Batch-means confidence intervals (runs/batch_means.h) on constructed
// series: exact values for a short series by hand, and the coverage of the
// 95 % interval for the mean of a strongly correlated AR(1) series (the
// rattling force of a held slider is correlated from period to period),
// where s/√n of the raw samples would cover far less often.
#include "runs/batch_means.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace beamslider;

TEST(BatchMeans, ShortSeriesByHand)
{
  // 10 values, 5 batches of 2: batch means 1.5, 3.5, 5.5, 7.5, 9.5; mean 5.5;
  // their standard deviation sqrt(10) (variance over B − 1 = 4: 40/4);
  // half width t_{0.975,4} · sqrt(10/5) = 2.776 · sqrt(2).
  const std::vector<double> x = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  const BatchMeansInterval r  = batch_means_interval(x, 5);
  EXPECT_EQ(r.n_batches, 5u);
  EXPECT_DOUBLE_EQ(r.mean, 5.5);
  EXPECT_NEAR(r.half_width, 2.776 * std::sqrt(2.), 1e-12);
  // The remainder is dropped at the start: 11 values in 5 batches of 2.
  std::vector<double> y = x;
  y.insert(y.begin(), 1000.);
  EXPECT_DOUBLE_EQ(batch_means_interval(y, 5).mean, 5.5);
  EXPECT_TRUE(std::isinf(batch_means_interval({3.}, 10).half_width));
}

TEST(BatchMeans, CoversTheMeanOfACorrelatedSeries)
{
  // x_k = m + a (x_{k−1} − m) + e_k, a = 0.9 (correlation time ~10 samples),
  // 400 samples per series (like 0.2 s … 3 s of periods), 10 batches.
  std::mt19937 random(3);
  std::normal_distribution<double> noise;
  const double m = 0.2, a = 0.9;
  unsigned int covered = 0, naive_covered = 0;
  const unsigned int trials = 1000;
  for (unsigned int t = 0; t < trials; ++t)
    {
      std::vector<double> x(400);
      double v = m + noise(random) / std::sqrt(1 - a * a);
      for (auto &xi : x)
        xi = v = m + a * (v - m) + noise(random);
      const BatchMeansInterval r = batch_means_interval(x, 10);
      covered += std::abs(r.mean - m) <= r.half_width;
      double mean = 0, var = 0;
      for (const double xi : x)
        mean += xi / x.size();
      for (const double xi : x)
        var += (xi - mean) * (xi - mean) / (x.size() - 1);
      naive_covered += std::abs(mean - m) <= 1.96 * std::sqrt(var / x.size());
    }
  const double coverage = double(covered) / trials, naive = double(naive_covered) / trials;
  std::cout << "coverage: batch means " << coverage << ", naive s/sqrt(n) " << naive << std::endl;
  EXPECT_GT(coverage, 0.88); // nominal 0.95; batches of 40 samples still carry some correlation
  EXPECT_LT(coverage, 0.99);
  EXPECT_LT(naive, 0.6) << "the naive interval ignores the correlation";
}
