// The mean of a correlated series with a confidence interval by batch
// means: split the series into B consecutive batches, take each batch's
// mean; if the batches are long against the correlation time, their means
// are nearly independent and normal, so
//   mean ± t_{0.975, B−1} · s_B / √B,   s_B the standard deviation of the batch means,
// is a 95 % interval for the mean (Law & Kelton; Alexopoulos & Seila 1998).
// Used for the period-averaged horizontal contact force F̄_x of the
// prescribed-position sweeps: the rattling makes successive periods
// correlated, so s/√n of the raw periods would claim far too much precision.
#pragma once

#include <vector>

namespace beamslider
{
  struct BatchMeansInterval
  {
    double mean = 0;
    double half_width = 0; // 95 % interval: mean ± half_width (infinite with < 2 batches)
    unsigned int n_batches = 0;
  };

  // B batches of equal length (the remainder at the start is dropped: it is
  // the part nearest the settling transient).
  BatchMeansInterval batch_means_interval(const std::vector<double> &series, unsigned int n_batches = 10);
} // namespace beamslider
