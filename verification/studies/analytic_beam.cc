#include "verification/studies/analytic_beam.h"

#include <cmath>
#include <algorithm>
#include <functional>
#include <stdexcept>

namespace beamslider::analytic
{
  namespace
  {
    // Bisection to machine precision on a bracket [a, b] with a sign change.
    double bisect(const std::function<double(double)> &f, double a, double b)
    {
      double fa = f(a);
      for (int i = 0; i < 200 && b - a > 4 * std::numeric_limits<double>::epsilon() * b; ++i)
        {
          const double m = 0.5 * (a + b), fm = f(m);
          if ((fm < 0) == (fa < 0))
            a = m, fa = fm;
          else
            b = m;
        }
      return 0.5 * (a + b);
    }

    // The n lowest positive roots of f, found by scanning in steps much
    // smaller than the root spacing (≈ π) and bisecting each sign change.
    std::vector<double> lowest_roots(const std::function<double(double)> &f, const unsigned int n)
    {
      std::vector<double> roots;
      const double step = 1e-3;
      double x = step, fx = f(x);
      while (roots.size() < n)
        {
          const double y = x + step, fy = f(y);
          if ((fx < 0) != (fy < 0) && std::isfinite(fx) && std::isfinite(fy))
            roots.push_back(bisect(f, x, y));
          x = y, fx = fy;
          if (x > 1e4)
            throw std::runtime_error("analytic beam: root search did not find enough roots");
        }
      return roots;
    }
  } // namespace

  std::vector<double> clamped_clamped_beta_L(const unsigned int n)
  {
    // cos x cosh x - 1 = 0, divided by cosh x: cos x - 1/cosh x = 0.
    return lowest_roots([](double x) { return std::cos(x) - 1. / std::cosh(x); }, n);
  }

  std::vector<double> spring_supported_beta_L(const unsigned int n, const double EI, const double L, const double k_r)
  {
    if (std::isinf(k_r))
      return clamped_clamped_beta_L(n);
    // In terms of x = βL and a = x/2; both symmetric and antisymmetric
    // conditions multiplied by L/(EI x) to make them dimensionless.
    const double kappa = k_r * L / EI; // dimensionless spring stiffness
    auto symmetric     = [kappa](double x) {
      const double a = 0.5 * x;
      return 2 * x * std::cos(a) + kappa * (std::cos(a) * std::tanh(a) + std::sin(a));
    };
    auto antisymmetric = [kappa](double x) {
      const double a = 0.5 * x;
      return 2 * x * std::sin(a) * std::tanh(a) + kappa * (std::sin(a) - std::tanh(a) * std::cos(a));
    };
    std::vector<double> s = lowest_roots(symmetric, n), t = lowest_roots(antisymmetric, n);
    std::vector<double> all(s);
    all.insert(all.end(), t.begin(), t.end());
    std::sort(all.begin(), all.end());
    all.resize(n);
    return all;
  }

  double frequency_from_beta_L(const double beta_L, const double EI, const double rhoA, const double L)
  {
    return beta_L * beta_L / (L * L) * std::sqrt(EI / rhoA);
  }
} // namespace beamslider::analytic
