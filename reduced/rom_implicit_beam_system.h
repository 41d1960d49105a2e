// The reduced-order model stepped with the FE's scheme (fem/fe_transient.h):
// one rung of the error ladder between the published ROM and the FE model,
// which changes the time integrator and nothing else.
//
// The smooth part of a Moreau step by the implicit midpoint rule (θ = ½),
// with the same midpoint structure as the explicit ROM (q_M = q_B + Δt/2 u_B,
// q_E = q_M + Δt/2 u_E):
//
//   R(u) = (u − u_B) + Δt [ C (u_B + u)/2 + Ω² q̄ + f_nl(q̄) − γ ẅ0(t_M) ] = 0,
//   q̄ = q_M + Δt/4 (u − u_B),   C = diag(2 D ω_n),   Ω² = diag(ω_n²),
//
// solved for u_free by Newton with the N × N iteration matrix
//   S = I + Δt/2 C + Δt²/4 (Ω² + ∂f_nl/∂q(q̄)).
// With the analytic membrane force f = (k/2)(q̄ᵀK'q̄) K'q̄ the tangent is
// (k/2)(q̄ᵀK'q̄) K' + k (K'q̄)(K'q̄)ᵀ, so S = D + α K' + β v vᵀ with the fixed
// diagonal D = I + Δt/2 C + Δt²/4 Ω², α = Δt²k/8 q̄ᵀK'q̄, β = Δt²k/4, v = K'q̄.
// One symmetric eigendecomposition per Δt, D^-½ K' D^-½ = V Λ Vᵀ, turns it into
//   S = D^½ V (I + αΛ + β z zᵀ) Vᵀ D^½,   z = Vᵀ D^-½ v,
// a diagonal plus rank one (Sherman–Morrison): O(N²) per solve instead of a
// dense LU's O(N³), which is what makes the ROM with every mode of the FE
// mesh (N = 64) affordable. A cubic tensor from STEP or ICE has no such
// structure and is solved by dense LU at every iteration. Contact impulses go
// through the last iteration's S, u_E = u_free + S⁻¹ W P, as in the FE. For a
// linear beam this is the trapezoidal rule: no step-size limit, no numerical
// damping, period elongation (ωΔt)²/12 per mode.
//
// Newton stops when ‖δu‖ ≤ 1e-10 (‖u‖ + ‖q̄‖/Δt) + 1e-14 (q_E within 1e-10
// of the state's size), and throws std::runtime_error (time and correction)
// after 30 iterations.
// Energy bookkeeping: damping −Δt ū·C ū, base load Δt ẅ0 γ·ū with
// ū = (u_B + u_E)/2, as for the FE.
//
// θ > ½ (the Moreau–Jean θ-method, as the FE reference runs it; issue 58's
// family (d)): q̄ = q_M + θ²Δt (u − u_B) + (2θ − 1)Δt u_B, the damping on
// θu + (1 − θ)u_B, the load at t_M + (2θ − 1)Δt, and S = I + θΔt C +
// θ²Δt² (Ω² + ∂f_nl/∂q); the stepper moves with θ too (theta()). It damps
// a mode by a factor per step that grows with ωΔt (→ (1 − θ)/θ per step for
// ωΔt ≫ 1): the modes the step cannot resolve ring down after each impact
// instead of ringing at a wrong frequency. θ = ½ is the same arithmetic,
// bit for bit, as the midpoint rule above.
#pragma once

#include "reduced/rom_beam_system.h"

#include <Eigen/Dense>

#include <limits>

namespace beamslider
{
  class RomImplicitBeamSystem : public RomBeamSystem
  {
  public:
    // θ in [½, 1], else std::invalid_argument.
    RomImplicitBeamSystem(ReducedOrderModel rom, ThicknessProfile thickness, BaseExcitation excitation,
                          double theta = 0.5);

    // The ROM of a scene on a given modal basis, stepped implicitly.
    static RomImplicitBeamSystem from_scene(const Scene &scene, ModalBasis basis);

    double max_stable_time_step() const override { return std::numeric_limits<double>::infinity(); }
    double theta() const override { return theta_; }
    // S = I + θΔt C + θ²Δt² K_t: not the explicit model's identity.
    bool iteration_matrix_is_identity() const override { return false; }

    // Newton iterations over all steps so far (for the benchmark note).
    unsigned long newton_iterations() const { return newton_iterations_; }

  protected:
    void compute_free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                               Eigen::VectorXd &u_free) override;
    void apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                        Eigen::Ref<Eigen::MatrixXd> X) const override;
    void compute_step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const override;

  private:
    double theta_ = 0.5;
    Eigen::VectorXd c_;       // 2 D ω_n
    Eigen::VectorXd omega2_;  // ω_n²
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_; // cubic tensors: S itself

    // The membrane form: S = D^½ V (E + β z zᵀ) Vᵀ D^½, E = I + αΛ, for the
    // last iteration (see above). `structured_dt_` is the Δt of D and V.
    bool structured_ = false;
    double structured_dt_ = 0, beta_ = 0, sm_denominator_ = 1;
    Eigen::VectorXd d_inv_sqrt_, lambda_, e_inv_, z_, e_inv_z_, Kq_;
    mutable Eigen::VectorXd work_;
    Eigen::MatrixXd W_; // D^-½ V
    void prepare_structure(double dt);
    // x = S⁻¹ r for the current α, β, z (x and r may not alias).
    void structured_solve(const Eigen::Ref<const Eigen::VectorXd> &r, Eigen::Ref<Eigen::VectorXd> x) const;
    bool factorised_ = false;
    double last_dt_ = 0, last_acceleration_ = 0;
    Eigen::VectorXd last_u_B_;
    unsigned long newton_iterations_ = 0;
    struct NewtonStep; // a step as numerics/newton.h's problem
  };
} // namespace beamslider
