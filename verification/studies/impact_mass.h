// The beam mass an impact moves: for a slider corner at x, one Moreau step
// changes the beam's velocity by S⁻¹ w P (w = ∂w(x)/∂q), so the corner meets
// the mass m = 1/(wᵀ S⁻¹ w). An impulse of a heavy rigid corner on it is
// about (1 + e_N) m times the approach velocity, so an impact, and the
// rattling that the adaptation integrates, changes with anything that
// changes m: the FE's Δt and formulation (`Time stepping/FE impulses`) and
// mesh, the ROM's N. This study computes m on each (doc/physics.md §7,
// report section 5.6); it costs a factorisation a setting.
#pragma once

#include "scene/scene.h"

#include <string>
#include <vector>

namespace beamslider
{
  struct ImpactMass
  {
    std::string formulation;   // FE: step | mass | redistributed; ROM: "ROM explicit"
    unsigned int elements = 0; // FE mesh (0 for the ROM)
    unsigned int modes    = 0; // ROM's N (0 for the FE)
    double time_step      = 0; // [s] (0 for the explicit ROM: S = I, no Δt dependence)
    double mass           = 0; // 1/(wᵀ S⁻¹ w) at the left corner [kg]
  };

  struct ImpactMassSettings
  {
    std::vector<std::string> formulations{"step", "mass", "redistributed"};
    std::vector<unsigned int> elements{32, 64};
    std::vector<double> time_steps{2e-5, 1e-5, 5e-6, 2.5e-6, 1.25e-6}; // coarsest first
    std::vector<unsigned int> modes{5, 7, 10, 15, 20, 30};
  };

  // m at the slider's left corner pair at the scene's start position
  // (x_C − B/2), the FE with the scene's FE θ and every setting's
  // formulation, mesh and Δt; the explicit ROM with each N.
  std::vector<ImpactMass> impact_masses(const Scene &scene, const ImpactMassSettings &settings);

  // Observed order of m over three steps h, h/2, h/4:
  // log₂ |m(h) − m(h/2)| / |m(h/2) − m(h/4)|; NaN when both differences are
  // below 1e-9 relative (no Δt dependence to measure).
  double observed_order(double m_h, double m_h2, double m_h4);
} // namespace beamslider
