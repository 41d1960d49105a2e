// Augmented-Lagrangian Gauss–Seidel solver for the contact impulses of one
// Moreau step (doc/physics.md §7–8; Studer, "Numerics of Unilateral Contacts and
// Friction", 2009, §5; Leine & Nijmeijer 2004).
//
// Numerics only (Siconos' split): the solver knows a Delassus matrix G, a
// free relative velocity c and friction coefficients μ_i, nothing about
// beams or sliders. With ξ = G P + c, contact i (unknowns P_i = (P_N, P_T),
// rows 2i and 2i+1) satisfies
//
//   P_N = prox_{R+}(P_N − r_N ξ_N) = max(0, P_N − r_N ξ_N)
//   P_T = prox_{[−μ P_N, μ P_N]}(P_T − r_T ξ_T)
//
// which is Signorini/Newton (ξ_N ≥ 0, P_N ≥ 0, ξ_N P_N = 0) and Coulomb on
// impulse level. r = ρ/G_ii (ρ the relaxation, 0 < ρ ≤ 1 is safe). One
// Gauss–Seidel sweep updates the contacts in order with the newest P.
// Convergence: the change of the relative velocities G ΔP over one sweep is at
// most `tolerance` times the velocity scale max(|c_i|, G_ii |P_i|). Reaching `max_iterations` first is a failure the caller
// must report; the solver never pretends it converged.
#pragma once

#include <Eigen/Dense>

namespace beamslider
{
  struct ProxSolverSettings
  {
    // projected: one projected Jacobi-style step per unknown (Studer's
    // augmented Lagrangian update, as the authors' code); exact_local: each
    // contact's 2×2 problem solved exactly with the others held (block
    // Gauss–Seidel), far fewer sweeps on the same fixed point.
    enum class Method
    {
      projected,
      exact_local
    };
    Method method = Method::projected;
    // Before any sweep, guess each contact's mode (open, sticking, sliding
    // left or right) from the warm start, solve the linear equations that
    // mode set implies, and accept the result if it satisfies every
    // condition exactly (to round-off); else correct the modes that failed
    // and try again, up to `mode_trials` times, then sweep as usual. Between
    // two Moreau steps the modes rarely change, so one small dense solve
    // replaces tens to hundreds of sweeps.
    bool guess_modes         = true;
    unsigned int mode_trials = 4;
    unsigned int max_iterations = 5000; // Gauss–Seidel sweeps (the mueller2023 smoke run needed up to ~1000)
    double tolerance            = 1e-10; // relative change of ξ = G P + c per sweep
    double relaxation           = 1.0;  // ρ in r_i = ρ / G_ii
  };

  struct ProxSolverResult
  {
    bool converged          = false;
    unsigned int iterations = 0;
    double residual         = 0; // last sweep's max |G ΔP| / velocity scale [-]
    bool by_modes           = false; // solved exactly by a mode guess (iterations = 0)
  };

  class ProxSolver
  {
  public:
    explicit ProxSolver(ProxSolverSettings settings = {});

    // Solves for P (size 2 n_contacts, layout (N0, T0, N1, T1, ...)); P holds
    // the warm start on entry. mu has one entry per contact.
    // Blocks of preallocated storage bind without copies; the solver's own
    // scratch grows to the largest problem seen and is reused after that.
    ProxSolverResult solve(const Eigen::Ref<const Eigen::MatrixXd> &G, const Eigen::Ref<const Eigen::VectorXd> &c,
                           const Eigen::Ref<const Eigen::VectorXd> &mu, Eigen::Ref<Eigen::VectorXd> P) const;

    const ProxSolverSettings &settings() const { return settings_; }

  private:
    // The mode-guess solve (ProxSolverSettings::guess_modes): true and P set
    // if a guess satisfied every condition.
    bool solve_by_modes(const Eigen::Ref<const Eigen::MatrixXd> &G, const Eigen::Ref<const Eigen::VectorXd> &c,
                        const Eigen::Ref<const Eigen::VectorXd> &mu, Eigen::Ref<Eigen::VectorXd> P) const;
    static bool solve_contact_exactly(const Eigen::Ref<const Eigen::MatrixXd> &G,
                                      const Eigen::Ref<const Eigen::VectorXd> &c, double mu, Eigen::Index i,
                                      Eigen::Ref<Eigen::VectorXd> P);
    ProxSolverSettings settings_;
    mutable Eigen::VectorXd r_, P_old_, dxi_; // scratch, at least 2 n_contacts
  };
} // namespace beamslider
