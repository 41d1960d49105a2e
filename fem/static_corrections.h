// A modal basis enriched with static corrections (doc/physics.md §5b): the
// slider loads the beam with point impulses at its corners, and N modes
// carry such a load's quasi-static deflection only as far as their own
// participation reaches (modal truncation misses the rest: the residual
// flexibility). The classic fix is to add, for unit transverse loads f_k at
// positions x_k, the part of the static response K⁻¹ f_k the kept modes
// do not carry:
//
//   ψ_k = K⁻¹ f_k − Σ_{n ≤ N} φ_n φ_nᵀ f_k / ω_n² .
//
// Every ψ_k is K- and M-orthogonal to the kept modes, so the Rayleigh–Ritz
// problem on span{φ_1 … φ_N, ψ_1 … ψ_m} splits: the modes stay as they are
// and the ψ block gives m Ritz vectors, mass-normalised, K-orthogonal, each
// with its Ritz frequency (above ω_N). The result is again a diagonal
// "modal" basis, so the reduced model, its cubic force (built from K' and
// k_ax of the basis) and its explicit step take it unchanged; the explicit
// step's limit becomes 2/ω of the highest Ritz vector.
//
// Load-dependent Ritz vectors (Wilson, Yuan & Dickens 1982) go one step
// further: after the static block Ψ₁ = [ψ_k], block j + 1 is K⁻¹ M Ψ_j, the
// static response to the inertia forces of block j, again without its part
// along the kept modes. Where the static corrections carry an impact's
// quasi-static deflection, the next blocks carry the first dynamic
// corrections to it: the response of the modes above N, ordered by what the
// corner loads excite rather than by frequency. Each block stays
// M-orthogonal to the kept modes (K⁻¹ M φ_n = φ_n / ω_n²), so the Ritz
// step above applies to all blocks together.
#pragma once

#include "fem/fe_beam.h"
#include "fem/fe_modes.h"

#include <vector>

namespace beamslider
{
  // The first n_modes of `modes` followed by the Ritz vectors of the static
  // corrections for unit transverse loads at `load_positions` [m] and, for
  // ritz_blocks > 1, of ritz_blocks − 1 further blocks of load-dependent
  // Ritz vectors, in ascending ω, sign as compute_bending_modes fixes it.
  // Vectors that the others (nearly) span are dropped, so the basis may hold
  // fewer than n_modes + ritz_blocks · load_positions.size() vectors.
  FEModes add_static_corrections(const FEBeam &beam, const FEModes &modes, unsigned int n_modes,
                                 const std::vector<double> &load_positions, unsigned int ritz_blocks = 1);

  // m load positions evenly over the beam: x_k = (k − ½) L / m.
  std::vector<double> static_correction_positions(double length, unsigned int m);

  // The vectors a beam's reduced model is built on: the n_modes lowest
  // bending modes, and for n_static_corrections = m > 0 the corrections at
  // static_correction_positions(L, m) grown to ritz_blocks blocks. The ROM
  // and the coefficients command share it, so the two mean the same basis.
  FEModes reduced_basis_vectors(const FEBeam &beam, unsigned int n_modes, unsigned int n_static_corrections,
                                unsigned int ritz_blocks);
} // namespace beamslider
