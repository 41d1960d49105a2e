// Seed Eq. 5 solved for the amplitude, see resonance_curve.h.
#include "reduced/resonance_curve.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace beamslider
{
  ResonanceCurveData ResonanceCurveData::from_model(const ReducedOrderModel &rom, const double slider_mass,
                                                    const double slider_inertia, const double thickness)
  {
    ResonanceCurveData d;
    const ModalBasis &basis = rom.basis();
    d.omega_1               = basis.omega[0];
    for (const CubicTerm &t : rom.analytic_cubic_terms())
      if (t.n == 0 && t.j == 0 && t.k == 0 && t.l == 0)
        d.b_111 = t.value;
    Eigen::VectorXd phi, dphi;
    basis.evaluate(0.5 * basis.length, phi, dphi);
    d.phi_1_centre   = phi[0];
    d.slider_mass    = slider_mass;
    d.slider_inertia = slider_inertia;
    d.thickness      = thickness;
    if (!(d.b_111 > 0.))
      throw std::invalid_argument("resonance curve: b_111 = " + std::to_string(d.b_111) +
                                  " must be > 0 (geometric nonlinearity switched off?)");
    return d;
  }

  double resonance_amplitude_over_h(const ReducedOrderModel &rom, const ResonanceCurveData &d, const double x_C,
                                    const double excitation_hz)
  {
    Eigen::VectorXd phi, dphi;
    rom.basis().evaluate(x_C, phi, dphi);
    const double Omega   = 2. * M_PI * excitation_hz;
    const double added   = 1. + d.slider_mass * phi[0] * phi[0] + d.slider_inertia * dphi[0] * dphi[0];
    const double q_hat_2 = (Omega * Omega * added - d.omega_1 * d.omega_1) / (0.75 * d.b_111);
    if (q_hat_2 < 0.)
      return std::numeric_limits<double>::quiet_NaN();
    return std::abs(d.phi_1_centre) * std::sqrt(q_hat_2) / d.thickness;
  }
} // namespace beamslider
