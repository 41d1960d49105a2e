// The 8 × 8 block views of banded matrices that every FE Newton iteration
// uses (fem/block_bidiagonal_factor.h, fem/block_tridiagonal_matrix.h),
// against Eigen's dense solve and product of the same matrices: random band
// matrices of the half-widths the FE meshes have (≤ 8), of sizes that do and
// do not fill the last block, and the refusal of a wider band.
#include "fem/block_bidiagonal_factor.h"
#include "fem/block_tridiagonal_matrix.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <gtest/gtest.h>

#include <random>

using namespace beamslider;

namespace
{
  // A random matrix with entries in [−1, 1] up to `half_width` places from
  // the diagonal; symmetric and diagonally dominant (SPD) if asked.
  Eigen::MatrixXd band_matrix(const int n, const int half_width, const bool spd, const unsigned int seed)
  {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> entry(-1., 1.);
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = std::max(0, i - half_width); j <= std::min(n - 1, i + half_width); ++j)
        if (!spd)
          A(i, j) = entry(random);
        else if (j <= i)
          A(i, j) = A(j, i) = entry(random);
    if (spd)
      A.diagonal().array() += 2. * half_width + 1.;
    return A;
  }

  // The LDLᵀ factor the FE model uses: natural (band) ordering.
  class NaturalLDLT
    : public Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>
  {
  public:
    const Eigen::VectorXd &diagonal() const { return this->m_diag; }
  };
} // namespace

TEST(BlockBidiagonalFactor, SolvesLikeADenseFactorisation)
{
  for (const int n : {131, 37, 8, 5})
    for (const int half_width : {1, 7, 8})
      {
        const Eigen::MatrixXd A = band_matrix(n, half_width, true, 7 * n + half_width);
        const Eigen::SparseMatrix<double> S = A.sparseView();
        NaturalLDLT ldlt;
        ldlt.compute(S);
        ASSERT_EQ(ldlt.info(), Eigen::Success);

        BlockBidiagonalFactor factor;
        ASSERT_TRUE(factor.assign(ldlt.matrixL().nestedExpression(), ldlt.diagonal().cwiseInverse()));
        ASSERT_FALSE(factor.empty());

        const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1., 2.).array().sin();
        Eigen::VectorXd x;
        factor.solve(b, x);
        const Eigen::VectorXd reference = A.llt().solve(b);
        ASSERT_EQ(x.size(), n);
        // The matrices are well conditioned (diagonally dominant): both
        // solves agree to round-off.
        EXPECT_LT((x - reference).norm(), 1e-13 * reference.norm()) << "n = " << n << ", half-width " << half_width;
      }
}

TEST(BlockBidiagonalFactor, NewValuesOnTheSamePatternReplaceTheOld)
{
  const int n = 50;
  BlockBidiagonalFactor factor;
  for (const unsigned int seed : {1u, 2u})
    {
      const Eigen::MatrixXd A = band_matrix(n, 7, true, seed);
      NaturalLDLT ldlt;
      ldlt.compute(Eigen::SparseMatrix<double>(A.sparseView()));
      ASSERT_TRUE(factor.assign(ldlt.matrixL().nestedExpression(), ldlt.diagonal().cwiseInverse()));
      const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
      Eigen::VectorXd x;
      factor.solve(b, x);
      EXPECT_LT((A * x - b).norm(), 1e-13 * b.norm()) << "seed " << seed;
    }
}

TEST(BlockBidiagonalFactor, RefusesABandWiderThanABlock)
{
  const Eigen::MatrixXd A = band_matrix(40, 9, true, 3);
  NaturalLDLT ldlt;
  ldlt.compute(Eigen::SparseMatrix<double>(A.sparseView()));
  BlockBidiagonalFactor factor;
  EXPECT_FALSE(factor.assign(ldlt.matrixL().nestedExpression(), ldlt.diagonal().cwiseInverse()));
  EXPECT_TRUE(factor.empty());
}

TEST(BlockTridiagonalMatrix, MultipliesLikeTheDenseMatrix)
{
  for (const int n : {131, 37, 8, 5})
    for (const int half_width : {0, 7, 8})
      {
        const Eigen::MatrixXd A = band_matrix(n, half_width, false, 11 * n + half_width);
        BlockTridiagonalMatrix blocks;
        ASSERT_TRUE(blocks.assign(Eigen::SparseMatrix<double, Eigen::RowMajor>(A.sparseView())));
        const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, 0., 3.).array().cos();
        Eigen::VectorXd y;
        blocks.multiply(v, y);
        const Eigen::VectorXd reference = A * v;
        ASSERT_EQ(y.size(), n);
        EXPECT_LT((y - reference).norm(), 1e-14 * (A.cwiseAbs() * v.cwiseAbs()).norm())
          << "n = " << n << ", half-width " << half_width;
      }
}

TEST(BlockTridiagonalMatrix, RefusesABandWiderThanABlock)
{
  BlockTridiagonalMatrix blocks;
  EXPECT_FALSE(blocks.assign(Eigen::SparseMatrix<double, Eigen::RowMajor>(band_matrix(30, 9, false, 5).sparseView())));
  EXPECT_TRUE(blocks.empty());
}
