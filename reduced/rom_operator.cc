#include "reduced/rom_operator.h"

#include <array>
#include <algorithm>

namespace beamslider
{
  ReducedOrderModel::ReducedOrderModel(ModalBasis basis, const double damping_ratio, const bool geometric_nonlinearity)
    : basis_(std::move(basis))
    , damping_ratio_(damping_ratio)
    , nonlinear_(geometric_nonlinearity)
  {
    set_damped_modes(n_modes());
  }

  void ReducedOrderModel::set_damped_modes(const unsigned int n_damped)
  {
    n_damped_ = std::min(n_damped, n_modes());
    damping_  = Eigen::VectorXd::Zero(n_modes());
    damping_.head(n_damped_) = 2. * damping_ratio_ * basis_.omega.head(n_damped_);
  }

  void ReducedOrderModel::set_cubic_terms(std::vector<CubicTerm> terms)
  {
    terms_ = std::move(terms);
  }

  Eigen::VectorXd ReducedOrderModel::nonlinear_force(const Eigen::VectorXd &q) const
  {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n_modes()), scratch(n_modes());
    add_nonlinear_force(q, 1., f, scratch);
    return f;
  }

  void ReducedOrderModel::add_nonlinear_force(const Eigen::VectorXd &q, const double scale, Eigen::VectorXd &f,
                                              Eigen::VectorXd &scratch) const
  {
    if (!nonlinear_)
      return;
    if (terms_)
      {
        for (const auto &t : *terms_)
          f[t.n] += scale * t.value * q[t.j] * q[t.k] * q[t.l];
        return;
      }
    // Uniform membrane force: f = N K'q.
    const double N = membrane_axial_force(q, scratch);
    f += (scale * N) * scratch;
  }

  double ReducedOrderModel::membrane_axial_force(const Eigen::VectorXd &q, Eigen::VectorXd &stretch_q) const
  {
    stretch_q.noalias() = basis_.stretch * q;
    return 0.5 * basis_.membrane_stiffness * q.dot(stretch_q);
  }

  Eigen::MatrixXd ReducedOrderModel::nonlinear_tangent(const Eigen::VectorXd &q) const
  {
    const unsigned int N = n_modes();
    Eigen::MatrixXd T    = Eigen::MatrixXd::Zero(N, N);
    if (!nonlinear_)
      return T;
    if (terms_)
      {
        for (const auto &t : *terms_)
          {
            T(t.n, t.j) += t.value * q[t.k] * q[t.l];
            T(t.n, t.k) += t.value * q[t.j] * q[t.l];
            T(t.n, t.l) += t.value * q[t.j] * q[t.k];
          }
        return T;
      }
    // d/dq [ (k/2)(qᵀKq) K q ] = (k/2)(qᵀKq) K + k (Kq)(Kq)ᵀ
    const Eigen::VectorXd Kq = basis_.stretch * q;
    const double k           = basis_.membrane_stiffness;
    return 0.5 * k * q.dot(Kq) * basis_.stretch + k * Kq * Kq.transpose();
  }

  Eigen::VectorXd ReducedOrderModel::linear_force(const Eigen::VectorXd &q, const Eigen::VectorXd &v) const
  {
    const Eigen::ArrayXd w = basis_.omega.array();
    return (w * w * q.array() + damping_.array() * v.array()).matrix();
  }

  std::vector<CubicTerm> ReducedOrderModel::analytic_cubic_terms() const
  {
    // b^(n)_jkl = (k/2) K'_jk K'_ln summed over the distinct permutations of
    // (j,k,l) gives the coefficient of q_j q_k q_l for sorted j ≤ k ≤ l.
    const unsigned int N = n_modes();
    const double half_k  = 0.5 * basis_.membrane_stiffness;
    const auto &K        = basis_.stretch;
    std::vector<CubicTerm> terms;
    for (unsigned int n = 0; n < N; ++n)
      for (unsigned int j = 0; j < N; ++j)
        for (unsigned int k = j; k < N; ++k)
          for (unsigned int l = k; l < N; ++l)
            {
              std::array<unsigned int, 3> idx{{j, k, l}};
              double value = 0;
              do
                {
                  value += half_k * K(idx[0], idx[1]) * K(idx[2], n);
                }
              while (std::next_permutation(idx.begin(), idx.end()));
              terms.push_back({n, j, k, l, value});
            }
    return terms;
  }
} // namespace beamslider
