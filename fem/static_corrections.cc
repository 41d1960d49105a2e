// Static corrections of a modal basis, see static_corrections.h.
#include "fem/static_corrections.h"

#include <deal.II/lac/sparse_matrix.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace beamslider
{
  std::vector<double> static_correction_positions(const double length, const unsigned int m)
  {
    std::vector<double> x(m);
    for (unsigned int k = 0; k < m; ++k)
      x[k] = (k + 0.5) * length / m;
    return x;
  }

  FEModes add_static_corrections(const FEBeam &beam, const FEModes &modes, const unsigned int n_modes,
                                 const std::vector<double> &load_positions, const unsigned int ritz_blocks)
  {
    if (n_modes > modes.shapes.size())
      throw std::invalid_argument("add_static_corrections: " + std::to_string(n_modes) + " modes requested, " +
                                  std::to_string(modes.shapes.size()) + " computed");
    if (ritz_blocks < 1)
      throw std::invalid_argument("add_static_corrections: ritz_blocks = 0; 1 is the static corrections alone");
    const auto &constraints = beam.bending_constraints();
    dealii::SparseMatrix<double> K_sparse, M_sparse;
    beam.assemble_mass_matrix(M_sparse, constraints);
    beam.assemble_internal_force(dealii::Vector<double>(beam.n_dofs()), nullptr, &K_sparse, constraints);
    const FreeDofProblem free = restrict_to_free_dofs(K_sparse, M_sparse, constraints);
    const Eigen::Index n      = free.dofs.size();
    const Eigen::Index m      = load_positions.size();

    // The kept modes and the unit loads on the free DoFs.
    Eigen::MatrixXd Phi(n, n_modes), F = Eigen::MatrixXd::Zero(n, m);
    for (unsigned int j = 0; j < n_modes; ++j)
      for (Eigen::Index a = 0; a < n; ++a)
        Phi(a, j) = modes.shapes[j][free.dofs[a]];
    for (Eigen::Index k = 0; k < m; ++k)
      {
        const FEPointShape s = beam.point_shape(load_positions[k]);
        for (unsigned int i = 0; i < 4; ++i)
          if (const int row = free.row_of_dof[s.w_dofs[i]]; row >= 0)
            F(row, k) += s.w_values[i];
      }

    // ψ_k = K⁻¹ f_k − Σ φ_n φ_nᵀ f_k / ω_n², then once more M-orthogonal to
    // the modes, which the subtraction gives only to round-off.
    Eigen::VectorXd inverse_omega_squared(n_modes);
    for (unsigned int j = 0; j < n_modes; ++j)
      inverse_omega_squared[j] = 1. / (modes.omega[j] * modes.omega[j]);
    const Eigen::LLT<Eigen::MatrixXd> K_factor(free.K);
    const auto without_modes = [&](Eigen::MatrixXd X) -> Eigen::MatrixXd {
      X -= Phi * (Phi.transpose() * free.M * X);
      // Unit M-norm per column: the blocks shrink by about 1/ω_{N+1}² each,
      // and the Gram threshold below is relative to the largest.
      for (Eigen::Index c = 0; c < X.cols(); ++c)
        if (const double norm = std::sqrt(X.col(c).dot(free.M * X.col(c))); norm > 0)
          X.col(c) /= norm;
      return X;
    };
    Eigen::MatrixXd block =
      without_modes(K_factor.solve(F) - Phi * inverse_omega_squared.asDiagonal() * (Phi.transpose() * F));
    Eigen::MatrixXd Psi(n, m * ritz_blocks);
    Psi.leftCols(m) = block;
    // Load-dependent Ritz blocks: K⁻¹ M times the block before.
    for (unsigned int j = 1; j < ritz_blocks; ++j)
      {
        block                    = without_modes(K_factor.solve(free.M * block));
        Psi.middleCols(j * m, m) = block;
      }

    // An M-orthonormal basis of span{ψ}: directions the others nearly span
    // (loads close together, or a load where the modes already carry it all)
    // are dropped below 1e-10 of the largest.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(Psi.transpose() * free.M * Psi);
    const double largest = gram.eigenvalues().size() ? gram.eigenvalues().maxCoeff() : 0.;
    std::vector<Eigen::Index> kept;
    for (Eigen::Index k = 0; k < Psi.cols(); ++k)
      if (gram.eigenvalues()[k] > 1e-10 * largest)
        kept.push_back(k);
    Eigen::MatrixXd Q(n, kept.size());
    for (std::size_t c = 0; c < kept.size(); ++c)
      Q.col(c) = Psi * gram.eigenvectors().col(kept[c]) / std::sqrt(gram.eigenvalues()[kept[c]]);

    // Rayleigh–Ritz on span{ψ}: QᵀKQ y = ω² y (QᵀMQ = I).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(Q.transpose() * free.K * Q);
    const Eigen::MatrixXd ritz_vectors = Q * ritz.eigenvectors();

    FEModes enriched;
    for (unsigned int j = 0; j < n_modes; ++j)
      {
        enriched.omega.push_back(modes.omega[j]);
        enriched.shapes.push_back(modes.shapes[j]);
      }
    for (Eigen::Index c = 0; c < ritz_vectors.cols(); ++c)
      {
        if (!(ritz.eigenvalues()[c] > 0))
          throw std::runtime_error("add_static_corrections: a Ritz value " + std::to_string(ritz.eigenvalues()[c]) +
                                   " is not positive: the beam is not supported against rigid motion");
        dealii::Vector<double> psi(beam.n_dofs());
        for (Eigen::Index a = 0; a < n; ++a)
          psi[free.dofs[a]] = ritz_vectors(a, c);
        fix_shape_sign(beam, psi);
        enriched.omega.push_back(std::sqrt(ritz.eigenvalues()[c]));
        enriched.shapes.push_back(std::move(psi));
      }
    // Ascending as a whole: the Ritz values come in ascending order and lie
    // above ω_N (Rayleigh quotients in the modes' M-orthogonal complement
    // are at least ω_{N+1}²).
    return enriched;
  }

  FEModes reduced_basis_vectors(const FEBeam &beam, const unsigned int n_modes,
                                const unsigned int n_static_corrections, const unsigned int ritz_blocks)
  {
    FEModes modes = compute_bending_modes(beam, n_modes);
    if (n_static_corrections == 0)
      return modes;
    return add_static_corrections(beam, modes, n_modes, static_correction_positions(beam.length(), n_static_corrections),
                                  ritz_blocks);
  }
} // namespace beamslider
