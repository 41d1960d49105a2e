// The FE beam as a BeamSystem (contact/beam_system.h): the implicit
// Moreau–Jean θ-scheme, θ = 1/2, on the von Kármán beam of fem/fe_beam.h
// (doc/physics.md §2–3, §7–8; Jean 1999; Acary & Brogliato 2008, ch. 10).
//
// Smooth equations of motion, in the FE DoFs q = (u, w, θ) relative to the base:
//   M q̈ + C q̇ + f(q) = r ẅ0(t) (+ contact forces),
// M the consistent mass, f the von Kármán internal force (with the support
// springs), r = −∫ρA N_w dx the base load, C the modal damping of
// fem/fe_modal_damping.h: C = Σ_{n≤N} 2 D ω_n (M φ_n)(M φ_n)ᵀ, ratio D on the N
// kept bending modes, and nothing on the others (higher bending modes and
// all axial modes stay undamped: φ_mᵀ C φ_m = 0 for m > N).
//
// One step from (t_B, q_B, u_B), Δt, with the midpoint structure of the
// shared stepper (q_M = q_B + Δt/2 u_B, q_E = q_M + Δt/2 u_E):
// the implicit midpoint rule on the smooth forces,
//   R(u) = M (u − u_B) + Δt [ f(q̄(u)) + C (u_B + u)/2 − r ẅ0(t_M) ] = 0,
//   q̄(u) = (q_B + q_E)/2 = q_M + Δt/4 (u − u_B),
// solved for u_free by Newton's method with the iteration matrix
//   S = ∂R/∂u = M + Δt/2 C + Δt²/4 K_t(q̄)          (θ = 1/2: θΔt C + θ²Δt² K_t).
// For a linear system this is the trapezoidal rule (Newmark γ = 1/2,
// β = 1/4): unconditionally stable, no numerical damping, energy-conserving,
// period elongation (ωΔt)²/12 per mode. With contact impulses P the end
// velocity is u_E = u_free + S⁻¹ W P: the Newton correction of R linearised
// about u_free (the error is second order in the impulse's velocity change
// times ∂K_t/∂q, and (S_true − S) S⁻¹ W P if S is a reused factorisation).
//
// Linear algebra. S = S₀ + U diag(Δt/2 · 2Dω_n) Uᵀ with the sparse, banded
// S₀ = M + Δt²/4 K_t and the rank-N damping U = [M φ_n]. S₀ is symmetric
// (K_t is the Hessian of the strain energy); it is factorised by a sparse
// LDLᵀ (Eigen::SimplicialLDLT, ordering and symbolic analysis once, numeric
// factorisation on refactorisation). We started with deal.II's UMFPACK: on
// the 131-DoF default mesh a factorisation cost about 100 µs and a solve
// about 10 µs, mostly call overhead, which made the step 2–3 times slower.
// The damping is folded in by Sherman–Morrison–Woodbury:
//   S⁻¹ b = y − Z (I + Dg UᵀZ)⁻¹ Dg Uᵀ y,   y = S₀⁻¹ b,  Z = S₀⁻¹ U,
// which costs N extra solves per factorisation and an N × N dense solve per
// right-hand side. Newton runs with the last factorisation (modified
// Newton) and refactorises K_t(q̄) when a correction shrinks by less than
// `max_contraction` (0.1), or every `refactor_interval` steps (default: never
// by count); for a linear beam S is factorised once. It stops when
// ‖δu‖ ≤ rtol (‖u‖ + ‖q̄‖/Δt), or when the contraction estimate
// c/(1 − c) ‖δu‖ is below that (Hairer & Wanner II, §IV.8); rtol = 1e-8
// keeps q_E within 1e-8 of the state's size. f(q̄) in the loop comes from
// shape data cached at the quadrature points (cached_internal_force, equal
// to FEBeam's assembly to round-off); K_t from FEBeam's assembly.
// Measured on the default mesh (32 elements, 131 DoFs), signature move
// (124 Hz, 14 m/s², x_C/L = 0.3, Δt = 2e-5 s, first 0.5 s): 4.1 Newton
// iterations and 1.3 iteration-matrix solves per step, one refactorisation
// per ~400 steps, 37–39 µs per step (1.9 s per simulated second).
// Refactorising every step (refactor_interval = 1) costs 2.4× (93 µs/step,
// still 3.1 iterations: the undamped stiff axial modes, ωΔt ≫ 1, flip sign
// every step and make u_B a poor start). The whole 60 s signature-move run
// (jump to ŵ/h ≈ 2.5 near t = 40 s, where Newton refactorises every ~8
// steps): 157 s wall on one core, 52 µs per step.
// Constrained DoFs (the supports) stay zero: their rows of M carry a diagonal
// filler and every right-hand side is zero there.
//
// Energy: ½ uᵀMu + V(q), V(q) = ∫₀¹ f(s q)·q ds evaluated with two-point
// Gauss in s (exact: the integrand is a cubic in s for von Kármán).
// step_work: damping −Δt ū·C ū and base load Δt ẅ0(t_M) r·ū, ū = (u_B + u_E)/2,
// which is exactly what the midpoint rule's impulses do.
//
// Units: SI; q holds u [m], w [m], θ [rad]; u the same per second.
#pragma once

