// The FE beam's solves with its iteration matrix (fe_transient.h): the
// factorisation of S₀ as blocks, the Woodbury terms of the damping, the kept
// columns of S⁻¹ that the contact directions use, and the blocks of S⁻¹ the
// contact step asks for.
#include "fem/fe_transient.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace beamslider
{
  void FETransientBeam::factorise(const Eigen::VectorXd &q_bar, const double dt)
  {
    assemble_iteration_matrix(q_bar, dt);
    ldlt_.factorize_upper(S0_);
    if (ldlt_.info() != Eigen::Success)
      throw std::runtime_error("FE transient: the LDL^T factorisation of S = M + dt^2/4 K_t failed (dt = " +
                               std::to_string(dt) + " s)");
    const auto &L = ldlt_.matrixL().nestedExpression();
    inverse_D_    = ldlt_.diagonal().cwiseInverse();
    // The factors as 8 × 8 blocks for the solves (a band of half-width ≤ 8,
    // the beam meshes here); L row by row (see L_rows_) only on a wider band:
    // set up on its first factorisation, then only the values move.
    if (!block_factor_.assign(L, inverse_D_))
      {
        const Eigen::Index nnz = L.nonZeros();
        if (static_cast<Eigen::Index>(L_pattern_.size()) != nnz ||
            !std::equal(L_pattern_.begin(), L_pattern_.end(), L.innerIndexPtr()))
          {
            L_rows_ = L;
            L_rows_.makeCompressed();
            L_pattern_.assign(L.innerIndexPtr(), L.innerIndexPtr() + nnz);
            L_rows_entry_.resize(nnz);
            for (Eigen::Index j = 0; j < L.outerSize(); ++j)
              for (Eigen::Index k = L.outerIndexPtr()[j]; k < L.outerIndexPtr()[j + 1]; ++k)
                {
                  const int i    = L.innerIndexPtr()[k];
                  const int *row = L_rows_.innerIndexPtr();
                  const auto at  = std::lower_bound(row + L_rows_.outerIndexPtr()[i], row + L_rows_.outerIndexPtr()[i + 1], j);
                  L_rows_entry_[k] = at - row;
                }
          }
        for (Eigen::Index k = 0; k < nnz; ++k)
          L_rows_.valuePtr()[L_rows_entry_[k]] = L.valuePtr()[k];
      }

    // Woodbury terms of the rank-N damping, S = S₀ + U Dg Uᵀ.
    const unsigned int rank = damping_->rank();
    if (rank > 0)
      {
        // Into storage sized once (a refactorisation allocates nothing).
        for (unsigned int k = 0; k < rank; ++k)
          {
            block_column_ = U_.col(k);
            solve_factored(block_column_, block_solution_);
            Z_.col(k)     = block_solution_;
          }
        Dg_ = (settings_.theta * dt) * modal_c_;
        capacitance_matrix_.noalias() = U_.transpose() * Z_;
        capacitance_matrix_           = Dg_.asDiagonal() * capacitance_matrix_;
        capacitance_matrix_.diagonal().array() += 1.;
        capacitance_.compute(capacitance_matrix_);
      }
    clear_inverse_columns();
    factorised_       = true;
    factorised_dt_    = dt;
    factorised_theta_ = settings_.theta;
    factorised_step_  = stats_.steps;
    factorised_q_bar_ = q_bar;
    ++stats_.factorisations;
  }

  void FETransientBeam::solve_factored(const Eigen::VectorXd &b, Eigen::VectorXd &x) const
  {
    if (!block_factor_.empty())
      {
        block_factor_.solve(b, x);
        return;
      }
    // S₀ = L D Lᵀ on a wider band: forward row by row, scale, backward with
    // Lᵀ (which Eigen already walks row by row).
    x = b;
    L_rows_.triangularView<Eigen::UnitLower>().solveInPlace(x);
    x.array() *= inverse_D_.array();
    ldlt_.matrixU().solveInPlace(x);
  }

  void FETransientBeam::solve(const Eigen::VectorXd &b, Eigen::VectorXd &x) const
  {
    solve_factored(b, x);
    const unsigned int rank = damping_->rank();
    if (rank == 0)
      return;
    // x −= Z (I + Dg UᵀZ)⁻¹ Dg Uᵀ x, through scratch of size rank: no heap.
    woodbury_rhs_.noalias() = U_.transpose() * x;
    woodbury_rhs_.array() *= Dg_.array();
    woodbury_v_ = capacitance_.solve(woodbury_rhs_);
    x.noalias() -= Z_ * woodbury_v_;
  }

  void FETransientBeam::clear_inverse_columns()
  {
    inverse_column_dof_.fill(-1);
    next_inverse_column_ = 0;
    mrm_current_         = false;
  }

  const double *FETransientBeam::inverse_column(const unsigned int dof) const
  {
    if (settings_.impulses_through_mass)
      return inverse_mass_.col(dof).data();
    for (unsigned int k = 0; k < n_inverse_columns; ++k)
      if (inverse_column_dof_[k] == static_cast<int>(dof))
        return inverse_columns_.col(k).data();
    const unsigned int k = next_inverse_column_;
    next_inverse_column_ = (k + 1) % n_inverse_columns;
    block_column_.setZero();
    block_column_[dof] = 1.;
    solve(block_column_, block_solution_);
    inverse_columns_.col(k) = block_solution_;
    inverse_column_dof_[k]  = static_cast<int>(dof);
    ++stats_.inverse_column_solves;
    return inverse_columns_.col(k).data();
  }

  void FETransientBeam::apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                               Eigen::Ref<Eigen::MatrixXd> X) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: iteration matrix used before its first factorisation");
    if (X.rows() != B.rows() || X.cols() != B.cols())
      throw std::logic_error("FE transient: apply_inverse_iteration_matrix needs X of B's size");
    // All right-hand sides at once (the contact directions, up to 8): one
    // pass of the sparse triangular solves over a block, then the Woodbury
    // correction as a block.
    // Scratch of the largest block (the contact directions: at most
    // max_block_columns), used by its leading columns: no allocation.
    const Eigen::Index m = B.cols();
    if (m > block_rhs_.cols())
      throw std::logic_error("FE transient: more right-hand sides than the scratch holds");
    // A block whose columns each touch a few DoFs (the contact directions:
    // four) is combined from the kept columns of S⁻¹.
    // One pass over each column finds its entries (free DoFs only).
    const unsigned int n = n_dofs();
    constexpr unsigned int max_sparse_entries = 8;
    std::array<std::array<unsigned int, max_sparse_entries>, max_block_columns> entries;
    std::array<unsigned int, max_block_columns> n_entries{};
    bool sparse = true;
    for (Eigen::Index j = 0; j < m && sparse; ++j)
      {
        const double *b = B.col(j).data();
        for (unsigned int i = 0; i < n; ++i)
          if (b[i] != 0. && !constrained_[i])
            {
              if (n_entries[j] == max_sparse_entries)
                {
                  sparse = false;
                  break;
                }
              entries[j][n_entries[j]++] = i;
            }
      }
    if (sparse)
      {
        for (Eigen::Index j = 0; j < m; ++j)
          {
            auto x = X.col(j);
            x.setZero();
            for (unsigned int k = 0; k < n_entries[j]; ++k)
              {
                const unsigned int i = entries[j][k];
                x += B(i, j) * Eigen::Map<const Eigen::VectorXd>(inverse_column(i), n);
              }
            if (settings_.redistributed_mass)
              {
                block_column_ = x;
                add_redistribution_term(block_column_);
                x = block_column_;
              }
          }
        stats_.iteration_matrix_solves += B.cols();
        return;
      }
    if (settings_.impulses_through_mass)
      {
        X.noalias() = inverse_mass_ * B; // zero rows and columns on the constrained and axial DoFs
        stats_.iteration_matrix_solves += B.cols();
        return;
      }
    auto rhs = block_rhs_.leftCols(m);
    rhs      = B;
    for (const unsigned int i : constrained_list_)
      rhs.row(i).setZero();
    for (Eigen::Index j = 0; j < m; ++j)
      {
        // Through plain vectors: Eigen's permuted solve into a column of a
        // Ref allocates a temporary.
        block_column_ = rhs.col(j);
        solve_factored(block_column_, block_solution_);
        X.col(j)      = block_solution_;
      }
    const unsigned int rank = damping_->rank();
    if (rank > 0)
      {
        auto v = block_v_.leftCols(m);
        auto w = block_w_.leftCols(m);
        v.noalias() = U_.transpose() * X;
        for (Eigen::Index j = 0; j < m; ++j)
          {
            woodbury_rhs_ = Dg_.cwiseProduct(v.col(j));
            woodbury_v_   = capacitance_.solve(woodbury_rhs_);
            w.col(j)      = woodbury_v_;
          }
        X.noalias() -= Z_ * w;
      }
    if (settings_.redistributed_mass)
      for (Eigen::Index j = 0; j < m; ++j)
        {
          block_column_ = X.col(j);
          add_redistribution_term(block_column_);
          X.col(j) = block_column_;
        }
    stats_.iteration_matrix_solves += B.cols();
  }

  void FETransientBeam::inverse_iteration_matrix_block(const unsigned int *index, const unsigned int k,
                                                     Eigen::Ref<Eigen::MatrixXd> out) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: iteration matrix used before its first factorisation");
    // Column b of the block is S⁻¹ e_{index[b]} read at the k coordinates;
    // each column is read before the next is asked for (a kept column may
    // be replaced by the next one solved).
    for (unsigned int b = 0; b < k; ++b)
      {
        const double *column = inverse_column(index[b]);
        for (unsigned int a = 0; a < k; ++a)
          out(a, b) = column[index[a]];
      }
    if (settings_.redistributed_mass)
      {
        // + Y C⁻¹ Yᵀ on the k coordinates.
        update_redistribution();
        for (unsigned int b = 0; b < k; ++b)
          {
            mrm_scratch_ = mrm_C_.solve(mrm_Y_.row(index[b]).transpose());
            for (unsigned int a = 0; a < k; ++a)
              out(a, b) += mrm_Y_.row(index[a]).dot(mrm_scratch_);
          }
      }
    ++stats_.contact_blocks;
  }

  void FETransientBeam::add_inverse_iteration_matrix_times(const unsigned int *index, const unsigned int k,
                                                         const double *y, Eigen::VectorXd &u) const
  {
    if (!factorised_)
      throw std::logic_error("FE transient: iteration matrix used before its first factorisation");
    const unsigned int n = n_dofs();
    for (unsigned int a = 0; a < k; ++a)
      if (y[a] != 0.)
        u += y[a] * Eigen::Map<const Eigen::VectorXd>(inverse_column(index[a]), n);
    if (settings_.redistributed_mass)
      {
        // + Y C⁻¹ Yᵀ (Σ y_a e_a).
        update_redistribution();
        Eigen::Vector2d v = Eigen::Vector2d::Zero();
        for (unsigned int a = 0; a < k; ++a)
          v += y[a] * mrm_Y_.row(index[a]).transpose();
        mrm_scratch_ = mrm_C_.solve(v);
        u.noalias() += mrm_Y_ * mrm_scratch_;
      }
  }
} // namespace beamslider
