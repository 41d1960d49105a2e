// The FE beam as the conservative system M q̈ + K q + f(q) = 0 that the
// harmonic-balance backbone solver (reduced/harmonic_balance.h) takes: dense
// matrices on the unconstrained DoFs (u, w, θ), K the linear stiffness and
// f(q) = f_int(q) − K q the geometric nonlinearity, with its tangent. The
// axial DoFs keep their inertia: this is the full model the ROM condenses.
//
// Cost of a mode-1 backbone to ŵ/h = 4 with H = 10 (compute_fe_backbone,
// measured 2026-11 on the mueller2023 beam, one core): 16 elements (65 DoFs) 1.5 s,
// 32 elements (129 DoFs) 5–7 s with the half-period symmetry; the full
// harmonic set on 16 elements 5.4 s. Tested in tests/test_fem_backbone.cc
// (linear limit, Eq. 4, against the ROM, symmetry, axial inertia).
#pragma once

#include "fem/fe_beam.h"
#include "reduced/beam_backbone.h"

#include <Eigen/Dense>

#include <vector>

namespace beamslider
{
  struct FEConservativeSystem
  {
    ConservativeSystem system;
    std::vector<unsigned int> free_dofs; // global DoF of each row of the dense system
    Eigen::VectorXd deflection_at(double x) const; // c with w(x) = cᵀ q_free
    // The half-period symmetry of the bending backbones (HarmonicBalance-
    // Settings::even_harmonic_dofs): true for the axial DoFs u, which carry
    // the even harmonics (the stretching ½w'² of an odd-harmonic w), false
    // for w and θ.
    std::vector<bool> even_harmonic_dofs() const;
    const FEBeam *beam = nullptr;
  };

  FEConservativeSystem make_fe_conservative_system(const FEBeam &beam);

  // The FE model's mode-1 backbone with output w(L/2), harmonics 0…H under
  // the half-period symmetry (w, θ odd harmonics up to H, u even ones).
  Backbone compute_fe_backbone(const FEConservativeSystem &fe, const BeamBackboneSettings &settings);
} // namespace beamslider
