// The FE beam as a BeamSystem (contact/beam_system.h): the implicit
// Moreau–Jean θ-scheme, θ = 1/2 unless set higher (FETransientSettings::theta),
// on the von Kármán beam of fem/fe_beam.h
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
// shared stepper (q_M = q_B + Δt/2 u_B, q_E = q_M + Δt/2 u_E), written for
// θ = 1/2 (the general θ at FETransientSettings::theta):
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
// LDLᵀ (Eigen::SimplicialLDLT on the upper triangle in the DoFs' own, banded
// order; symbolic analysis once, numeric factorisation on refactorisation).
// We started with deal.II's UMFPACK: on the 131-DoF default mesh a
// factorisation cost about 100 µs and a solve about 10 µs, mostly call
// overhead. A solve is ~1000 multiply-adds, but each unknown of a
// triangular solve waits for the previous ones, so it is bound by that
// chain's latency, not by the arithmetic: on a banded SPD matrix of this
// size and half-bandwidth (131, 7; one core, 2026-11-27) Eigen's
// SimplicialLDLT::solve takes 2.6 µs, the same factor with L walked row by
// row and 1/D kept (what solve_factored does) 2.3 µs, LAPACK's band
// dpbtrs 2.3 µs (3.9 µs in an earlier measurement), a dense LLᵀ 5.7 µs.
// What the solves use now is the factor once more as 8 × 8 blocks (the
// band makes L block-bidiagonal, fem/block_bidiagonal_factor.h): products
// of compile-time size that vectorise, and a chain from block to block
// instead of from unknown to unknown, 0.6 µs per solve (2026-11-29); the
// residual's M (u − u_B) the same way (fem/block_tridiagonal_matrix.h,
// 0.86 → 0.44 µs). Both agree with the sparse versions to round-off (8e-15
// relative over the FeContact windows), which stay for a band wider than 8.
// The damping is folded in by Sherman–Morrison–Woodbury:
//   S⁻¹ b = y − Z (I + Dg UᵀZ)⁻¹ Dg Uᵀ y,   y = S₀⁻¹ b,  Z = S₀⁻¹ U,
// which costs N extra solves per factorisation and an N × N dense solve per
// right-hand side; only the contact impulses use it. Newton's corrections
// are solved with S₀ alone: Δt/2 C is of relative size Δt D ω_n ≤ 1e-4, so
// leaving it out only slows the contraction by that factor, and the residual
// keeps the damping exactly (the converged u_free is unchanged). Every
// scratch is sized once: a step, a refactorisation included, allocates
// nothing (FeContact's allocations/step).
// Newton runs with the last factorisation (modified
// Newton) and refactorises K_t(q̄) when a correction shrinks by less than
// `max_contraction` (0.01), or every `refactor_interval` steps (default:
// never by count); for a linear beam S is factorised once. It stops when
// ‖δu‖ ≤ rtol (‖u‖ + ‖q̄‖/Δt), or when the contraction estimate
// c/(1 − c) ‖δu‖ is below that (Hairer & Wanner II, §IV.8); rtol = 1e-8
// keeps q_E within 1e-8 of the state's size. Two iterations are the floor
// of this test (a contraction needs two corrections; the first correction
// is ≳ 10³ tolerances even right after a refactorisation).
// The hot path touches no deal.II object: f(q̄) and K_t(q̄) come from shape
// data cached per cell at the quadrature points (internal_force_cached,
// assemble_iteration_matrix: equal to FEBeam's FEValues assembly to
// round-off, tested), written straight into S₀'s value array through a
// per-cell map of local entries; M, r, U are Eigen objects; the contact
// kinematics evaluate the Hermite shape functions of the cell directly.
// What a step costs and where the time goes is measured by the FeContact
// benchmark (verification/benchmarks) and recorded, with its date, in the
// README's benchmark table.
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
#include "fem/block_bidiagonal_factor.h"
#include "fem/block_tridiagonal_matrix.h"
#include "fem/fe_beam.h"
#include "fem/fe_modal_damping.h"
#include "fem/fe_modes.h"
#include "scene/scene.h"

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include <array>
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
    // factor triggers a refactorisation with the current tangent. 0.01
    // rather than 0.1: with the tangent assembled from cached data a
    // refactorisation costs ~20 µs (about two steps), and keeping the
    // contraction below 0.01 brings Newton from 3.4 to 2.06 iterations per
    // step for 0.02 refactorisations per step (signature move, Δt = 1e-5 s,
    // 32 elements: 16.6 -> 12.6 µs per step).
    double max_contraction = 0.01;
    // Newton's start: u_B plus the last step's smooth velocity change (true),
    // or u_B (false). Extrapolating gains nothing measurable (4.6 against 4.5
    // iterations per step on the signature move): the undamped stiff
    // modes, ωΔt ≫ 1, flip sign every step under the midpoint rule and
    // dominate the first correction either way. Measured again 2026-11-27
    // (FeContact/32/0): the first correction is 2e7–6e7 tolerances, 85–95 %
    // of it (M-norm) in the undamped bending modes with ωΔt ≥ 2, the axial
    // part ~1e3 tolerances; extrapolating the bending velocities linearly
    // and repeating the axial ones of two steps back (the period-two flip)
    // leaves it as large, and Newton at its floor of two iterations per
    // step (2.00 against 2.02).
    bool extrapolate = false;
    // θ ∈ [1/2, 1] of the Moreau–Jean scheme: q_E = q_B + Δt((1 − θ)u_B + θu_E),
    //   R(u) = M (u − u_B) + Δt [ f(q_θ) + C u_θ − r ẅ0(t_B + θΔt) ],
    //   q_θ = (1 − θ) q_B + θ q_E,  u_θ = (1 − θ) u_B + θ u,
    //   S = M + θΔt C + θ²Δt² K_t(q_θ).
    // 1/2 is the implicit midpoint rule above (second order, no numerical
    // damping). Above 1/2 the scheme is first order and damps each mode per
    // step by a factor that goes from 1 − (θ − ½)(ωΔt)² for ωΔt ≪ 1 (a
    // numerical damping ratio (θ − ½)ωΔt) to (1 − θ)/θ for ωΔt → ∞ (the
    // spectral radius of the amplification matrix of ẍ = −ω²x): it removes the undamped high bending modes that ring
    // after each impact and that the step does not resolve. Whether an end
    // state computed so agrees with the reference's is measured, not
    // assumed: doc/findings.md. The stepper moves the slider with the
    // same θ (BeamSystem::theta).
    double theta = 0.5;
    // Refactorise at least every this many steps (0: only when Newton needs it).
    unsigned int refactor_interval = 0;
    // false: the axial DoFs carry no mass, so the membrane is in static
    // equilibrium at every instant (the reduced model's assumption,
    // doc/physics.md §5): the error ladder's rung "FE without axial
    // inertia". The axial rows of R become (Δt/2) f_axial(q_E) = 0 with
    // q_E = q_M + Δt/2 u, equilibrium at the step's end, whose Jacobian
    // Δt²/4 K_axial is S₀'s axial block (M's is zero), so the same
    // factorisation serves. Imposing it at the midpoint instead,
    // f_axial(q̄) = 0 (the midpoint rule applied as it stands to this
    // index-1 system), leaves the end values' error undamped, flipping sign
    // every step: on the signature move the axial velocities grew to 6e5
    // m/s and Newton failed after 15 s. The massless DoFs' velocity is the
    // step's mean (finish_step), so nothing flips from step to step.
    bool axial_inertia = true;
    // The lowest bending modes that carry the damping ratio D (0: the
    // scene's N, `Discretisation/Number of modes`).
    unsigned int damped_modes = 0;
    // What the contact impulses P move (`Time stepping/FE impulses`).
    // false: the iteration matrix, u_E = u_free + S⁻¹ W P (Moreau–Jean). An
    // impact then sees the beam mass 1/(wᵀS⁻¹w) under the corner, which
    // falls like √Δt while Δt is long against the mesh's highest period
    // (1.2, 0.85, 0.61 g at 2e-5, 1e-5, 5e-6 s on 32 elements) and reaches
    // the semi-discrete value 1/(wᵀM⁻¹w) = 0.27 g only below ~1e-7 s: each
    // impulse, and the rattling it drives, drifts with Δt.
    // true: the mass matrix, u_E = u_free + M⁻¹ W P, the velocity jump of
    // the semi-discrete system M du = f dt + W dP at any Δt (the impulse
    // first, then the smooth step's velocity; the split of the
    // nonsmooth generalised-α scheme, Chen, Acary, Virlez & Brüls 2013).
    // M⁻¹ on the bending DoFs is kept dense (the consistent mass has no
    // axial–bending coupling, so an impulse moves no axial DoF).
    bool impulses_through_mass = false;
    // true: no beam mass at the contact points (mass redistribution,
    // Khenous, Laborde & Renard 2008). With W = [N_w(x_left), N_w(x_right)]
    // the Hermite values at the two corner pairs (BeamSystem::
    // set_contact_abscissae), the step uses
    //   M̃ = M − W A Wᵀ,   A = (Wᵀ M⁻¹ W)⁻¹,
    // the kinetic energy left once the least needed to move the contact
    // points at their velocity is taken out: M̃ M⁻¹W = 0, so the points
    // carry no inertia, an impact moves the slider alone, and the beam
    // answers through its stiffness, not its highest modes. The removed
    // mass (the 2 × 2 matrix A, ≈ 0.27 g a point on 32 elements) halves
    // with each mesh refinement, and it feels no base load either
    // (r̃ = −M̃ ι). M̃ follows the slider; S̃ = S − W A Wᵀ is solved by
    // Woodbury on S's factorisation. Not with impulses_through_mass.
    bool redistributed_mass = false;
  };

  // Counters for the benchmark note.
  struct FETransientStatistics
  {
    unsigned long steps = 0, newton_iterations = 0, factorisations = 0;
    // Dense solves with S (columns of S⁻¹B through apply_inverse_iteration_matrix).
    unsigned long iteration_matrix_solves = 0;
    // Blocks of S⁻¹ on the contact directions' coordinates (one per step with
    // contact: the Moreau step's local form).
    unsigned long contact_blocks = 0;
    // Columns of S⁻¹ solved for the contact directions (the rest come from
    // those kept since the last factorisation).
    unsigned long inverse_column_solves = 0;
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
    double thickness_at(const double x) const override { return beam_->thickness_at(x); }

    // Throws std::out_of_range outside [0, L]. Gradients are dense, zero on
    // constrained DoFs.
    void evaluate(double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const override;
    // w and w' at x depend on the four Hermite DoFs of the cell under x
    // (fewer next to a support): the contact code works on those alone.
    bool has_local_kinematics() const override { return true; }
    void evaluate_local(double x, const Eigen::VectorXd &q, LocalPointKinematics &out) const override;
    void evaluate_displacement(double x, const Eigen::VectorXd &q, double &w, double &dw) const override;

    double max_stable_time_step() const override { return std::numeric_limits<double>::infinity(); }
    double theta() const override { return settings_.theta; }

    // Kinetic energy with M̃ when the mass is redistributed.
    double energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const override;
    // The corners' places for the redistributed mass (ignored without it).
    void set_contact_abscissae(double x_left, double x_right) override;
    // W A Wᵀ of the redistributed mass (zero without it), for tests.
    Eigen::MatrixXd removed_mass() const;
    // The exact FE fields, 4 samples per element: u, w, w', w'' from the shape
    // functions, N = EA (u' + ½w'²) (u' alone without geometric nonlinearity).
    BeamFieldSamples sample_fields(const Eigen::VectorXd &q) const override;
    void save_state(CheckpointWriter &out) const override;
    void load_state(CheckpointReader &in) override;

    // Strain energy V(q) [J] (from the cached quadrature data) and internal
    // force f(q) [N, N m] (FEBeam's assembly, for tests of the cached one).
    double strain_energy(const Eigen::VectorXd &q) const;
    Eigen::VectorXd internal_force(const Eigen::VectorXd &q) const;
    // The same f(q) from shape values cached at the quadrature points (what
    // the Newton loop computes: FEBeam's assembly rebuilds its FEValues on
    // every call, which was a third of the step). Zero on constrained DoFs.
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

    // S₀ = M + Δt²/4 K_t(q̄) as the Newton loop builds it from the cached
    // quadrature data, dense (for tests: it must equal M + Δt²/4 times
    // FEBeam's tangent on the free DoFs).
    Eigen::MatrixXd cached_iteration_matrix(const Eigen::VectorXd &q_bar, double dt);

  protected:
    // Throws TransientNewtonFailure (t_M, iteration, residual).
    void compute_free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                               Eigen::VectorXd &u_free) override;
    void apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                        Eigen::Ref<Eigen::MatrixXd> X) const override;
    // From the kept columns of S⁻¹ (inverse_column).
    void inverse_iteration_matrix_block(const unsigned int *index, unsigned int k,
                                        Eigen::Ref<Eigen::MatrixXd> out) const override;
    void add_inverse_iteration_matrix_times(const unsigned int *index, unsigned int k, const double *y,
                                            Eigen::VectorXd &u) const override;
    // Without axial inertia: the massless axial DoFs get the step's mean velocity.
    void finish_step(const Eigen::VectorXd &q_B, const Eigen::VectorXd &q_E, double dt,
                     Eigen::VectorXd &u_E) const override;
    void compute_step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const override;

  private:
    // Factorises S₀ = M + Δt²/4 K_t(q̄) and the Woodbury terms of the damping.
    void factorise(const Eigen::VectorXd &q_bar, double dt);
    // S₀'s values (upper triangle) from the cached quadrature data.
    void assemble_iteration_matrix(const Eigen::VectorXd &q_bar, double dt);
    // f(q̄) from the cached quadrature data, zero on constrained DoFs.
    void internal_force_cached(const Eigen::VectorXd &q, Eigen::VectorXd &f) const;
    // Its loop over the cells, n_u axial DoFs per cell.
    template <unsigned int n_u>
    void internal_force_cells(const Eigen::VectorXd &q, Eigen::VectorXd &f) const;
    // x = S⁻¹ b (b zero on constrained DoFs).
    void solve(const Eigen::VectorXd &b, Eigen::VectorXd &x) const;

    std::unique_ptr<FEBeam> beam_;
    BaseExcitation excitation_;
    FETransientSettings settings_;
    double damping_ratio_;
    FEModes modes_;
    dealii::SparseMatrix<double> M_;
    dealii::Vector<double> r_;
    std::unique_ptr<ModalDamping> damping_;
    std::vector<bool> constrained_;
    std::vector<unsigned int> constrained_list_;

    // The hot path works on Eigen objects only: M (row-major for the
    // product), the base load, the damping's U = [M φ_n] and 2 D ω_n.
    Eigen::SparseMatrix<double, Eigen::RowMajor> M_eigen_;
    BlockTridiagonalMatrix M_blocks_; // M as 8 × 8 blocks, for the residual's M (u − u_B)
    Eigen::VectorXd r_eigen_;
    Eigen::MatrixXd U_;            // [M φ_n]
    Eigen::VectorXd modal_c_;      // 2 D ω_n [1/s]

    // S₀ (Eigen's sparse LDLᵀ on the pattern of the FE matrices, upper
    // triangle; symbolic analysis once) and the Woodbury terms.
    Eigen::SparseMatrix<double> S0_;
    Eigen::VectorXd M_in_S0_;          // M's values in S0_'s layout
    std::vector<std::ptrdiff_t> spring_entry_; // S0_ value index of each spring's diagonal
    // Eigen's sparse LDLᵀ of S₀'s upper triangle in the DoFs' own order:
    // deal.II numbers a 1D mesh's DoFs along the beam, so S₀ is banded
    // (half-bandwidth 7 on the default mesh) and its factor has 444 entries
    // below the diagonal against AMD's 382; a fill-reducing ordering costs
    // two permutations per solve, and Eigen's in-place inverse permutation
    // allocates on every solve. factorize_upper goes straight to the numeric
    // factorisation (SimplicialLDLT::factorize builds an empty n × n matrix
    // first, an allocation per refactorisation, even when it copies nothing).
    class BandOrderLDLT
      : public Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>
    {
    public:
      void factorize_upper(const Eigen::SparseMatrix<double> &upper) { this->template factorize_preordered<true>(upper); }
      // D by reference (vectorD() returns a copy: an allocation).
      const Eigen::VectorXd &diagonal() const { return this->m_diag; }
    };
    BandOrderLDLT ldlt_;
    // The factor's L once more, row by row, and 1/D: Eigen solves a
    // column-major L by scattering into x, each entry of a band updated by
    // several columns in turn (a chain through memory), and divides by D;
    // row by row the forward solve is a dot product per row: 2.6 → 2.3 µs
    // per S₀⁻¹ b (the largest part of a step). L's pattern is fixed
    // by the symbolic analysis, so the copy is set up once and each
    // factorisation only moves the values (L_rows_entry_[k]: where L's k-th
    // value goes), allocating nothing.
    Eigen::SparseMatrix<double, Eigen::RowMajor> L_rows_;
    std::vector<Eigen::Index> L_rows_entry_;
    std::vector<int> L_pattern_; // L's row indices when L_rows_ was set up
    Eigen::VectorXd inverse_D_;
    // The same factors as fixed-size blocks (fem/block_bidiagonal_factor.h),
    // what solve_factored uses when L's band is at most 8 wide (the beam
    // meshes here: 7); L_rows_ solves otherwise.
    BlockBidiagonalFactor block_factor_;
    // x = S₀⁻¹ b with the factors above (x may not alias b).
    void solve_factored(const Eigen::VectorXd &b, Eigen::VectorXd &x) const;
    bool factorised_        = false;
    double factorised_dt_   = 0;
    double factorised_theta_ = 0.5;
    unsigned long factorised_step_ = 0;
    Eigen::VectorXd factorised_q_bar_; // where K_t of the factorisation was taken
    Eigen::MatrixXd Z_;            // S₀⁻¹ U
    Eigen::VectorXd Dg_;           // θΔt · 2 D ω_n
    Eigen::MatrixXd capacitance_matrix_;              // I + Dg UᵀZ
    Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_; // its LU
    mutable Eigen::VectorXd woodbury_rhs_, woodbury_v_; // scratch of size rank
    // Scratch for solve_iteration_matrix, sized once for the largest block:
    // the contact directions, two per slider corner.
    static constexpr Eigen::Index max_block_columns = 8;
    mutable Eigen::MatrixXd block_rhs_, block_v_, block_w_;
    mutable Eigen::VectorXd block_column_, block_solution_;
    // Columns of S⁻¹ (Woodbury included) for single DoFs, kept until the
    // next factorisation. A contact direction is ∂g/∂q at one point of the
    // beam: it touches the 4 Hermite DoFs of one cell, so S⁻¹ W needs S⁻¹
    // e_i for those few DoFs only, and the slider stays on the same cells
    // for thousands of steps between refactorisations. Each column costs
    // one solve the first time, then an axpy of length n (the contact part
    // of a step went from one sparse solve per direction to a few axpys).
    // Round-robin replacement when full; the values do not depend on which
    // columns are kept, so a run restored from a checkpoint gives the same
    // bits.
    static constexpr unsigned int n_inverse_columns = 16;
    mutable Eigen::MatrixXd inverse_columns_; // n × n_inverse_columns
    mutable std::array<int, n_inverse_columns> inverse_column_dof_{};
    // M⁻¹ for impulses_through_mass: dense, zero outside the free bending DoFs.
    Eigen::MatrixXd inverse_mass_;
    void set_up_inverse_mass();
    mutable unsigned int next_inverse_column_ = 0;
    // S⁻¹ e_i from the cache, solved and stored on first use.
    const double *inverse_column(unsigned int dof) const;
    // Forget the kept columns (a new factorisation).
    void clear_inverse_columns();

    // Last step, for the predictor and step_work.
    double last_dt_ = 0, last_acceleration_ = 0;
    Eigen::VectorXd last_u_B_, last_u_free_;
    bool have_last_ = false;

    // Per cell: its Hermite and axial DoFs, where it lies, its quadrature
    // points in quadrature_, and where each local entry (i, j) of the
    // tangent goes in S0_'s values (−1 for a constrained row or
    // column). Local order: (w0, θ0, w1, θ1), then the axial DoFs.
    static constexpr unsigned int max_axial_dofs = 7; // axial degree ≤ 6
    static constexpr unsigned int max_cell_dofs  = 4 + max_axial_dofs;
    struct CellData
    {
      std::array<unsigned int, 4> w_dofs{};
      std::array<unsigned int, max_axial_dofs> u_dofs{};
      unsigned int n_u = 0, first_qp = 0, n_qp = 0;
      double x0 = 0, h = 0;   // left vertex and length [m]
      double EA = 0, EI = 0;  // the section's stiffnesses [N], [N m^2]
      std::vector<std::ptrdiff_t> entry; // (4 + n_u)² indices into S0_'s values
    };
    // Shape data at one quadrature point: ε = u' + ½w'², κ = w''.
    struct QuadraturePointData
    {
      std::array<double, 4> dN, ddN;               // Hermite N_a', N_a''
      std::array<double, max_axial_dofs> du;       // axial shape derivatives
      double JxW;
    };
    // A cell's DoF values of q: (w0, θ0, w1, θ1) and the axial ones.
    static void gather(const CellData &cell, const Eigen::VectorXd &q, std::array<double, 4> &qw,
                       std::array<double, max_axial_dofs> &qu);
    // The same shape data for two neighbouring cells side by side (lane 0:
    // cell 2p, lane 1: cell 2p + 1), so that internal_force_cells evaluates
    // both cells' quadrature points in one SIMD register: each lane does a
    // single cell's operations in their order, so the force is the same to
    // the last bit as cell by cell.
    struct QuadraturePointPair
    {
      std::array<Eigen::Array2d, 4> dN, ddN;
      std::array<Eigen::Array2d, max_axial_dofs> du;
      Eigen::Array2d JxW;
    };
    std::vector<CellData> cells_;        // ordered from x = 0 to L
    // The cell under x ∈ [0, L] (throws std::out_of_range outside) and ξ ∈ [0, 1] there.
    const CellData &cell_at(double x, double &xi) const;
    std::vector<QuadraturePointData> quadrature_;
    std::vector<QuadraturePointPair> paired_quadrature_; // [pair][point], the pairs of cells_ (an odd last one twice)
    std::vector<std::pair<unsigned int, double>> springs_; // (DoF, k_r or 2 k_t)

    // The constructor's stages, in their order: the supports' constrained
    // DoFs; M (without axial inertia: its free axial block zeroed) and r;
    // the modes, the damping's U and 2 D ω_n and the solves' scratch; M in
    // Eigen form and S₀'s pattern; the cells from x = 0 to L; their
    // quadrature data and S₀ entries; the cells in pairs; the springs.
    void find_support_constraints();
    void assemble_mass_and_base_load();
    void set_up_modal_damping(unsigned int n_kept);
    void set_up_iteration_matrix_pattern();
    void collect_cells();
    void cache_cell_quadrature();
    void pair_cell_quadrature();
    void set_up_support_springs();
    // The index of S₀'s entry (i, j) in its values, −1 for a constrained
    // row or column or below the diagonal.
    std::ptrdiff_t iteration_matrix_entry(unsigned int i, unsigned int j);

    mutable FETransientStatistics stats_; // counts solves in const solve_iteration_matrix too
    // Scratch of the Newton loop.
    Eigen::VectorXd q_bar_, u_, res_, du_, f_, tmp_;
    struct NewtonStep; // compute_free_velocity() as numerics/newton.h's problem
    // Without axial inertia: the free axial DoFs, and q_E, f(q_E) scratch.
    std::vector<unsigned int> massless_axial_;
    Eigen::VectorXd q_end_, f_end_;
    mutable Eigen::VectorXd u_mean_, u_theta_; // ū and u_θ of step_work
    mutable Eigen::VectorXd energy_q_, energy_f_, energy_Mu_; // scratch of energy()

    // The redistributed mass (FETransientSettings::redistributed_mass):
    // W (n × 2), A = (Wᵀ M⁻¹ W)⁻¹, the base load r̃ = r + W A Wᵀι, and for
    // the solves with S̃ = S − W A Wᵀ by Woodbury,
    //   S̃⁻¹ b = S⁻¹ b + Y C⁻¹ Wᵀ S⁻¹ b,  Y = S⁻¹ W,  C = A⁻¹ − Wᵀ Y,
    // Y and C's factor made on first use after a new W or factorisation.
    using NByTwo = Eigen::Matrix<double, Eigen::Dynamic, 2>;
    NByTwo mrm_W_;
    Eigen::Matrix2d mrm_A_ = Eigen::Matrix2d::Zero();
    Eigen::VectorXd iota_, r_tilde_; // ι: 1 on the free w values, 0 elsewhere
    mutable NByTwo mrm_Y_;
    mutable Eigen::LLT<Eigen::Matrix2d> mrm_C_;
    mutable bool mrm_current_ = false;
    std::array<double, 2> mrm_x_{{-1., -1.}};
    void set_up_redistribution();
    // Y and C for the current W and factorisation.
    void update_redistribution() const;
    // x ← x + Y C⁻¹ Wᵀ x: S⁻¹ b made S̃⁻¹ b.
    void add_redistribution_term(Eigen::VectorXd &x) const;
    mutable Eigen::Vector2d mrm_scratch_;
  };
} // namespace beamslider
