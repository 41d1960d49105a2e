// Test fixture shared by the test_reduced_* tests: the analytic modes of a
// clamped–clamped Euler–Bernoulli beam, mass-normalised, built independently of
// any FE code, and the ModalBasis of doc/physics.md §5 computed from them by
// quadrature.
//
//   φ_n(x) = C_n [cosh βx − cos βx − σ_n (sinh βx − sin βx)],
//   σ_n = (cosh βL − cos βL)/(sinh βL − sin βL),  cos βL cosh βL = 1,
//   ω_n = β_n² sqrt(EI/(ρA)),  ∫ ρA φ_n² dx = 1,
//   K'_jk = ∫ φ_j' φ_k' dx,  γ_n = −ρA ∫ φ_n dx,  k_ax = EA/L (ideal clamp).
//
// The hyperbolic terms are evaluated as ½e^{βx}(1−σ) + ½e^{−βx}(1+σ) with 1−σ
// written without cancellation, so high modes keep full precision.
// Default data: the mueller2023 beam (L = 0.14 m, b = 14.04 mm, h = 1 mm,
// E = 210 GPa, ρ = 7683 kg/m³; Müller, Beck & Krack, MSSP 2023).
#pragma once

#include "scene/scene.h"
#include "reduced/modal_basis.h"

#include <Eigen/Dense>

#include <cmath>
#include <functional>
#include <vector>

namespace beamslider_test
{
  struct ClampedBeam
  {
    double L = 0.14, b = 14.04e-3, h = 1e-3, E = 210e9, rho = 7683;
    double A() const { return b * h; }
    double I() const { return b * h * h * h / 12; }

    // Roots of cos B cosh B = 1 (as cos B − 1/cosh B = 0), Newton from the
    // tabulated values (4.730041, 7.853205, …) or (2n+1)π/2 beyond.
    static double root(const unsigned int n)
    {
      static const double table[] = {4.730041, 7.853205, 10.995608, 14.137165, 17.278760};
      const double pi             = std::acos(-1.);
      double B                    = n < 5 ? table[n] : (2. * n + 3.) * pi / 2.;
      for (int it = 0; it < 50; ++it)
        {
          const double g  = std::cos(B) - 1. / std::cosh(B);
          const double dg = -std::sin(B) + std::tanh(B) / std::cosh(B);
          const double dB = -g / dg;
          B += dB;
          if (std::abs(dB) < 1e-15 * B)
            break;
        }
      return B;
    }

    // Unnormalised shape φ̃ and its derivative dφ̃/dx at x for root B.
    void shape(const double B, const double x, double &phi, double &dphi) const
    {
      const double beta = B / L, z = beta * x;
      const double s    = std::sinh(B) - std::sin(B);
      const double one_minus_sigma = (std::cos(B) - std::sin(B) - std::exp(-B)) / s;
      const double sigma           = 1. - one_minus_sigma;
      const double ep = 0.5 * std::exp(z) * one_minus_sigma, em = 0.5 * std::exp(-z) * (1. + sigma);
      phi  = ep + em - std::cos(z) + sigma * std::sin(z);
      dphi = beta * (ep - em + std::sin(z) + sigma * std::cos(z));
    }

    // Composite 5-point Gauss–Legendre on n_intervals equal intervals of [0, L].
    double integrate(const std::function<double(double)> &f, const unsigned int n_intervals = 400) const
    {
      static const double xg[] = {-0.9061798459386640, -0.5384693101056831, 0., 0.5384693101056831,
                                  0.9061798459386640};
      static const double wg[] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                  0.2369268850561891};
      const double dx = L / n_intervals;
      double sum      = 0;
      for (unsigned int i = 0; i < n_intervals; ++i)
        for (int g = 0; g < 5; ++g)
          sum += 0.5 * dx * wg[g] * f((i + 0.5) * dx + 0.5 * dx * xg[g]);
      return sum;
    }

    // The N lowest modes: roots, normalisation constants, and the basis.
    struct Modes
    {
      std::vector<double> B, C;
      beamslider::ModalBasis basis;
    };

    Modes modes(const unsigned int N, const unsigned int n_intervals = 400) const
    {
      Modes m;
      for (unsigned int n = 0; n < N; ++n)
        {
          m.B.push_back(root(n));
          const double B = m.B.back();
          const double I2 = integrate(
            [&](double x) {
              double p, d;
              shape(B, x, p, d);
              return p * p;
            },
            n_intervals);
          m.C.push_back(1. / std::sqrt(rho * A() * I2));
        }
      auto &basis  = m.basis;
      basis.length = L;
      basis.omega.resize(N);
      basis.gamma.resize(N);
      basis.stretch.resize(N, N);
      basis.membrane_stiffness = E * A() / L;
      const std::vector<double> B = m.B, C = m.C;
      const ClampedBeam beam      = *this;
      basis.evaluate = [beam, B, C](double x, Eigen::VectorXd &phi, Eigen::VectorXd &dphi) {
        phi.resize(B.size());
        dphi.resize(B.size());
        for (unsigned int n = 0; n < B.size(); ++n)
          {
            double p, d;
            beam.shape(B[n], x, p, d);
            phi[n]  = C[n] * p;
            dphi[n] = C[n] * d;
          }
      };
      // Quadrature points and weights, then φ and φ' of all modes there once:
      // K' = Dᵀ W D, γ = −ρA Pᵀ w.
      const double xg[] = {-0.9061798459386640, -0.5384693101056831, 0., 0.5384693101056831, 0.9061798459386640};
      const double wg[] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                           0.2369268850561891};
      const double dx = L / n_intervals;
      Eigen::VectorXd w(5 * n_intervals);
      Eigen::MatrixXd P(5 * n_intervals, N), D(5 * n_intervals, N);
      for (unsigned int i = 0; i < n_intervals; ++i)
        for (int g = 0; g < 5; ++g)
          {
            const unsigned int r = 5 * i + g;
            w[r]                 = 0.5 * dx * wg[g];
            Eigen::VectorXd p, d;
            basis.evaluate((i + 0.5) * dx + 0.5 * dx * xg[g], p, d);
            P.row(r) = p.transpose();
            D.row(r) = d.transpose();
          }
      for (unsigned int n = 0; n < N; ++n)
        basis.omega[n] = B[n] * B[n] / (L * L) * std::sqrt(E * I() / (rho * A()));
      basis.gamma   = -rho * A() * P.transpose() * w;
      basis.stretch = D.transpose() * w.asDiagonal() * D;
      return m;
    }
  };

  // |a − b| ≤ tol·|b| (relative to the reference b).
  inline double relative_error(const double a, const double b) { return std::abs(a - b) / std::abs(b); }

  // The mueller2023 scene (scene.h's defaults) with its supports ideal
  // clamps, the beam these analytic modes describe.
  inline beamslider::Scene ideal_clamp_scene()
  {
    beamslider::Scene scene;
    scene.name                 = "mueller2023-analytic-clamp";
    scene.supports.ideal_clamp = true;
    return scene;
  }
} // namespace beamslider_test