#include "contact/base_excitation.h"
#include "contact/beam_system.h"
#include "fem/fe_beam.h"
#include "fem/fe_modal_damping.h"
#include "fem/fe_modes.h"
#include "meshes/scene.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <memory>
#include <stdexcept>

namespace beamslider
{
  // Newton on the smooth forces did not converge within a step.
  class TransientNewtonFailure : public std::runtime_error
  {
  public:
    TransientNewtonFailure(double t_M, unsigned int iteration, double correction, double velocity_norm);
    double t_M;             // midpoint time of the failed step [s]
    unsigned int iteration; // iterations done
    double correction;      // last ‖δu‖ [m/s]
  };

  struct FETransientSettings
  {
    // Newton: ‖δu‖ ≤ rtol (‖u‖ + ‖q̄‖/Δt) + atol, i.e. q_E within rtol of the
    // state's size (far below the scheme's (ωΔt)²/12).
    double relative_tolerance   = 1e-8;
    double absolute_tolerance   = 1e-13; // [m/s]
    unsigned int max_iterations = 30;    // per step, including refactorisations
    // A modified-Newton iteration whose correction shrinks by less than this
    // factor triggers a refactorisation with the current tangent.
    double max_contraction = 0.1;
    // Newton's start: u_B plus the last step's smooth velocity change (true),
    // or u_B (false). Extrapolating gains nothing measurable (4.6 against 4.5
    // iterations per step on the signature move): the undamped stiff axial
    // modes, ωΔt ≫ 1, flip sign every step under the midpoint rule and
    // dominate the first correction either way.
    bool extrapolate = false;
    // Refactorise at least every this many steps (0: only when Newton needs it).
    unsigned int refactor_interval = 0;
  };

  // Counters for the benchmark note.
  struct FETransientStatistics
  {
    unsigned long steps = 0, newton_iterations = 0, factorisations = 0, iteration_matrix_solves = 0;
  };

  class FETransientBeam : public BeamSystem
  {
  public:
    // The beam of `scene` (mesh: n_elements, 0 = the scene's), damping ratio D
    // on the scene's N lowest bending modes, the given base excitation.
    FETransientBeam(const Scene &scene, const BaseExcitation &excitation, unsigned int n_elements = 0,
                    FETransientSettings settings = {});

    unsigned int n_dofs() const override { return beam_->n_dofs(); }
    double length() const override { return beam_->length(); }
    double thickness() const override { return beam_->beam_data().thickness; }

    // Throws std::out_of_range outside [0, L]. Gradients are dense, zero on
    // constrained DoFs.
    void evaluate(double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const override;

    // Throws TransientNewtonFailure (t_M, iteration, residual).
    void free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                       Eigen::VectorXd &u_free) override;
    void solve_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                Eigen::Ref<Eigen::MatrixXd> X) const override;
    double max_stable_time_step() const override { return std::numeric_limits<double>::infinity(); }

