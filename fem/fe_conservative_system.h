// The FE beam as the conservative system M q̈ + K q + f(q) = 0 that the
// harmonic-balance backbone solver (reduced/harmonic_balance.h) takes: dense
// matrices on the unconstrained DoFs (u, w, θ), K the linear stiffness and
// f(q) = f_int(q) − K q the geometric nonlinearity, with its tangent. The
// axial DoFs keep their inertia: this is the full model the ROM condenses.
#pragma once

#include "fem/fe_beam.h"
#include "reduced/harmonic_balance.h"

#include <Eigen/Dense>

#include <vector>

namespace beamslider
{
  struct FEConservativeSystem
  {
    ConservativeSystem system;
    std::vector<unsigned int> free_dofs; // global DoF of each row of the dense system
    Eigen::VectorXd deflection_at(double x) const; // c with w(x) = cᵀ q_free
    const FEBeam *beam = nullptr;
  };

  FEConservativeSystem make_fe_conservative_system(const FEBeam &beam);
} // namespace beamslider
