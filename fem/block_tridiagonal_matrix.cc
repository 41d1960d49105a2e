// The block-tridiagonal copy of a banded matrix, see block_tridiagonal_matrix.h.
#include "fem/block_tridiagonal_matrix.h"

#include <cstdlib>

namespace beamslider
{
  bool BlockTridiagonalMatrix::assign(const Eigen::SparseMatrix<double, Eigen::RowMajor> &A)
  {
    constexpr int B      = block_size;
    const Eigen::Index n = A.rows();
    for (Eigen::Index i = 0; i < A.outerSize(); ++i)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, i); it; ++it)
        if (std::abs(it.col() - i) > B)
          {
            n_ = 0;
            return false;
          }
    n_        = n;
    n_blocks_ = (n + B - 1) / B;
    left_.assign(n_blocks_, Block::Zero());
    diagonal_.assign(n_blocks_, Block::Zero());
    right_.assign(n_blocks_, Block::Zero());
    for (Eigen::Index i = 0; i < A.outerSize(); ++i)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, i); it; ++it)
        {
          const Eigen::Index I = i / B, J = it.col() / B;
          Block &block = J < I ? left_[I] : J == I ? diagonal_[I] : right_[I];
          block(i % B, it.col() % B) = it.value();
        }
    v_.setZero(n_blocks_ * B);
    y_.setZero(n_blocks_ * B);
    return true;
  }

  void BlockTridiagonalMatrix::multiply(const Eigen::VectorXd &v, Eigen::VectorXd &y) const
  {
    constexpr int B = block_size;
    v_.head(n_)     = v; // the padding stays zero
    for (Eigen::Index I = 0; I < n_blocks_; ++I)
      {
        Eigen::Matrix<double, B, 1> y_I = diagonal_[I].lazyProduct(v_.segment<B>(B * I));
        if (I > 0)
          y_I += left_[I].lazyProduct(v_.segment<B>(B * (I - 1)));
        if (I + 1 < n_blocks_)
          y_I += right_[I].lazyProduct(v_.segment<B>(B * (I + 1)));
        y_.segment<B>(B * I) = y_I;
      }
    y = y_.head(n_);
  }
} // namespace beamslider
