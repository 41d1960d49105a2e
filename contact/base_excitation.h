// Harmonic base excitation of the beam's supports (doc/physics.md §1):
//
//   w0(t) = (â/Ω²) cos Ωt ,   ẇ0(t) = −(â/Ω) sin Ωt ,   ẅ0(t) = −â cos Ωt ,
//
// â the base acceleration amplitude [m/s²], Ω = 2π f_ex [rad/s]. Ω = 0 means
// no excitation (the base stands still; used by the static tests).
// The beam coordinates are relative to the base; the slider's are absolute, so
// every gap depends explicitly on time through w0.
#pragma once

#include "scene/scene.h"

#include <cmath>
#include <limits>

namespace beamslider
{
  struct BaseExcitation
  {
    double acceleration_amplitude = 0; // â [m/s²]
    double angular_frequency      = 0; // Ω [rad/s]

    static BaseExcitation from_scene(const ExcitationData &e)
    {
      return {e.acceleration_amplitude, 2. * M_PI * e.frequency_hz};
    }

    double displacement(const double t) const // w0 [m]
    {
      if (angular_frequency == 0.)
        return 0.;
      return acceleration_amplitude / (angular_frequency * angular_frequency) * std::cos(angular_frequency * t);
    }
    double velocity(const double t) const // ẇ0 [m/s]
    {
      if (angular_frequency == 0.)
        return 0.;
      return -acceleration_amplitude / angular_frequency * std::sin(angular_frequency * t);
    }
    double acceleration(const double t) const // ẅ0 [m/s²]
    {
      if (angular_frequency == 0.)
        return 0.;
      return -acceleration_amplitude * std::cos(angular_frequency * t);
    }
    // w0 and ẇ0 at one time, with one shared evaluation of the phase's
    // sine and cosine (the compiler's sincos; the same bits as displacement()
    // and velocity(), which the contact step asks for together).
    void displacement_and_velocity(const double t, double &w0, double &dw0) const
    {
      if (angular_frequency == 0.)
        {
          w0 = dw0 = 0.;
          return;
        }
      const double phase = angular_frequency * t;
      const double c = std::cos(phase), s = std::sin(phase);
      w0  = acceleration_amplitude / (angular_frequency * angular_frequency) * c;
      dw0 = -acceleration_amplitude / angular_frequency * s;
    }
    // One excitation period [s] (infinite without excitation).
    double period() const
    {
      return angular_frequency > 0. ? 2. * M_PI / angular_frequency : std::numeric_limits<double>::infinity();
    }
  };
} // namespace beamslider
