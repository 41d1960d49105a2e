// The beam parts of a Moreau step's contact directions for a model with
// local kinematics (BeamSystem::has_local_kinematics: the FE beam), kept on
// the few coordinates they touch instead of as dense columns of length n.
//
// A corner's W_N and W_T depend on w and w' at one point: on the FE beam the
// four Hermite DoFs of the cell under it. With K the union of the active
// corners' coordinates (K ≤ 16, usually 4 or 8) and E = [e_i, i ∈ K],
//   W_b = E W,                      W: K × 2m
//   W_bᵀ u = Wᵀ (Eᵀ u)              (u gathered at K)
//   W_bᵀ S⁻¹ W_b = Wᵀ (Eᵀ S⁻¹ E) W  (the K × K block of S⁻¹)
//   S⁻¹ W_b P = S⁻¹ E (W P)         (K columns of S⁻¹)
// so a step's contact work no longer grows with the mesh: on the default
// 131-DoF beam the dense forms were a fifth of the FE step.
#pragma once

#include "contact/beam_system.h"
#include "contact/slider_contact.h"

#include <Eigen/Dense>

#include <array>

namespace beamslider
{
  class LocalDirections
  {
  public:
    static constexpr int max_coordinates = n_slider_corners * LocalPointKinematics::capacity;
    static constexpr int max_directions  = 2 * n_slider_corners;

    void clear() { n_coordinates_ = 0; }

    // Columns `column` (normal) and `column + 1` (tangent) from a closed
    // corner's local beam parts (CornerKinematics::local_*).
    void set_corner(const unsigned int column, const CornerKinematics &corner)
    {
      W_.block(0, column, n_coordinates_, 2).setZero();
      for (unsigned int a = 0; a < corner.n_local; ++a)
        {
          const unsigned int r = row_of(corner.local_index[a]);
          W_(r, column) += corner.local_normal[a];
          W_(r, column + 1) += corner.local_tangent[a];
        }
    }

    unsigned int n_coordinates() const { return n_coordinates_; }
    const unsigned int *index() const { return index_.data(); }
    // W's first `directions` columns on the K coordinates.
    auto directions(const Eigen::Index directions) const { return W_.topLeftCorner(n_coordinates_, directions); }

    // out = Wᵀ (Eᵀ u) + W_sᵀ v + imposed: the directions' relative velocities.
    template <typename SliderBlock, typename Imposed, typename Out>
    void relative_velocities(const Eigen::Index directions, const SliderBlock &W_s, const Imposed &imposed,
                             const Eigen::VectorXd &u, const Eigen::Vector3d &v, Out &&out) const
    {
      for (Eigen::Index j = 0; j < directions; ++j)
        {
          double sum = 0.;
          for (unsigned int a = 0; a < n_coordinates_; ++a)
            sum += W_(a, j) * u[index_[a]];
          out[j] = sum + (W_s(0, j) * v[0] + W_s(1, j) * v[1] + W_s(2, j) * v[2]) + imposed[j];
        }
    }

  private:
    // The row of coordinate i, appended (zero in every column) if new.
    unsigned int row_of(const unsigned int i)
    {
      for (unsigned int r = 0; r < n_coordinates_; ++r)
        if (index_[r] == i)
          return r;
      index_[n_coordinates_] = i;
      W_.row(n_coordinates_).setZero();
      return n_coordinates_++;
    }

    unsigned int n_coordinates_ = 0;
    std::array<unsigned int, max_coordinates> index_{};
    Eigen::Matrix<double, max_coordinates, max_directions> W_;
  };
} // namespace beamslider
