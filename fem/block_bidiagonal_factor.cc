// The block-bidiagonal copy of an LDLᵀ factor, see block_bidiagonal_factor.h.
#include "fem/block_bidiagonal_factor.h"

#include <algorithm>

namespace beamslider
{
  bool BlockBidiagonalFactor::assign(const Eigen::SparseMatrix<double> &L, const Eigen::VectorXd &inverse_D)
  {
    constexpr int B    = block_size;
    const Eigen::Index n = L.rows();
    for (Eigen::Index j = 0; j < L.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
        if (it.row() - j > B)
          {
            n_ = 0;
            return false;
          }

    const Eigen::Index n_blocks = (n + B - 1) / B;
    if (n != n_)
      {
        n_        = n;
        n_blocks_ = n_blocks;
        A_.resize(n_blocks);
        C_.resize(n_blocks);
        E_.resize(n_blocks);
        inverse_D_.resize(n_blocks * B);
        y_.resize(n_blocks * B);
      }
    // Block row I of L: its entries lie in the columns of blocks I − 1 and I
    // (a band of half-width ≤ B). L is stored by columns, so each block row
    // is gathered from the columns it spans.
    auto gather = [&](const Eigen::Index I, const Eigen::Index J, Block &out) {
      out.setZero();
      for (Eigen::Index j = J * B; j < std::min((J + 1) * B, n); ++j)
        for (Eigen::SparseMatrix<double>::InnerIterator it(L, j); it; ++it)
          if (it.row() > j && it.row() / B == I)
            out(it.row() % B, j % B) = it.value();
    };
    for (Eigen::Index I = 0; I < n_blocks; ++I)
      {
        gather(I, I, diagonal_);
        A_[I].setIdentity();
        diagonal_.triangularView<Eigen::UnitLower>().solveInPlace(A_[I]);
        if (I > 0)
          {
            gather(I, I - 1, below_);
            C_[I].noalias()     = A_[I] * below_;
            E_[I - 1].noalias() = (below_ * A_[I - 1]).transpose();
          }
      }
    inverse_D_.head(n) = inverse_D;
    inverse_D_.tail(n_blocks * B - n).setOnes();
    return true;
  }

  void BlockBidiagonalFactor::solve(const Eigen::VectorXd &b, Eigen::VectorXd &x) const
  {
    constexpr int B = block_size;
    using Segment   = Eigen::Matrix<double, B, 1>;
    y_.head(n_)     = b;
    y_.tail(n_blocks_ * B - n_).setZero();
    // L y = b: y_I = A_I b_I − C_I y_I−1.
    Segment previous = A_[0].lazyProduct(y_.segment<B>(0));
    y_.segment<B>(0) = previous;
    for (Eigen::Index I = 1; I < n_blocks_; ++I)
      {
        Segment y_I = A_[I].lazyProduct(y_.segment<B>(B * I));
        y_I -= C_[I].lazyProduct(previous);
        y_.segment<B>(B * I) = y_I;
        previous             = y_I;
      }
    y_.array() *= inverse_D_.array();
    // Lᵀ x = z: x_I = A_Iᵀ z_I − E_I x_I+1.
    const Eigen::Index last = n_blocks_ - 1;
    previous                = A_[last].transpose().lazyProduct(y_.segment<B>(B * last));
    y_.segment<B>(B * last) = previous;
    for (Eigen::Index I = last - 1; I >= 0; --I)
      {
        Segment x_I = A_[I].transpose().lazyProduct(y_.segment<B>(B * I));
        x_I -= E_[I].lazyProduct(previous);
        y_.segment<B>(B * I) = x_I;
        previous             = x_I;
      }
    x = y_.head(n_);
  }
} // namespace beamslider
