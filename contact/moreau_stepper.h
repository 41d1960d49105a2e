// Moreau midpoint time stepping of beam + rigid slider with unilateral,
// frictional contact and Newton impact (doc/physics.md §7–8; Moreau 1988;
// Studer 2009; Krack et al. 2017), written once for any BeamSystem.
//
// One step from (t_B, q_B, u_B, s_B, v_B), Δt, written here for θ = 1/2 (the
// beam model's theta(): with θ > 1/2 the Δt/2 before the contact detection
// becomes (1 − θ) Δt and the one after it θ Δt, for beam and slider alike):
//   t_M = t_B + Δt/2,  q_M = q_B + Δt/2 u_B,  s_M = s_B + Δt/2 v_B
//   u_free from the beam (BeamSystem::free_velocity), v_free = v_B + Δt (0, −g, 0)
//   active set: corners with g_N(t_M, q_M, s_M) ≤ 0
//   γ = Wᵀ(u, v) + w_imp (normal and tangential relative velocities)
//   G = W_bᵀ S⁻¹ W_b + W_sᵀ M_s⁻¹ W_s,  c = γ(u_free, v_free) + ε γ(u_B, v_B)
//   P from the prox solver (prox_solver.h), warm-started per corner
//   u_E = u_free + S⁻¹ W_b P,  v_E = v_free + M_s⁻¹ W_s P
//   q_E = q_M + Δt/2 u_E,  s_E = s_M + Δt/2 v_E
// ε = diag(e_N, 0). The active-set test uses g_N ≤ 0 (the design notes wrote < 0) so
// that a corner resting with exactly zero gap, as in the initial state, is
// held from the first step instead of falling freely for one step.
//
// Energy bookkeeping per step (the midpoint step changes the kinetic energy by
// exactly impulse · mean velocity): gravity −m g (z_E − z_B); beam damping and
// base load from BeamSystem::step_work; at each active contact the impulse
// times the mean relative velocity, split into normal (impacts, ≤ 0 for
// e_N ≤ 1) and tangential (friction, ≤ 0); and the work the moving base does
// through the contacts, −P·w_imp (the beam is described relative to the base,
// the slider absolutely). The only discretisation error is the beam's strain
// energy, evaluated at q_M instead of along q_B → q_E.
//
// Supports: a corner outside [0, L] would need the beam outside the beam. The
// stepper checks every corner before it evaluates the beam and throws
// SliderAtSupport (naming t, x_C and the support); the state stays the last
// good one. Non-finite states and solver failures also throw; nothing is
// silently accepted.
#pragma once

#include "contact/base_excitation.h"
#include "contact/beam_system.h"
#include "numerics/state_bytes.h"
#include "contact/explicit_modal_form.h"
#include "contact/local_directions.h"
#include "contact/prox_solver.h"
#include "contact/slider_contact.h"

#include <Eigen/Dense>

#include <array>
#include <limits>
#include <stdexcept>
#include <string>

namespace beamslider
{
  // The full state: time, beam coordinates and velocities, slider coordinates
  // s = (x_C [m], z_C [m], β [rad]) and velocities v.
  struct SystemState
  {
    double t = 0;
    Eigen::VectorXd q, u;
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
  };

  // The contact solver hit its iteration cap.
  class ContactSolverFailure : public std::runtime_error
  {
  public:
    ContactSolverFailure(double t, unsigned int n_active, std::string active_corners, double residual,
                         unsigned int iterations);
    double t;
    unsigned int n_active;
    std::string active_corners; // e.g. "upper-left upper-right"
    double residual;
    unsigned int iterations;
  };

  // A slider corner reached a support (x ∉ [0, L]) by a plausible move (an
  // overshoot of less than the window width in half a step).
  class SliderAtSupport : public std::runtime_error
  {
  public:
    SliderAtSupport(double t, double x_C, double x_corner, double length);
    double t;        // start time of the step that would have crossed [s]
    double x_C;      // slider position then [m]
    double x_corner; // the corner's x at the step's midpoint [m]
    double support;  // 0 or L [m]
  };

  // NaN or Inf in the state after a step.
  class NonFiniteState : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // The state left the physically possible set: a corner penetrates the beam
  // deeper than the whole clearance R − h (the slider would be through the
  // beam), or the slider jumped past a support by more than its own window
  // width within half a step. Both mean a diverging integration (parameters
  // outside the model's range, or a time step that cannot resolve the
  // contact), never physics; the step is not accepted.
  class UnphysicalState : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // What one step did.
  struct StepReport
  {
    unsigned int n_active        = 0;
    unsigned int iterations      = 0;
    double residual              = 0;
    Eigen::Vector3d slider_impulse = Eigen::Vector3d::Zero(); // W_s P: contact impulse on the slider [N s, N s, N m s]
    double work_gravity          = 0; // [J]
    double work_damping          = 0;
    double work_excitation       = 0;
    double work_impact           = 0; // normal contact impulses × mean normal relative velocity
    double work_friction         = 0; // tangential
    double work_base_contact     = 0; // −P·w_imp
  };

