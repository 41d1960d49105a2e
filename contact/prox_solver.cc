// Augmented-Lagrangian Gauss–Seidel prox solver, see prox_solver.h.
#include "contact/prox_solver.h"

#include <algorithm>
#include <array>
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

  namespace
  {
    // z = A⁻¹ b by a full-pivoting LU of the K × K matrix A (one solution
    // with the free unknowns zero if A is singular), into fixed-size storage.
    template <int K, typename Matrix, typename Vector>
    void solve_fixed_size(const Matrix &A, const Vector &b, Vector &z)
    {
      const Eigen::FullPivLU<Eigen::Matrix<double, K, K>> lu(A.template topLeftCorner<K, K>());
      z = lu.solve(b.template head<K>());
    }

    constexpr int max_n = 8; // unknowns of the mode-guess solve: four corners, the slider's most
    using Small         = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, max_n, max_n>;
    using SmallVector   = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, max_n, 1>;
    using Trial         = Eigen::Matrix<double, max_n, 1>;
    using MatrixRef     = Eigen::Ref<const Eigen::MatrixXd>;
    using VectorRef     = Eigen::Ref<const Eigen::VectorXd>;

    enum class Mode : unsigned char
    {
      open,
      stick,
      slide_positive, // P_T = +μ P_N
      slide_negative  // P_T = −μ P_N
    };

    // A guess of each contact's mode, and the k linear equations it implies.
    struct ModeSet
    {
      std::array<Mode, max_n / 2> mode;
      Eigen::Index k = 0;
      std::array<Eigen::Index, max_n> equation, unknown; // ξ row of each equation, P entry of each unknown
      std::array<double, max_n> slope;                    // P_T = slope · P_N for a sliding contact's unknown
    };

    // The modes the warm start P points to.
    void guess_from_warm_start(const Eigen::Ref<Eigen::VectorXd> &P, const VectorRef &mu, const Eigen::Index m,
                               ModeSet &set)
    {
      for (Eigen::Index i = 0; i < m; ++i)
        {
          const double p_N = P[2 * i], p_T = P[2 * i + 1];
          if (!(p_N > 0.))
            set.mode[i] = Mode::open;
          else if (std::abs(p_T) >= mu[i] * p_N * (1. - 1e-12) && mu[i] > 0.)
            set.mode[i] = p_T > 0. ? Mode::slide_positive : Mode::slide_negative;
          else
            set.mode[i] = Mode::stick;
        }
    }

    // Unknowns and equations of the mode set.
    void set_up_equations(const VectorRef &mu, const Eigen::Index m, ModeSet &set)
    {
      Eigen::Index &k = set.k;
      k               = 0;
      for (Eigen::Index i = 0; i < m; ++i)
        switch (set.mode[i])
          {
            case Mode::open:
              break;
            case Mode::stick:
              set.equation[k] = 2 * i, set.unknown[k] = 2 * i, set.slope[k] = 0., ++k;
              set.equation[k] = 2 * i + 1, set.unknown[k] = 2 * i + 1, set.slope[k] = 0., ++k;
              break;
            case Mode::slide_positive:
            case Mode::slide_negative:
              set.equation[k] = 2 * i, set.unknown[k] = 2 * i;
              set.slope[k]    = (set.mode[i] == Mode::slide_positive ? 1. : -1.) * mu[i];
              ++k;
              break;
          }
    }

    // The impulses of the mode set (trial, zero but for its k > 0
    // unknowns) from its equations A z = −E c; false if they are
    // inconsistent (no solution in this mode set).
    bool solve_equations(const MatrixRef &G, const VectorRef &c, const double c_scale, const ModeSet &set,
                         Trial &trial)
    {
      const Eigen::Index k = set.k;
      Small A(k, k);
      SmallVector b(k), z;
      for (Eigen::Index r = 0; r < k; ++r)
        {
          b[r] = -c[set.equation[r]];
          for (Eigen::Index j = 0; j < k; ++j)
            {
              // A sliding contact's unknown P_N also moves its P_T = slope · P_N.
              A(r, j) = G(set.equation[r], set.unknown[j]);
              if (set.slope[j] != 0.)
                A(r, j) += set.slope[j] * G(set.equation[r], set.unknown[j] + 1);
            }
        }
      if (k == 1)
        {
          // One equation a z = b, the commonest mode set (a single
          // sliding corner; over half of the solves on the signature
          // move), where the LU's set-up costs more than the solve:
          // what Eigen's full-pivoting LU returns, to the bit: rank
          // 0 (z = 0) unless a is finite and nonzero, and a zero
          // right-hand side left as it is (its sign kept).
          const double a = A(0, 0);
          z.resize(1);
          z[0] = std::isfinite(a) && a != 0. ? (b[0] != 0. ? b[0] / a : b[0]) : 0.;
        }
      else
        switch (k)
          {
            // Two to four unknowns (two corners on one face, or a
            // sticking one): Eigen's LU at the size it has, whose
            // loops unroll, rather than at the capacity's run-time size.
            case 2:
              solve_fixed_size<2>(A, b, z);
              break;
            case 3:
              solve_fixed_size<3>(A, b, z);
              break;
            case 4:
              solve_fixed_size<4>(A, b, z);
              break;
            default:
              {
                const Eigen::FullPivLU<Small> lu(A);
                z = lu.solve(b);
              }
          }
      // The residual inlined (≤ 64 products): it only decides
      // acceptance against a tolerance seven orders above round-off.
      if (!z.allFinite() || (A.lazyProduct(z) - b).cwiseAbs().maxCoeff() > 1e-9 * std::max(c_scale, 1e-300))
        return false;
      for (Eigen::Index j = 0; j < k; ++j)
        {
          trial[set.unknown[j]] = z[j];
          if (set.slope[j] != 0.)
            trial[set.unknown[j] + 1] = set.slope[j] * z[j];
        }
      return true;
    }

    // The conditions each mode leaves to be checked; a contact whose check
    // fails moves to the mode it points to. True if all hold.
    bool modes_hold(const MatrixRef &G, const VectorRef &c, const VectorRef &mu, const double c_scale,
                    const Trial &trial, ModeSet &set)
    {
      const Eigen::Index n = c.size(), m = n / 2;
      // Into storage of fixed capacity (no heap), inlined: a call into
      // Eigen's matrix–vector kernel costs more than these ≤ 64 products.
      SmallVector xi(n);
      xi.noalias() = G.lazyProduct(trial.head(n));
      xi += c;
      double scale = c_scale;
      for (Eigen::Index i = 0; i < n; ++i)
        scale = std::max(scale, G(i, i) * std::abs(trial[i]));
      const double tol = 1e-12 * scale;
      bool all_hold    = true;
      for (Eigen::Index i = 0; i < m; ++i)
        {
          const double p_N = trial[2 * i], p_T = trial[2 * i + 1];
          const double gN = G(2 * i, 2 * i), gT = G(2 * i + 1, 2 * i + 1);
          Mode &mode = set.mode[i];
          switch (mode)
            {
              case Mode::open:
                if (xi[2 * i] < -tol)
                  mode = Mode::stick, all_hold = false;
                break;
              case Mode::stick:
                if (gN * p_N < -tol)
                  mode = Mode::open, all_hold = false;
                else if (gT * std::abs(p_T) > gT * mu[i] * p_N + tol)
                  mode = p_T > 0. ? Mode::slide_positive : Mode::slide_negative, all_hold = false;
                break;
              case Mode::slide_positive:
              case Mode::slide_negative:
                {
                  const double s = mode == Mode::slide_positive ? 1. : -1.;
                  if (gN * p_N < -tol)
                    mode = Mode::open, all_hold = false;
                  else if (s * xi[2 * i + 1] > tol)
                    mode = Mode::stick, all_hold = false;
                  break;
                }
            }
        }
      return all_hold;
    }
  } // namespace

  // Each contact's conditions in a given mode are linear:
  //   open:    P = 0                       (check: ξ_N ≥ 0)
  //   stick:   ξ_N = 0, ξ_T = 0            (check: P_N ≥ 0, |P_T| ≤ μ P_N)
  //   slide s: ξ_N = 0, P_T = s μ P_N      (check: P_N ≥ 0, s ξ_T ≤ 0)
  // so a mode set gives k ≤ 2 n_contacts linear equations A z = −E c for the
  // unknown impulses z. A may be singular: two corners on one face of the
  // (locally rigid) beam share their directions, and only the sum of their
  // impulses is determined; a full-pivoting LU gives one solution, the
  // residual check below confirms it solves the equations, and the mode
  // checks decide. A failed check moves that contact to the mode it points
  // to (open → stick, stick → open or slide, slide → open or stick) for the
  // next trial. Tolerances: round-off relative to the problem's velocity
  // scale.
  bool ProxSolver::solve_by_modes(const Eigen::Ref<const Eigen::MatrixXd> &G, const Eigen::Ref<const Eigen::VectorXd> &c,
                                  const Eigen::Ref<const Eigen::VectorXd> &mu, Eigen::Ref<Eigen::VectorXd> P) const
  {
    const Eigen::Index n = c.size(), m = n / 2;
    if (n > max_n)
      return false;
    ModeSet set;
    guess_from_warm_start(P, mu, m, set);
    const double c_scale = c.cwiseAbs().maxCoeff();
    Trial trial;
    for (unsigned int attempt = 0; attempt < settings_.mode_trials; ++attempt)
      {
        set_up_equations(mu, m, set);
        trial.head(n).setZero();
        if (set.k > 0 && !solve_equations(G, c, c_scale, set, trial))
          return false;
        if (modes_hold(G, c, mu, c_scale, trial, set))
          {
            // Round-off below the tolerance moved back inside the cones.
            for (Eigen::Index i = 0; i < m; ++i)
              {
                const double p_N = std::max(0., trial[2 * i]);
                P[2 * i]         = p_N;
                P[2 * i + 1]     = std::clamp(trial[2 * i + 1], -mu[i] * p_N, mu[i] * p_N);
              }
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

    // A zero diagonal would mean a contact that no mass can move; refuse it
    // rather than divide by zero.
    for (Eigen::Index i = 0; i < n; ++i)
      if (!(G(i, i) > 0.))
        {
          std::ostringstream m;
          m << "prox solver: Delassus diagonal G(" << i << "," << i << ") = " << G(i, i)
            << " is not positive (a contact direction no mass can move)";
          throw std::runtime_error(m.str());
        }

    if (settings_.guess_modes && solve_by_modes(G, c, mu, P))
      {
        result.converged = true;
        result.by_modes  = true;
        return result;
      }

    // Step sizes from the diagonal of G, for the sweeps only (a mode guess
    // that holds needs none: most solves end above).
    if (r_.size() < n)
      {
        r_.resize(n);
        P_old_.resize(n);
        dxi_.resize(n);
      }
    auto r = r_.head(n), P_old = P_old_.head(n), dxi = dxi_.head(n);
    for (Eigen::Index i = 0; i < n; ++i)
      r[i] = settings_.relaxation / G(i, i);

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
