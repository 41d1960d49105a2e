// The beam as the contact code sees it (doc/architecture.md): a second-order system
// in coordinates q (modal for the reduced model, nodal for the FE model) that
// provides one Moreau–Jean step without contact and the kinematics of the
// beam at any point. The slider, the gaps, the force directions W, the
// Moreau step and the prox solver are written once against this interface, so
// an FE trace and a ROM trace differ only through the beam model.
//
// Step structure (Moreau midpoint / Moreau–Jean with θ = 1/2):
//   q_M    = q_B + Δt/2 u_B                           (where contacts are detected)
//   u_E    = u_free + S⁻¹ W P                         (P: contact impulses)
//   q_E    = q_M + Δt/2 u_E
// u_free is the end velocity without contact impulses; S is the iteration
// matrix (the mass matrix M for the explicit midpoint scheme; the effective
// matrix M + θΔt C + θ²Δt² K_t for an implicit scheme). The Delassus matrix
// is G = Wᵀ S⁻¹ W.
#pragma once

#include <Eigen/Dense>

#include <limits>

namespace beamslider
{
  // Transverse displacement (relative to the moving base) and slope at one x,
  // with their gradients with respect to the beam coordinates.
  struct BeamPointKinematics
  {
    double w  = 0;           // [m]
    double dw = 0;           // w' [-]
    Eigen::VectorXd grad_w;  // ∂w/∂q
    Eigen::VectorXd grad_dw; // ∂w'/∂q
  };

  class CheckpointWriter;
  class CheckpointReader;

  class BeamSystem
  {
  public:
    virtual ~BeamSystem() = default;

    virtual unsigned int n_dofs() const = 0;
    virtual double length() const       = 0; // L [m]
    virtual double thickness() const    = 0; // h [m]

    // w, w' and gradients at x ∈ [0, L] for coordinates q. w and w' are
    // linear in q (w = grad_w · q): AdaptationRun takes the gradient at the
    // centre once and forms w(L/2) by a dot product every step.
    virtual void evaluate(double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const = 0;

    // End velocity of one step of size dt without contact impulses, given the
    // midpoint time t_M, midpoint coordinates q_M and start velocity u_B.
    // May factorise/update the iteration matrix S for solve_iteration_matrix.
    // A model whose own solver fails (an implicit model's Newton iteration)
    // throws a std::runtime_error saying where and why; AdaptationRun stops
    // the run cleanly with it (RunStatus::beam_solver_failure).
    virtual void free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                               Eigen::VectorXd &u_free) = 0;

    // X = S⁻¹ B for the iteration matrix of the last free_velocity call. X
    // has B's size on entry (the caller's preallocated storage: blocks of
    // fixed buffers, so that a time step allocates nothing).
    virtual void solve_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                        Eigen::Ref<Eigen::MatrixXd> X) const = 0;

    // Largest time step the scheme can take (infinity for unconditionally
    // stable schemes). The stepper refuses larger steps with a clear message.
    virtual double max_stable_time_step() const = 0;

    // Mechanical energy of the beam (kinetic relative to the base + strain) [J],
    // for energy bookkeeping.
    virtual double energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const = 0;

    // Work [J] done on the beam during the last step (the one of the last
    // free_velocity call) by its damping forces and by the base-excitation
    // load, given that step's end velocity u_E. A midpoint step changes the
    // kinetic energy by exactly Δt h·(u_B + u_E)/2, so the work of each part of
    // h is its impulse times the mean velocity.
    // Why this is in the interface: free_velocity lumps all smooth forces into
    // u_free, and only the beam model knows which part is damping and which is
    // the base load; the energy balance of the adaptation runs (doc/verification.md)
    // needs them separately. A model that cannot split them may return NaN.
    virtual void step_work(const Eigen::VectorXd & /*u_E*/, double &damping_work, double &excitation_work) const
    {
      damping_work    = std::numeric_limits<double>::quiet_NaN();
      excitation_work = std::numeric_limits<double>::quiet_NaN();
    }

    // Called with the step's start and end coordinates and the end velocity
    // before they become the state. Coordinates without mass (the FE
    // without axial inertia) carry no momentum: their velocity is the mean
    // over the step, (q_E − q_B)/Δt, not the midpoint rule's 2(q_E − q_B)/Δt
    // − u_B, which flips sign every step and never decays. Others keep u_E.
    virtual void finish_step(const Eigen::VectorXd & /*q_B*/, const Eigen::VectorXd & /*q_E*/, double /*dt*/,
                             Eigen::VectorXd & /*u_E*/) const
    {}

    // Whatever the model carries from one step to the next and that changes
    // a later step's result in any bit (a reused factorisation and the point
    // it was made at, a predictor's history), for checkpoints
    // (contact/checkpoint.h): a model restored by load_state continues
    // bit-identically. A model without such state keeps the defaults.
    virtual void save_state(CheckpointWriter & /*out*/) const {}
    virtual void load_state(CheckpointReader & /*in*/) {}
  };
} // namespace beamslider
