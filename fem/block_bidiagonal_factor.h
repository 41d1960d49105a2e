// The factors of S₀ = L D Lᵀ (fem/fe_transient.h) once more, as fixed-size
// 8 × 8 blocks, for the solves of every Newton iteration.
//
// S₀ is banded: in the DoFs' own order (fem/fe_transient.h) no entry of the
// default mesh lies more than 7 places below the diagonal, and an LDLᵀ
// without pivoting keeps that band. Cut into blocks of
// 8 rows, a band of half-width ≤ 8 makes L block-bidiagonal:
//   L = | L₀₀              |
//       | L₁₀  L₁₁         |
//       |      L₂₁  L₂₂    |  …
// so L y = b is, block row by block row,
//   y_I = L_II⁻¹ b_I − (L_II⁻¹ L_I,I−1) y_I−1 = A_I b_I − C_I y_I−1,
// and Lᵀ x = z, from the last block row up,
//   x_I = A_Iᵀ z_I − (A_Iᵀ L_I+1,Iᵀ) x_I+1 = A_Iᵀ z_I − E_I x_I+1.
// A_I, C_I and E_I are formed once per factorisation; a solve is then two
// 8 × 8 products of compile-time size per block and direction, which Eigen
// unrolls and vectorises (at -O3, fem/CMakeLists.txt), and the only chain
// from block to block is one of them (A_I b_I does not wait for anything).
// A sparse triangular solve does the same arithmetic through an index per
// entry, a loop of unknown length per row and a chain through every
// unknown; that, not the arithmetic, is what it spends its time on: on a
// 131 × 131 band of half-width 7 (the default mesh's size) 1.7 µs per solve
// against 0.6 µs here (one core, 2026-11-29).
//
// The diagonal blocks' inverses are those of unit lower triangles of an
// LDLᵀ of the SPD iteration matrix. Over the FeContact benchmark's windows
// the solves agreed with the sparse ones to 8e-15 relative (measured once,
// 2026-11-29); tests/test_fem_band_blocks.cc checks them against Eigen's
// dense solve.
//
// The last block is padded with rows of the identity (zero right-hand side,
// D⁻¹ = 1), which leave the other unknowns alone.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include <vector>

namespace beamslider
{
  class BlockBidiagonalFactor
  {
  public:
    static constexpr int block_size = 8;

    // Copies the unit lower factor L (its strictly lower entries; the
    // diagonal is ignored) and D⁻¹. Returns false, and keeps nothing, if an
    // entry of L lies more than block_size places below the diagonal: then
    // L is not block-bidiagonal and the caller solves otherwise. Storage is
    // sized on the first call (and when n changes); later calls move values
    // only and allocate nothing.
    bool assign(const Eigen::SparseMatrix<double> &L, const Eigen::VectorXd &inverse_D);

    bool empty() const { return n_ == 0; }

    // x = (L D Lᵀ)⁻¹ b. x is resized only if its size differs from b's.
    void solve(const Eigen::VectorXd &b, Eigen::VectorXd &x) const;

  private:
    using Block = Eigen::Matrix<double, block_size, block_size>;
    Eigen::Index n_ = 0, n_blocks_ = 0;
    // A_I = L_II⁻¹, C_I = A_I L_I,I−1 (C_0 unused), E_I = A_Iᵀ L_I+1,Iᵀ (the
    // last unused).
    std::vector<Block, Eigen::aligned_allocator<Block>> A_, C_, E_;
    Block diagonal_, below_; // L_II and L_I,I−1 while they are formed
    Eigen::VectorXd inverse_D_; // padded with ones
    mutable Eigen::VectorXd y_; // padded scratch of the solves
  };
} // namespace beamslider