  class MoreauStepper
  {
  public:
    // Throws std::invalid_argument for dt ≤ 0 or dt > beam.max_stable_time_step()
    // (naming the time step, its value and the limit).
    MoreauStepper(BeamSystem &beam, const SliderParameters &slider, const ContactLaw &law,
                  const BaseExcitation &base, double time_step, ProxSolverSettings solver = {});

    // State with the beam at rest (q = u = 0) and the slider resting on it at
    // x_C with zero velocity, at time t.
    SystemState resting_state(double x_C, double t = 0.) const;

    void set_state(const SystemState &state);
    const SystemState &state() const { return state_; }

    // The current state with the slider carried along the beam to x_C, as if
    // its window slid there with the beam held still: z_C, β and their rates
    // change by the differences of w, atan w' and their rates between the old
    // and the new x_C, so each corner keeps its gap up to the beam's curvature
    // under the window; a last shift of z_C gives the side nearer the beam
    // (upper or lower corners) its old smallest gap, so a resting slider stays
    // resting and none goes through the beam. Keeping z_C and β would put the
    // window where the beam was at the old x_C: on a beam vibrating at a few
    // h, a step of 0.025 L puts a corner through the beam. Throws
    // std::invalid_argument if a corner would leave [0, L].
    SystemState slider_moved_to(double x_C) const;

    // Hold x_C fixed (v_x = 0; z_C and β stay free, contacts stay active):
    // seed §4.2. The horizontal contact force is then the force needed to keep
    // the slider in place.
    void set_prescribed_horizontal_position(bool prescribed) { prescribed_x_ = prescribed; }
    bool prescribed_horizontal_position() const { return prescribed_x_; }

    // One step of size time_step(). Throws SliderAtSupport, ContactSolverFailure,
    // NonFiniteState or UnphysicalState; on a throw the state is unchanged.
    // For a beam that hands out its explicit modal form (the explicit
    // reduced model on a mode table, BeamSystem::explicit_modal_form) the
    // step is taken by step_explicit_modal (explicit_modal_step.cc): the same
    // scheme on the form's data, equal to the general step to round-off.
    const StepReport &step();

    // Whether step() takes the explicit modal step; use_general_step() makes
    // it step through the BeamSystem interface instead (the comparison of
    // the two in the tests, and a way to tell them apart in a study).
    bool takes_explicit_modal_step() const { return modal_ != nullptr; }
    void use_general_step() { modal_ = nullptr; }

    double time_step() const { return dt_; }
    const BeamSystem &beam() const { return beam_; }
    const SliderGeometry &geometry() const { return geometry_; }
    const SliderParameters &slider() const { return slider_; }
    const BaseExcitation &base() const { return base_; }

    // Energies [J]: beam (relative to the base), slider kinetic.
    double beam_energy() const { return beam_.energy(state_.q, state_.u); }
    double slider_kinetic_energy() const;

    // Everything that carries from one step to the next (state, time origin
    // and step count, warm starts, the held-position switch, and the beam
    // model's own state), for bit-identical checkpoints (checkpoint.h).
    void save(CheckpointWriter &out) const;
    void load(CheckpointReader &in);

    // Impulses carried to the next step (warm start), (P_N, P_T) per corner.
    const std::array<Eigen::Vector2d, n_slider_corners> &corner_impulses() const { return warm_; }

