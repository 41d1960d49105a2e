// The beam's mode-1 backbone and the seed's single-mode formulas; see
// beam_backbone.h.
#include "reduced/beam_backbone.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace beamslider
{
  ConservativeSystem make_conservative_system(const ReducedOrderModel &rom)
  {
    const unsigned int N = rom.n_modes();
    ConservativeSystem s;
    s.mass      = Eigen::MatrixXd::Identity(N, N);
    s.stiffness = rom.basis().omega.array().square().matrix().asDiagonal();
    s.force     = [&rom](const Eigen::VectorXd &q) { return rom.nonlinear_force(q); };
    s.tangent   = [&rom](const Eigen::VectorXd &q) { return rom.nonlinear_tangent(q); };
    return s;
  }

  BackboneSettings make_beam_backbone_settings(const Eigen::VectorXd &output, const BeamBackboneSettings &beam)
  {
    if (!(beam.thickness > 0))
      throw std::invalid_argument("BeamBackboneSettings: thickness = " + std::to_string(beam.thickness) + " m; must be > 0");
    BackboneSettings s;
    s.hb.n_harmonics          = beam.n_harmonics;
    s.output                  = output;
    s.mode                    = 0;
    s.start_amplitude         = beam.start_over_h * beam.thickness;
    s.end_amplitude           = beam.end_over_h * beam.thickness;
    s.max_step                = beam.max_step;
    s.initial_step            = std::min(s.initial_step, s.max_step);
    s.restart_past_tongues    = beam.restart_past_tongues;
    s.keep_points_when_interrupted = beam.keep_points_when_interrupted;
    s.tongue_frequency_deviation = 0.03;
    s.normalise_by_mode          = true;
    for (const double r : beam.landing_over_h)
      s.landing_amplitudes.push_back(r * beam.thickness);
    return s;
  }

  Backbone compute_rom_backbone(const ReducedOrderModel &rom, const double x_out, const BeamBackboneSettings &beam)
  {
    Eigen::VectorXd phi, dphi;
    rom.basis().evaluate(x_out, phi, dphi);
    BackboneSettings s       = make_beam_backbone_settings(phi, beam);
    s.hb.odd_harmonics_only  = true;
    return compute_backbone(make_conservative_system(rom), s);
  }

  double single_mode_backbone_frequency(const double omega_1, const double b_111, const double q_hat)
  {
    const double w2 = omega_1 * omega_1 + 0.75 * b_111 * q_hat * q_hat;
    if (!(w2 > 0))
      throw std::invalid_argument("single_mode_backbone_frequency: ω₁² + ¾ b₁₁₁ q̂² = " + std::to_string(w2) +
                                  " (ω₁ = " + std::to_string(omega_1) + " rad/s, b₁₁₁ = " + std::to_string(b_111) +
                                  ", q̂ = " + std::to_string(q_hat) + "); must be > 0");
    return std::sqrt(w2);
  }

  double single_mode_backbone_frequency_with_slider(const double omega_1, const double b_111, const double q_hat,
                                                    const double slider_mass, const double slider_inertia,
                                                    const double phi_1_at_slider, const double dphi_1_at_slider)
  {
    if (!(slider_mass >= 0) || !(slider_inertia >= 0))
      throw std::invalid_argument("single_mode_backbone_frequency_with_slider: slider mass " +
                                  std::to_string(slider_mass) + " kg and inertia " + std::to_string(slider_inertia) +
                                  " kg m²; must be ≥ 0");
    const double w = single_mode_backbone_frequency(omega_1, b_111, q_hat);
    return w / std::sqrt(1. + slider_mass * phi_1_at_slider * phi_1_at_slider +
                         slider_inertia * dphi_1_at_slider * dphi_1_at_slider);
  }

  double single_mode_backbone_ratio(const double c, const double w_over_h)
  {
    return std::sqrt(1 + c * w_over_h * w_over_h);
  }

  double single_mode_backbone_coefficient(const double omega_1, const double b_111, const double phi_1_at_output,
                                          const double thickness)
  {
    if (!(omega_1 > 0) || phi_1_at_output == 0 || !(thickness > 0))
      throw std::invalid_argument("single_mode_backbone_coefficient: need ω₁ > 0 (" + std::to_string(omega_1) +
                                  "), φ₁(x) ≠ 0 (" + std::to_string(phi_1_at_output) + "), h > 0 (" +
                                  std::to_string(thickness) + ")");
    return 0.75 * b_111 * thickness * thickness / (phi_1_at_output * phi_1_at_output * omega_1 * omega_1);
  }
} // namespace beamslider
