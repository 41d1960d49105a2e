// A pushing spring–dashpot's restitution and its inverse, see
// spring_dashpot_restitution.h.
#include "numerics/spring_dashpot_restitution.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    // ζ is searched in [0, ζ_max]: above critical damping the oscillation's
    // closed form changes, and a contact that damped is no impact law
    // anyone asks for.
    constexpr double largest_damping_ratio = 0.999;

    // Bisection of a sign change of f on [a, b], to round-off.
    template <typename F>
    double bisect(const F &f, double a, double b)
    {
      const bool positive_at_a = f(a) > 0.;
      for (unsigned int i = 0; i < 200 && b - a > 1e-15 * (1. + std::abs(a)); ++i)
        {
          const double m = 0.5 * (a + b);
          ((f(m) > 0.) == positive_at_a ? a : b) = m;
        }
      return 0.5 * (a + b);
    }
  } // namespace

  double pushing_spring_dashpot_restitution(const double zeta)
  {
    if (!(zeta >= 0. && zeta <= largest_damping_ratio))
      throw std::invalid_argument("damping ratio outside [0, 0.999]");
    // Unit mass and stiffness, penetration x(0) = 0, ẋ(0) = 1:
    // x = e^{−ζt} sin(ω_d t)/ω_d, ẋ = e^{−ζt}(cos ω_d t − ζ/ω_d sin ω_d t);
    // the force x + 2ζẋ is 2ζ > 0 at t = 0 and −2ζ e^{−ζπ/ω_d} < 0 at
    // t = π/ω_d, with one zero between.
    const double wd   = std::sqrt(1. - zeta * zeta);
    auto velocity     = [&](const double t) {
      return std::exp(-zeta * t) * (std::cos(wd * t) - zeta / wd * std::sin(wd * t));
    };
    auto force        = [&](const double t) {
      return std::exp(-zeta * t) * std::sin(wd * t) / wd + 2. * zeta * velocity(t);
    };
    if (zeta == 0.)
      return 1.;
    const double t_leave = bisect(force, 0., M_PI / wd);
    return -velocity(t_leave);
  }

  double smallest_compliant_restitution() { return pushing_spring_dashpot_restitution(largest_damping_ratio); }

  double pushing_spring_dashpot_damping_ratio(const double e)
  {
    const double e_min = smallest_compliant_restitution();
    if (!(e > e_min && e <= 1.))
      {
        std::ostringstream m;
        m << "restitution e_N = " << e << " is outside (" << e_min
          << ", 1], the range a compliant normal law (Contact/Normal stiffness > 0) reaches with a damper that "
             "only pushes; use the rigid law (Normal stiffness = 0) for a smaller e_N";
        throw std::invalid_argument(m.str());
      }
    if (e == 1.)
      return 0.;
    return bisect([&](const double zeta) { return pushing_spring_dashpot_restitution(zeta) - e; }, 0.,
                  largest_damping_ratio);
  }
} // namespace beamslider