  private:
    const StepReport &step_explicit_modal();
    // The step's skeleton (moreau_step_skeleton.h), taken with the stages of
    // one of its two forms, each specialised in its own file for a tag
    // local to it: the general one (moreau_stepper.cc) and the explicit
    // modal one (explicit_modal_step.cc).
    template <typename FormStages>
    const StepReport &take_step(FormStages &stages);
    template <typename Form>
    class Stages;
    // What both steps share: the support check of the corners at the
    // detection configuration; the check of one corner's gap (throws for a
    // corner through the beam or a non-finite gap; true if it is closed);
    // the contact solve; the reports of a failed contact solve and of a
    // non-finite end state; and taking the end state over.
    void check_corners_on_beam(double t_B, const Eigen::Vector3d &s_M, const SliderFrame &frame) const;
    bool corner_is_closed(const unsigned int k, const double gap, const double thickness, const double t_B)
    {
      // The common cases inline; the rare ones (through the beam, NaN) throw.
      gap_M_[k] = gap; // the compliant law's force needs it
      if (gap > 0. && gap <= std::numeric_limits<double>::max())
        return false;
      if (gap >= thickness - slider_.window_height)
        return true;
      return corner_is_closed_or_throw(k, gap, thickness, t_B);
    }
    bool corner_is_closed_or_throw(unsigned int k, double gap, double thickness, double t_B) const;
    // The contact impulses P_ from the free relative velocities in c_ and
    // the Delassus matrix G_ of the m active corners: c_ += ε γ_B (rigid
    // corners) or the compliant law's terms (add_compliant_terms), the warm
    // start, the prox solver; a solve that fails throws.
    void solve_contact_impulses(double t_B, const std::array<unsigned int, n_slider_corners> &active, unsigned int m,
                                const Eigen::Matrix<double, 2 * n_slider_corners, 1> &gamma_B);
    // The compliant law on the same solver: the impulse over the step,
    // P_N = max(0, −Δt (k_N g_θ + c_N γ_θ)), with g_θ and γ_θ the gap and
    // its rate at the step's θ-point, linear in the end's γ_E, is the
    // complementarity 0 ≤ P_N ⊥ γ_E + (P_N + b)/a ≥ 0: a = Δt θ (k_N Δt_E
    // + c_N) on G's diagonal (as 1/a), b/a added to c.
    void add_compliant_terms(const std::array<unsigned int, n_slider_corners> &active, unsigned int m,
                             const Eigen::Matrix<double, 2 * n_slider_corners, 1> &gamma_B);
    [[noreturn]] static void throw_solver_failure(double t_B, const std::array<unsigned int, n_slider_corners> &active,
                                                  unsigned int m, const ProxSolverResult &result);
    [[noreturn]] void throw_non_finite_end(double t_B) const;
    void accept_step(const Eigen::Vector3d &s_E, const Eigen::Vector3d &v_E,
                     const std::array<Eigen::Vector2d, n_slider_corners> &new_warm);

    BeamSystem &beam_;
    SliderParameters slider_;
    SliderGeometry geometry_;
    ContactLaw law_;
    BaseExcitation base_;
    double dt_;
    ProxSolver solver_;
    bool prescribed_x_ = false;

    SystemState state_;
    // t = t_origin + k Δt, so that time does not accumulate round-off over
    // millions of steps; reset by set_state.
    double t_origin_           = 0;
    unsigned long steps_taken_ = 0;
    StepReport report_;
    std::array<Eigen::Vector2d, n_slider_corners> warm_;

    // Storage reused every step, sized once in the constructor for the four
    // corners (2 unknowns each) and the beam's n coordinates: a step works on
    // leading blocks and allocates nothing (tests/test_rom_step_allocations.cc).
    static constexpr int max_unknowns = 2 * n_slider_corners;
    Eigen::VectorXd q_M_, u_free_, u_E_, u_mean_, q_next_;              // n
    Eigen::MatrixXd W_b_, X_b_;                                         // n × 8
    Eigen::Matrix<double, 3, max_unknowns> W_s_;
    Eigen::Matrix<double, max_unknowns, max_unknowns> G_, G_compliant_;
    std::array<double, n_slider_corners> gap_M_{}; // g_N of each corner at the detection configuration [m]
    Eigen::Matrix<double, max_unknowns, 1> c_, P_, gamma_B_, gamma_mean_, imposed_;
    Eigen::Matrix<double, n_slider_corners, 1> mu_;
    CornerKinematics corner_;
    // The local form of the directions (a model with local kinematics), the
    // block of S⁻¹ on their coordinates, S⁻¹ block times W, and W P.
    static constexpr int max_local = LocalDirections::max_coordinates;
    LocalDirections local_directions_;
    Eigen::Matrix<double, max_local, max_local> S_block_;
    Eigen::Matrix<double, max_local, max_unknowns> SW_;
    Eigen::Matrix<double, max_local, 1> y_;
    // The explicit modal step's data (null: the general step) and its
    // K'q_M; the corners' positions in the slider frame, from the centre of
    // mass, (±B/2, ζR/2 + d).
    const ExplicitModalForm *modal_ = nullptr;
    Eigen::VectorXd stretch_q_;
    std::array<Eigen::Vector2d, n_slider_corners> corner_position_;
  };
} // namespace beamslider
