// The mode-1 backbone of a beam as the reports and the `backbone` command use
// it, on top of the generic solver of harmonic_balance.h: output y = w(x_out)
// [m], amplitudes given in thicknesses h, pseudo-arclength with restarts past
// internal-resonance tongues. Also the single-mode, single-harmonic backbone
// of the seed (Eq. 4) and its version with the slider's inertia (Eq. 5).
#pragma once

#include "reduced/harmonic_balance.h"
#include "reduced/rom_operator.h"

#include <Eigen/Dense>

#include <vector>

namespace beamslider
{
  // The ROM as a ConservativeSystem: M = I, K = diag ω_n², f = nonlinear_force
  // (damping is dropped: the backbone is the undamped one). The ROM must
  // outlive the returned object.
  ConservativeSystem make_conservative_system(const ReducedOrderModel &rom);

  struct BeamBackboneSettings
  {
    unsigned int n_harmonics = 10; // H
    double thickness = 0;          // h [m]
    double start_over_h = 0.01, end_over_h = 4; // first and last ŵ/h
    bool restart_past_tongues = true;
    double max_step = 0.05;        // largest arclength step (fraction of the end amplitude)
    std::vector<double> landing_over_h; // ŵ/h at which points are solved for exactly
    bool keep_points_when_interrupted = false; // BackboneSettings' (the `backbone` command)
  };

  // The generic settings for a beam's mode-1 backbone with output functional
  // c = `output` (any model: the ROM's φ(x_out), the FE model's w(x_out) row).
  BackboneSettings make_beam_backbone_settings(const Eigen::VectorXd &output, const BeamBackboneSettings &beam);

  // The ROM's mode-1 backbone with output c = φ(x_out) (odd harmonics only:
  // the cubic ROM is odd, so this equals the full set 0…H exactly).
  Backbone compute_rom_backbone(const ReducedOrderModel &rom, double x_out, const BeamBackboneSettings &beam);

  // Seed Eq. 4: ω = sqrt(ω₁² + ¾ b₁₁₁ q̂²) [rad/s]; b₁₁₁ [1/(s² m² kg)], q̂ [m kg^1/2].
  double single_mode_backbone_frequency(double omega_1, double b_111, double q_hat);
  // Seed Eq. 5: the same divided by 1 + m φ₁(x_C)² + J φ₁'(x_C)² under the
  // root (slider mass m [kg], inertia J [kg m²], φ₁ [kg^-1/2], φ₁' [kg^-1/2/m]).
  double single_mode_backbone_frequency_with_slider(double omega_1, double b_111, double q_hat, double slider_mass,
                                                    double slider_inertia, double phi_1_at_slider,
                                                    double dphi_1_at_slider);
  // The coefficient c of (ω/ω₁)² = 1 + c (ŵ/h)² with ŵ = φ₁(x_out) q̂ (Eq. 4
  // rewritten): c = ¾ b₁₁₁ h² / (φ₁(x_out)² ω₁²) [-].
  double single_mode_backbone_coefficient(double omega_1, double b_111, double phi_1_at_output, double thickness);
  // Eq. 4 in that form: ω/ω₁ = sqrt(1 + c (ŵ/h)²) [-].
  double single_mode_backbone_ratio(double c, double w_over_h);
} // namespace beamslider
