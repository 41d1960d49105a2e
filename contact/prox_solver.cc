// Augmented-Lagrangian Gauss–Seidel prox solver, see prox_solver.h.
#include "contact/prox_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  ProxSolver::ProxSolver(const ProxSolverSettings settings)
    : settings_(settings)
  {
    if (!(settings_.relaxation > 0. && settings_.relaxation <= 2.))
      {
        std::ostringstream m;
        m << "prox solver relaxation = " << settings_.relaxation << " is outside the allowed range (0, 2]";
        throw std::invalid_argument(m.str());
      }
    if (settings_.max_iterations == 0)
      throw std::invalid_argument("prox solver max_iterations = 0; it must be at least 1");
    if (!(settings_.tolerance > 0.))
      {
        std::ostringstream m;
        m << "prox solver tolerance = " << settings_.tolerance << " must be positive";
        throw std::invalid_argument(m.str());
      }
  }

  // The local problem of contact i with the other impulses held: ξ_i = A P_i
  // + b, A the 2×2 diagonal block of G. Its solution is one of: open (P = 0,
  // if b_N ≥ 0), sticking (A P = −b inside the cone |P_T| ≤ μ P_N), or
  // sliding in direction s = ±1 (P_T = s μ P_N, ξ_N = 0, and the sliding
  // velocity ξ_T opposing the friction impulse: s ξ_T ≤ 0). The first that
  // holds is taken; false if none does (round-off at a case boundary), and
  // the caller falls back to the projected update.
  bool ProxSolver::solve_contact_exactly(const Eigen::Ref<const Eigen::MatrixXd> &G,
                                         const Eigen::Ref<const Eigen::VectorXd> &c, const double mu,
                                         const Eigen::Index i, Eigen::Ref<Eigen::VectorXd> P)
  {
    const Eigen::Index iN = 2 * i, iT = 2 * i + 1;
    const double a_nn = G(iN, iN), a_nt = G(iN, iT), a_tn = G(iT, iN), a_tt = G(iT, iT);
    // b = c_i + Σ_{j≠i} G_ij P_j
    const double b_N = G.row(iN).dot(P) + c[iN] - a_nn * P[iN] - a_nt * P[iT];
    const double b_T = G.row(iT).dot(P) + c[iT] - a_tn * P[iN] - a_tt * P[iT];
    if (b_N >= 0.)
      {
        P[iN] = P[iT] = 0.;
        return true;
      }
    const double det = a_nn * a_tt - a_nt * a_tn;
    if (det > 0.)
      {
        const double p_N = (-b_N * a_tt + b_T * a_nt) / det;
        const double p_T = (-b_T * a_nn + b_N * a_tn) / det;
        if (p_N >= 0. && std::abs(p_T) <= mu * p_N)
          {
            P[iN] = p_N;
            P[iT] = p_T;
            return true;
          }
      }
    for (const double s : {1., -1.})
      {
        const double a = a_nn + s * mu * a_nt;
        if (!(a > 0.))
          continue;
        const double p_N  = -b_N / a;
        const double xi_T = (a_tn + s * mu * a_tt) * p_N + b_T;
        if (p_N >= 0. && s * xi_T <= 0.)
          {
            P[iN] = p_N;
            P[iT] = s * mu * p_N;
            return true;
          }
      }
    return false;
  }

  ProxSolverResult ProxSolver::solve(const Eigen::Ref<const Eigen::MatrixXd> &G,
                                     const Eigen::Ref<const Eigen::VectorXd> &c,
                                     const Eigen::Ref<const Eigen::VectorXd> &mu, Eigen::Ref<Eigen::VectorXd> P) const
  {
    const Eigen::Index n = c.size();
    if (G.rows() != n || G.cols() != n || P.size() != n || 2 * mu.size() != n)
      throw std::invalid_argument("prox solver: G, c, P must have size 2 n_contacts and mu n_contacts");

    ProxSolverResult result;
    if (n == 0)
      {
        result.converged = true;
        return result;
      }

    // Step sizes from the diagonal of G. A zero diagonal would mean a contact
    // that no mass can move; refuse it rather than divide by zero.
    if (r_.size() < n)
      {
        r_.resize(n);
        P_old_.resize(n);
        dxi_.resize(n);
      }
    auto r = r_.head(n), P_old = P_old_.head(n), dxi = dxi_.head(n);
    for (Eigen::Index i = 0; i < n; ++i)
      {
        if (!(G(i, i) > 0.))
          {
            std::ostringstream m;
            m << "prox solver: Delassus diagonal G(" << i << "," << i << ") = " << G(i, i)
              << " is not positive (a contact direction no mass can move)";
            throw std::runtime_error(m.str());
          }
        r[i] = settings_.relaxation / G(i, i);
      }

    // Convergence is judged on the relative velocities, G ΔP over one sweep,
    // not on P itself: with redundant contacts (two corners on a rigid beam
    // share one tangent direction) the split of P is not unique and
    // Gauss–Seidel creeps along that null space while ξ is already converged.
    for (unsigned int it = 1; it <= settings_.max_iterations; ++it)
      {
        P_old = P;
        for (Eigen::Index i = 0; i < n / 2; ++i)
          {
            const Eigen::Index iN = 2 * i, iT = 2 * i + 1;
            if (settings_.method == ProxSolverSettings::Method::exact_local &&
                solve_contact_exactly(G, c, mu[i], i, P))
              continue;
            const double xi_N     = G.row(iN).dot(P) + c[iN];
            const double P_N      = std::max(0., P[iN] - r[iN] * xi_N);
            P[iN]                 = P_N;

            const double xi_T  = G.row(iT).dot(P) + c[iT];
            const double bound = mu[i] * P_N;
            P[iT]              = std::clamp(P[iT] - r[iT] * xi_T, -bound, bound);
          }
        P_old         = P - P_old; // the sweep's change ΔP, in place (no temporary)
        dxi.noalias() = G * P_old;
        // Velocity scale: the free relative velocities and what the impulses do.
        double scale = c.cwiseAbs().maxCoeff();
        for (Eigen::Index i = 0; i < n; ++i)
          scale = std::max(scale, G(i, i) * std::abs(P[i]));
        const double change = dxi.cwiseAbs().maxCoeff();
        result.iterations   = it;
        result.residual     = scale > 0. ? change / scale : change;
        if (!std::isfinite(result.residual))
          return result; // not converged: a NaN in G or c
        if (change <= settings_.tolerance * scale)
          {
            result.converged = true;
            return result;
          }
      }
    return result;
  }
} // namespace beamslider
