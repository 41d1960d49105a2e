// The FE beam's redistributed mass: no inertia at the slider's contact
// points (FETransientSettings::redistributed_mass, doc/physics.md §7).
#include "fem/fe_transient.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace beamslider
{
  void FETransientBeam::set_up_redistribution()
  {
    // ι, the rigid translation w = 1 on the free DoFs: the Hermite value
    // DoFs (local 0 and 2 of each cell) are 1, the slopes 0.
    const unsigned int n = n_dofs();
    iota_.setZero(n);
    for (const CellData &cell : cells_)
      for (const unsigned int a : {0u, 2u})
        if (!constrained_[cell.w_dofs[a]])
          iota_[cell.w_dofs[a]] = 1.;
    mrm_W_.setZero(n, 2);
    mrm_Y_.setZero(n, 2);
    r_tilde_ = r_eigen_;
  }

  void FETransientBeam::set_contact_abscissae(const double x_left, const double x_right)
  {
    if (!settings_.redistributed_mass || (x_left == mrm_x_[0] && x_right == mrm_x_[1]))
      return;
    // W's columns: the Hermite values at the two points (their few entries).
    LocalPointKinematics point;
    std::array<std::array<unsigned int, LocalPointKinematics::capacity>, 2> index{};
    std::array<unsigned int, 2> n_index{};
    const std::array<double, 2> x{{x_left, x_right}};
    for (unsigned int j = 0; j < 2; ++j)
      {
        mrm_W_.col(j).setZero();
        evaluate_local(x[j], iota_, point);
        for (unsigned int a = 0; a < point.n; ++a)
          {
            mrm_W_(point.index[a], j) = point.grad_w[a];
            index[j][a]               = point.index[a];
          }
        n_index[j] = point.n;
      }
    // Wᵀ M⁻¹ W from the few entries of each column.
    Eigen::Matrix2d WMW = Eigen::Matrix2d::Zero();
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        for (unsigned int a = 0; a < n_index[i]; ++a)
          for (unsigned int b = 0; b < n_index[j]; ++b)
            WMW(i, j) += mrm_W_(index[i][a], i) * inverse_mass_(index[i][a], index[j][b]) * mrm_W_(index[j][b], j);
    const Eigen::LLT<Eigen::Matrix2d> llt(WMW);
    if (llt.info() != Eigen::Success)
      throw std::runtime_error("FE transient: the contact points x = " + std::to_string(x_left) + ", " +
                               std::to_string(x_right) +
                               " m carry no mass of their own (W^T M^-1 W is singular): no mass can be taken away there");
    mrm_A_ = llt.solve(Eigen::Matrix2d::Identity());
    // r̃ = −M̃ ι = r + W A Wᵀ ι.
    r_tilde_ = r_eigen_;
    r_tilde_.noalias() += mrm_W_ * (mrm_A_ * (mrm_W_.transpose() * iota_));
    mrm_x_       = x;
    mrm_current_ = false;
  }

  void FETransientBeam::update_redistribution() const
  {
    if (mrm_current_)
      return;
    if (!factorised_)
      throw std::logic_error("FE transient: redistributed mass used before the first factorisation");
    // Y = S⁻¹ W from the kept columns of S⁻¹ (a column of W touches four DoFs).
    const unsigned int n = n_dofs();
    for (unsigned int j = 0; j < 2; ++j)
      {
        mrm_Y_.col(j).setZero();
        for (unsigned int i = 0; i < n; ++i)
          if (mrm_W_(i, j) != 0.)
            mrm_Y_.col(j) += mrm_W_(i, j) * Eigen::Map<const Eigen::VectorXd>(inverse_column(i), n);
      }
    // C = A⁻¹ − Wᵀ S⁻¹ W = Wᵀ (M⁻¹ − S⁻¹) W: positive definite, S exceeds M
    // by θΔt C + θ²Δt² K.
    const Eigen::Matrix2d A_inverse = mrm_A_.inverse();
    const Eigen::Matrix2d C         = A_inverse - mrm_W_.transpose() * mrm_Y_;
    mrm_C_.compute(C);
    if (mrm_C_.info() != Eigen::Success)
      throw std::runtime_error("FE transient: the redistributed mass's Woodbury matrix W^T (M^-1 - S^-1) W is not "
                               "positive definite at x = " +
                               std::to_string(mrm_x_[0]) + ", " + std::to_string(mrm_x_[1]) + " m");
    mrm_current_ = true;
  }

  void FETransientBeam::add_redistribution_term(Eigen::VectorXd &x) const
  {
    update_redistribution();
    mrm_scratch_.noalias() = mrm_W_.transpose() * x;
    mrm_scratch_           = mrm_C_.solve(mrm_scratch_);
    x.noalias() += mrm_Y_ * mrm_scratch_;
  }

  Eigen::MatrixXd FETransientBeam::removed_mass() const
  {
    if (!settings_.redistributed_mass)
      return Eigen::MatrixXd::Zero(n_dofs(), n_dofs());
    return mrm_W_ * mrm_A_ * mrm_W_.transpose();
  }
} // namespace beamslider
