// A banded sparse matrix once more, as fixed-size 8 × 8 blocks, for its
// products with vectors: the FE mass matrix M of every Newton residual
// (fem/fe_transient.h).
//
// Cut into blocks of 8 rows and columns, a matrix whose entries lie at most
// 8 places from the diagonal is block-tridiagonal, so
//   (A v)_I = A_I,I−1 v_I−1 + A_II v_I + A_I,I+1 v_I+1,
// three 8 × 8 products of compile-time size per block row, which Eigen
// unrolls and vectorises (at -O3, fem/CMakeLists.txt). A sparse product does
// the same arithmetic through an index per entry and a loop of unknown
// length per row: on a 131 × 131 band of half-width 7 (the default mesh's
// size) 0.86 against 0.44 µs per product (one core, 2026-11-29). The last
// block is padded with zeros.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <vector>

namespace beamslider
{
  class BlockTridiagonalMatrix
  {
  public:
    static constexpr int block_size = 8;

    // Copies A (square). Returns false, and keeps nothing, if an entry lies
    // more than block_size places from the diagonal.
    bool assign(const Eigen::SparseMatrix<double, Eigen::RowMajor> &A);

    bool empty() const { return n_ == 0; }

    // y = A v (y may not alias v). y is resized only if its size differs.
    void multiply(const Eigen::VectorXd &v, Eigen::VectorXd &y) const;

  private:
    using Block = Eigen::Matrix<double, block_size, block_size>;
    Eigen::Index n_ = 0, n_blocks_ = 0;
    // A_I,I−1, A_II and A_I,I+1 of block row I (left_[0] and the last right_ are zero).
    std::vector<Block, Eigen::aligned_allocator<Block>> left_, diagonal_, right_;
    mutable Eigen::VectorXd v_, y_; // padded copies of the operands
  };
} // namespace beamslider