    double energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const override;
    void step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const override;
    void save_state(CheckpointWriter &out) const override;
    void load_state(CheckpointReader &in) override;

    // Strain energy V(q) [J] and internal force f(q) [N, N m] (FEBeam's assembly).
    double strain_energy(const Eigen::VectorXd &q) const;
    Eigen::VectorXd internal_force(const Eigen::VectorXd &q) const;
    // The same f(q) from shape values cached at the quadrature points (what
    // the Newton loop calls: FEBeam's assembly rebuilds its FEValues on every
    // call, which was a third of the step). Zero on constrained DoFs.
    void cached_internal_force(const dealii::Vector<double> &q, dealii::Vector<double> &f) const;

    const FEBeam &beam() const { return *beam_; }
    const FEModes &modes() const { return modes_; }
    const ModalDamping &damping() const { return *damping_; }
    const dealii::SparseMatrix<double> &mass_matrix() const { return M_; }
    const dealii::Vector<double> &base_load() const { return r_; }
    const BaseExcitation &excitation() const { return excitation_; }
    const FETransientStatistics &statistics() const { return stats_; }
    FETransientSettings &settings() { return settings_; }

    // Conversions between the FE vector and the coordinates of the interface.
    static void to_dealii(const Eigen::VectorXd &a, dealii::Vector<double> &b);
    static void to_eigen(const dealii::Vector<double> &a, Eigen::VectorXd &b);

  private:
    void factorise(const dealii::Vector<double> &q_bar, double dt);
    // x = S⁻¹ b (b zero on constrained DoFs).
    void solve(const dealii::Vector<double> &b, dealii::Vector<double> &x) const;

    std::unique_ptr<FEBeam> beam_;
    BaseExcitation excitation_;
    FETransientSettings settings_;
    double damping_ratio_;
    FEModes modes_;
    dealii::SparseMatrix<double> M_, K_, S0_;
    dealii::Vector<double> r_;
    std::unique_ptr<ModalDamping> damping_;
    std::vector<bool> constrained_;

    // Factorisation of S₀ (Eigen's sparse LDLᵀ on S₀'s pattern) and the Woodbury terms.
    Eigen::SparseMatrix<double> S0_eigen_;
    std::vector<std::ptrdiff_t> S0_entry_; // deal.II entry k ↦ index in S0_eigen_'s values
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
    bool factorised_        = false;
    double factorised_dt_   = 0;
    unsigned long factorised_step_ = 0;
    dealii::Vector<double> factorised_q_bar_; // where K_t of the factorisation was taken
    Eigen::MatrixXd Z_;            // S₀⁻¹ U
    Eigen::MatrixXd U_;            // [M φ_n]
    Eigen::VectorXd Dg_;           // Δt/2 · 2 D ω_n
    Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_; // I + Dg UᵀZ
    mutable Eigen::VectorXd woodbury_rhs_, woodbury_v_; // scratch of size rank

    // Last step, for the predictor and step_work.
    double last_dt_ = 0, last_acceleration_ = 0;
    Eigen::VectorXd last_u_B_, last_u_free_;
    bool have_last_ = false;

    // Shape data at every quadrature point, from FEBeam::point_shape, for
    // cached_internal_force: ε = u' + ½w'², κ = w'' and their DoFs.
    struct QuadraturePointData
    {
      std::array<unsigned int, 4> w_dofs;
      std::array<double, 4> dN, ddN; // Hermite N_a', N_a''
      std::vector<unsigned int> u_dofs;
      std::vector<double> du;        // axial shape derivatives
      double JxW;
    };
    std::vector<QuadraturePointData> quadrature_;
    std::vector<std::pair<unsigned int, double>> springs_; // (DoF, k_r or 2 k_t)

    mutable FETransientStatistics stats_; // counts solves in const solve_iteration_matrix too
    // Scratch.
    mutable dealii::Vector<double> tmp_a_, tmp_b_, tmp_c_;
    dealii::Vector<double> q_bar_, u_, res_, du_, f_, uB_, qM_;
  };
} // namespace beamslider
