// The reduced-order model (seed Eqs. 1–3, doc/physics.md §5) as a BeamSystem, so
// that the contact code of contact/ runs on it unchanged.
//
// Mass-normalised modes give M = I. One explicit Moreau midpoint step
// (doc/physics.md §7–8) of the smooth part:
//
//   h(t_M, q_M, u_B) = −(c ∘ u_B + ω² ∘ q_M + f_nl(q_M)) + γ ẅ0(t_M),  c_n = 2 D ω_n
//   u_free = u_B + Δt h,     S = I
//
// [q] = m kg^1/2, [u] = m kg^1/2/s, [h] = m kg^1/2/s². The scheme is explicit
// in the stiffness: stable only for Δt ≤ 2/ω_max (ω_max the highest kept
// mode; the cubic term lowers the limit a little at large amplitude).
//
// Energy: T + V = ½ uᵀu + ½ Σ ω_n² q_n² + V_nl(q), with V_nl = ¼ qᵀ f_nl(q)
// (exact for any cubic force that derives from a potential, Euler's theorem on
// homogeneous functions). w(x) = Σ φ_n(x) q_n via ModalBasis::evaluate.
#pragma once

#include "contact/base_excitation.h"
#include "contact/beam_system.h"
#include "contact/explicit_modal_form.h"
#include "scene/scene.h"
#include "reduced/rom_operator.h"

namespace beamslider
{
  class RomBeamSystem : public BeamSystem
  {
  public:
    // thickness h(x) [m] of the beam (for the contact surfaces; a number for a uniform beam).
    RomBeamSystem(ReducedOrderModel rom, ThicknessProfile thickness, BaseExcitation excitation);

    // The ROM of a scene on a given modal basis: damping ratio, geometric
    // nonlinearity switch, thickness and excitation from the scene.
    static RomBeamSystem from_scene(const Scene &scene, ModalBasis basis);

    unsigned int n_dofs() const override { return rom_.n_modes(); }
    double length() const override { return rom_.basis().length; }
    double thickness() const override { return thickness_.largest(); }
    double thickness_at(const double x) const override { return thickness_.at(x); }

    // Throws std::out_of_range for x outside [0, L]: modes are not defined there.
    void evaluate(double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const override;
    // From the basis's displacement function where it has one (ModalBasis).
    void evaluate_displacement(double x, const Eigen::VectorXd &q, double &w, double &dw) const override;

    // 2/ω_max [s].
    double max_stable_time_step() const override;

    // S = I: unit modal masses, and the explicit scheme adds nothing to them.
    // A model derived from this one with another iteration matrix (the
    // implicit ROM) must say false here too.
    bool iteration_matrix_is_identity() const override { return true; }

    // The data of the explicit step (contact/explicit_modal_form.h), for a
    // basis on a Hermite mode table (every basis from an FE beam or a solid)
    // and the membrane form of the cubic force or none; null otherwise (an
    // analytic basis, STEP or ICE cubic terms), and the stepper then steps
    // this model through the BeamSystem interface. Valid while this model
    // lives. Null as well for any class derived from this one (the implicit
    // ROM, a test's model with a failing solver): a derived model may step
    // otherwise, and the form would bypass its overrides.
    const ExplicitModalForm *explicit_modal_form() const override;

    double energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const override;

    // w, w' at 129 points, w'' by differences and the uniform axial force of
    // the reduced model, N = k_ax · ½∫w'² dx (axial inertia neglected,
    // doc/physics.md §5; 0 without geometric nonlinearity).
    BeamFieldSamples sample_fields(const Eigen::VectorXd &q) const override;

    const ReducedOrderModel &model() const { return rom_; }
    const BaseExcitation &excitation() const { return excitation_; }

  protected:
    // Throws std::invalid_argument for dt above max_stable_time_step().
    void compute_free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                               Eigen::VectorXd &u_free) override;
    // The explicit scheme's iteration matrix is the identity (unit modal masses).
    void apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                        Eigen::Ref<Eigen::MatrixXd> X) const override
    {
      X = B;
    }
    void compute_step_work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const override;

  private:
    ReducedOrderModel rom_;
    ThicknessProfile thickness_; // h(x), piecewise constant [m]
    BaseExcitation excitation_;
    double omega_max_ = 0; // ω of the highest kept mode [rad/s], for the stability limit each step checks

    // Kept from the last free_velocity call, for step_work.
    double last_dt_ = 0;
    Eigen::VectorXd last_u_B_, last_damping_force_, last_excitation_force_;
    Eigen::VectorXd h_, scratch_; // smooth force and K'q of free_velocity
    mutable Eigen::VectorXd u_mean_; // (u_B + u_E)/2 of step_work
    mutable Eigen::VectorXd energy_force_, energy_scratch_; // f(q) and K'q of energy()
    Eigen::VectorXd omega_squared_;       // ω_n², for the explicit modal form
    mutable ExplicitModalForm form_;      // filled by explicit_modal_form()
  };
} // namespace beamslider
