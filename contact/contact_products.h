// The Moreau step's small products of the contact block (2m ≤ 8 directions),
// written out: calls into Eigen's product kernels cost more than their
// arithmetic for a reduced model's few modes. Each sums in the order of the
// Eigen expression it stands for, with the build's SSE2 packets (no -march),
// so a step keeps its bits; tests/test_contact_slider.cc checks them against
// those expressions on random data.
#pragma once

#include <Eigen/Dense>

namespace beamslider
{
  // The relative velocities of the contact directions,
  //   out = W_bᵀ u + W_sᵀ v + imposed,
  // each entry summed as the three Eigen expressions W_bᵀu (its row-major
  // matrix–vector kernel with SSE2's two-lane packets, the build's; no
  // -march: two running sums over the entry pairs, the lanes added, then
  // the odd last entry, added into a zeroed result), += W_sᵀv (a lazy
  // product, left to right) and += imposed would sum it, so `out` has
  // their bits without the calls.
  template <typename BeamBlock, typename SliderBlock, typename Imposed, typename Out>
  void relative_velocities(const BeamBlock &W_b, const SliderBlock &W_s, const Imposed &imposed,
                           const Eigen::VectorXd &u, const Eigen::Vector3d &v, Out &&out)
  {
    const Eigen::Index n = u.size();
    const double *b      = u.data();
    for (Eigen::Index k = 0; k < W_b.cols(); ++k)
      {
        const double *a = W_b.col(k).data();
        double lane_0 = 0., lane_1 = 0.;
        Eigen::Index j = 0;
        for (; j + 2 <= n; j += 2)
          {
            lane_0 = a[j] * b[j] + lane_0;
            lane_1 = a[j + 1] * b[j + 1] + lane_1;
          }
        double sum = lane_0 + lane_1;
        for (; j < n; ++j)
          sum += a[j] * b[j];
        double entry = 0. + sum; // the kernel adds into a zeroed result: −0 becomes +0
        entry += (W_s(0, k) * v[0] + W_s(1, k) * v[1]) + W_s(2, k) * v[2];
        out[k] = entry + imposed[k];
      }
  }

  // G += W_sᵀ M_s⁻¹ W_s for the slider's inverse mass M_s⁻¹ = diag(inv_mass),
  // each entry summed left to right as Eigen's lazy product
  // (W_sᵀ diag(inv_mass)) · W_s sums it.
  template <typename SliderBlock, typename Matrix>
  void add_slider_part(const SliderBlock &W_s, const Eigen::Vector3d &inv_mass, Matrix &&G)
  {
    for (Eigen::Index j = 0; j < W_s.cols(); ++j)
      for (Eigen::Index i = 0; i < W_s.cols(); ++i)
        G(i, j) += (W_s(0, i) * inv_mass[0]) * W_s(0, j) + (W_s(1, i) * inv_mass[1]) * W_s(1, j) +
                   (W_s(2, i) * inv_mass[2]) * W_s(2, j);
  }

  // out += X P, each row's sum left to right and then added, as Eigen's
  // lazy product sums it.
  template <typename Matrix, typename Vector>
  void add_product(const Matrix &X, const Vector &P, Eigen::VectorXd &out)
  {
    const Eigen::Index cols = P.size();
    for (Eigen::Index r = 0; r < out.size(); ++r)
      {
        double sum = X(r, 0) * P[0];
        for (Eigen::Index k = 1; k < cols; ++k)
          sum += X(r, k) * P[k];
        out[r] += sum;
      }
  }
} // namespace beamslider
