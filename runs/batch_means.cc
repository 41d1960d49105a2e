// Batch-means confidence interval, see batch_means.h.
#include "runs/batch_means.h"

#include <cmath>
#include <limits>

namespace beamslider
{
  namespace
  {
    // Student's t, two-sided 95 %, for ν = 1 … 30 degrees of freedom; the
    // normal 1.96 beyond.
    double t_975(const unsigned int nu)
    {
      static const double table[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                     2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                     2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
      return nu >= 1 && nu <= 30 ? table[nu - 1] : 1.96;
    }
  } // namespace

  BatchMeansInterval batch_means_interval(const std::vector<double> &series, const unsigned int n_batches)
  {
    BatchMeansInterval r;
    const std::size_t n = series.size();
    if (n == 0)
      {
        r.mean = r.half_width = std::numeric_limits<double>::quiet_NaN();
        return r;
      }
    const unsigned int B      = static_cast<unsigned int>(std::min<std::size_t>(n_batches, n));
    const std::size_t length  = n / B;
    const std::size_t skipped = n - B * length;
    std::vector<double> means(B, 0.);
    for (unsigned int b = 0; b < B; ++b)
      {
        for (std::size_t k = 0; k < length; ++k)
          means[b] += series[skipped + b * length + k];
        means[b] /= length;
      }
    double mean = 0;
    for (const double m : means)
      mean += m / B;
    r.mean      = mean;
    r.n_batches = B;
    if (B < 2)
      {
        r.half_width = std::numeric_limits<double>::infinity();
        return r;
      }
    double var = 0;
    for (const double m : means)
      var += (m - mean) * (m - mean) / (B - 1);
    r.half_width = t_975(B - 1) * std::sqrt(var / B);
    return r;
  }
} // namespace beamslider
