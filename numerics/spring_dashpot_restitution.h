// The restitution of a spring–dashpot contact whose force may push but
// never pull (Kelvin–Voigt, force k x + c ẋ while positive), and the damping
// ratio that gives a wanted restitution: what the compliant corners of the
// contact law (doc/physics.md §4, Contact/Normal stiffness) take their
// damping from, so that e_N means the same with rigid and compliant corners.
// The corner leaves when the force reaches zero, while the spring is still
// compressed, so the restitution is not the textbook exp(−ζπ/√(1 − ζ²)).
#pragma once

namespace beamslider
{
  // The restitution of a mass on a spring–dashpot of damping ratio ζ ∈ [0, 1)
  // whose force may only push: from the closed-form damped oscillation, the
  // velocity ratio at the first time the force vanishes.
  double pushing_spring_dashpot_restitution(double damping_ratio);

  // The damping ratio ζ whose restitution is e; throws std::invalid_argument
  // naming e_N for e outside (e(ζ → 1), 1] (about (0.135, 1]: a dashpot
  // that only pushes returns at least 13.5 % of the approach velocity up to
  // critical damping).
  double pushing_spring_dashpot_damping_ratio(double restitution);

  // The smallest restitution the compliant law reaches (ζ just below 1).
  double smallest_compliant_restitution();
} // namespace beamslider
