// The beam as the contact code sees it (doc/architecture.md): a second-order system
// in coordinates q (modal for the reduced model, nodal for the FE model) that
// provides one Moreau–Jean step without contact and the kinematics of the
// beam at any point. The slider, the gaps, the force directions W, the
// Moreau step and the prox solver are written once against this interface, so
// an FE trace and a ROM trace differ only through the beam model.
//
// Step structure (Moreau–Jean θ-scheme; θ = 1/2, the Moreau midpoint rule,
// unless the model asks for more, see theta()):
//   q_M    = q_B + (1 − θ) Δt u_B                     (where contacts are detected)
//   u_E    = u_free + S⁻¹ W P                         (P: contact impulses)
//   q_E    = q_M + θ Δt u_E
// u_free is the end velocity without contact impulses; S is the iteration
// matrix (the mass matrix M for the explicit midpoint scheme; the effective
// matrix M + θΔt C + θ²Δt² K_t for an implicit scheme). The Delassus matrix
// is G = Wᵀ S⁻¹ W. free_velocity returns a BeamStep that carries the rest of
// the step (the solves with S, the works, the finish), so they cannot be asked
// of a step that has not begun.
#pragma once

#include <Eigen/Dense>

#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // The beam's fields at sample points x (BeamSystem::sample_fields).
  struct BeamFieldSamples
  {
    std::vector<double> x;           // sample positions [m]
    std::vector<double> u;           // axial displacement [m]
    std::vector<double> w;           // deflection relative to the base [m]
    std::vector<double> dw;          // slope w' [-]
    std::vector<double> curvature;   // w'' [1/m]
    std::vector<double> axial_force; // N [N]
  };

  // Transverse displacement (relative to the moving base) and slope at one x,
  // with their gradients with respect to the beam coordinates.
  struct BeamPointKinematics
  {
    double w  = 0;           // [m]
    double dw = 0;           // w' [-]
    Eigen::VectorXd grad_w;  // ∂w/∂q
    Eigen::VectorXd grad_dw; // ∂w'/∂q
  };

  // w, w' at one x with their gradients on the few coordinates they depend
  // on, for a model whose point kinematics are local (the FE beam: the four
  // Hermite DoFs of the cell under x; BeamSystem::has_local_kinematics). The
  // Moreau step then works on those coordinates alone instead of on dense
  // gradients of length n: the dense products were a fifth of an FE step.
  struct LocalPointKinematics
  {
    static constexpr unsigned int capacity = 4;
    double w  = 0;   // [m]
    double dw = 0;   // w' [-]
    unsigned int n = 0;                          // coordinates touched (≤ capacity)
    std::array<unsigned int, capacity> index{};  // which ones
    std::array<double, capacity> grad_w{};       // ∂w/∂q there
    std::array<double, capacity> grad_dw{};      // ∂w'/∂q there
  };

  struct ExplicitModalForm;
  class CheckpointWriter;
  class CheckpointReader;
  class BeamSystem;

  // One step of a beam without contact, as returned by BeamSystem::free_velocity.
  // The step order — free velocity, then any number of iteration-matrix
  // solves, then the step's works and its finish — is carried by this object:
  // what needs the step (the solve with the iteration matrix the free velocity
  // factorised, the works of its forces) can only be asked of it. It is a
  // small value (a pointer and a serial number); using it after its beam has
  // begun another step throws std::logic_error.
  class BeamStep
  {
  public:
    // X = S⁻¹ B for this step's iteration matrix S. X has B's size on entry
    // (the caller's preallocated storage: blocks of fixed buffers, so that a
    // time step allocates nothing).
    void solve_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B, Eigen::Ref<Eigen::MatrixXd> X) const;

    // Work [J] done on the beam during this step by its damping forces and by
    // the base-excitation load, given the step's end velocity u_E (see
    // BeamSystem::compute_step_work).
    void work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const;

    // Called with the step's start and end coordinates and the end velocity
    // before they become the state (see BeamSystem::finish_step).
    void finish(const Eigen::VectorXd &q_B, const Eigen::VectorXd &q_E, Eigen::VectorXd &u_E) const;

    double time_step() const { return dt_; } // Δt [s]

    // True when the iteration matrix is the identity (the explicit reduced
    // model: unit modal masses), so that S⁻¹ W is W itself and the caller
    // may skip the solve and its copy.
    bool iteration_matrix_is_identity() const;

    // For a model with local kinematics (BeamSystem::has_local_kinematics):
    // out(a, b) = (S⁻¹)_{i_a i_b} for the k coordinates i = index[0..k), the
    // block of S⁻¹ that the contact directions on those coordinates see.
    void inverse_iteration_matrix_block(const unsigned int *index, unsigned int k, Eigen::Ref<Eigen::MatrixXd> out) const;
    // u += S⁻¹ y for y zero but on the k coordinates index[0..k) (values y[0..k)).
    void add_inverse_iteration_matrix_times(const unsigned int *index, unsigned int k, const double *y,
                                            Eigen::VectorXd &u) const;

  private:
    friend class BeamSystem;
    BeamStep(const BeamSystem &beam, unsigned long serial, double dt)
      : beam_(&beam)
      , serial_(serial)
      , dt_(dt)
    {}
    void check_current() const;

    const BeamSystem *beam_;
    unsigned long serial_;
    double dt_;
  };

  class BeamSystem
  {
  public:
    virtual ~BeamSystem() = default;

    virtual unsigned int n_dofs() const = 0;
    virtual double length() const       = 0; // L [m]
    // h [m]: the beam's thickness, its thickest section's if it varies (the
    // reference for R/h and for amplitudes in thicknesses).
    virtual double thickness() const    = 0;
    // The thickness at x [m], where the slider's corners meet the surfaces
    // ±h(x)/2; constant along a uniform beam.
    virtual double thickness_at(double /*x*/) const { return thickness(); }

    // w, w' and gradients at x ∈ [0, L] for coordinates q. w and w' are
    // linear in q (w = grad_w · q): AdaptationRun takes the gradient at the
    // centre once and forms w(L/2) by a dot product every step.
    virtual void evaluate(double x, const Eigen::VectorXd &q, BeamPointKinematics &out) const = 0;

    // w and w' at x without their gradients: what the contact detection
    // asks of a corner before it knows whether the corner touches (in most
    // steps most corners are open). The default takes them from evaluate();
    // a model overrides it with the few operations it needs.
    virtual void evaluate_displacement(double x, const Eigen::VectorXd &q, double &w, double &dw) const;

    // True for a model whose w and w' at a point depend on at most
    // LocalPointKinematics::capacity coordinates (the FE beam), which then
    // gives them by evaluate_local and the blocks of S⁻¹ on them by its
    // steps (BeamStep::inverse_iteration_matrix_block,
    // add_inverse_iteration_matrix_times). False: dense gradients
    // (evaluate) and dense solves (BeamStep::solve_iteration_matrix).
    virtual bool has_local_kinematics() const { return false; }
    // Throws std::logic_error unless has_local_kinematics().
    virtual void evaluate_local(double x, const Eigen::VectorXd &q, LocalPointKinematics &out) const;

    // Where the slider's two corner pairs are along the beam [m] in the
    // step that begins next; the Moreau stepper says it before each
    // free_velocity. A model whose mass follows the contact points (the FE
    // beam with its mass redistributed away from them,
    // FETransientSettings::redistributed_mass) keeps them; others ignore it.
    virtual void set_contact_abscissae(double /*x_left*/, double /*x_right*/) {}

    // Begins a step of size dt: the end velocity u_free without contact
    // impulses, given the time t_M = t_B + (1 − θ) Δt of the detection
    // configuration q_M (the midpoint for θ = 1/2) and the start
    // velocity u_B. The returned step solves with this step's iteration matrix
    // and gives its works. A model whose own solver fails (an implicit model's
    // Newton iteration) throws a std::runtime_error saying where and why;
    // AdaptationRun stops the run cleanly with it (RunStatus::beam_solver_failure).
    BeamStep free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                           Eigen::VectorXd &u_free)
    {
      ++step_serial_; // a step object of the step before is stale from here on, even if this throws
      compute_free_velocity(t_M, q_M, u_B, dt, u_free);
      return BeamStep(*this, step_serial_, dt);
    }

    // θ ∈ [1/2, 1] of the step structure above: q_E = q_B + Δt ((1 − θ) u_B
    // + θ u_E). 1/2 (the midpoint rule, second order, no numerical damping)
    // for every model but an FE beam set to damp its unresolved modes
    // (FETransientSettings::theta); the stepper moves the slider with it too.
    virtual double theta() const { return 0.5; }

    // True for a model whose iteration matrix S is the identity in every
    // step (BeamStep::iteration_matrix_is_identity).
    virtual bool iteration_matrix_is_identity() const { return false; }
    // The explicit reduced model's data, for a model whose step the Moreau
    // stepper may take itself (contact/explicit_modal_form.h); null for any
    // other model, which the stepper then steps through this interface. A
    // model that hands it out promises that free_velocity, the iteration
    // matrix (S = I) and step_work are exactly what the form says.
    virtual const ExplicitModalForm *explicit_modal_form() const { return nullptr; }

    // Largest time step the scheme can take (infinity for unconditionally
    // stable schemes). The stepper refuses larger steps with a clear message.
    virtual double max_stable_time_step() const = 0;

    // Mechanical energy of the beam (kinetic relative to the base + strain) [J],
    // for energy bookkeeping.
    virtual double energy(const Eigen::VectorXd &q, const Eigen::VectorXd &u) const = 0;

    // The beam's fields at sample points along x for coordinates q (for
    // animations and pictures). The default samples evaluate() at 129 points,
    // w'' by differences of w', u = 0 and the axial force unknown (NaN); models
    // override it with their own fields.
    virtual BeamFieldSamples sample_fields(const Eigen::VectorXd &q) const;

    // Whatever the model carries from one step to the next and that changes
    // a later step's result in any bit (a reused factorisation and the point
    // it was made at, a predictor's history), for checkpoints
    // (io/checkpoint.h): a model restored by load_state continues
    // bit-identically. A model without such state keeps the defaults.
    virtual void save_state(CheckpointWriter & /*out*/) const {}
    virtual void load_state(CheckpointReader & /*in*/) {}

  protected:
    // The model's part of free_velocity: u_free; may factorise/update the
    // iteration matrix S for apply_inverse_iteration_matrix.
    virtual void compute_free_velocity(double t_M, const Eigen::VectorXd &q_M, const Eigen::VectorXd &u_B, double dt,
                                       Eigen::VectorXd &u_free) = 0;

    // X = S⁻¹ B for the iteration matrix of the last compute_free_velocity.
    virtual void apply_inverse_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                                Eigen::Ref<Eigen::MatrixXd> X) const = 0;
    // The local forms of the same (BeamStep); a model with local kinematics
    // overrides both, the defaults throw std::logic_error.
    virtual void inverse_iteration_matrix_block(const unsigned int *index, unsigned int k,
                                                Eigen::Ref<Eigen::MatrixXd> out) const;
    virtual void add_inverse_iteration_matrix_times(const unsigned int *index, unsigned int k, const double *y,
                                                    Eigen::VectorXd &u) const;

    // Work [J] done on the beam during the last step by its damping forces
    // and by the base-excitation load, given that step's end velocity u_E. A
    // midpoint step changes the kinetic energy by exactly Δt h·(u_B + u_E)/2,
    // so the work of each part of h is its impulse times the mean velocity.
    // Why this is in the interface: free_velocity lumps all smooth forces into
    // u_free, and only the beam model knows which part is damping and which is
    // the base load; the energy balance of the adaptation runs (doc/verification.md)
    // needs them separately. A model that cannot split them returns NaN.
    virtual void compute_step_work(const Eigen::VectorXd & /*u_E*/, double &damping_work,
                                   double &excitation_work) const
    {
      damping_work    = std::numeric_limits<double>::quiet_NaN();
      excitation_work = std::numeric_limits<double>::quiet_NaN();
    }

    // Coordinates without mass (the FE without axial inertia) carry no
    // momentum: their velocity is the mean over the step, (q_E − q_B)/Δt, not
    // the midpoint rule's 2(q_E − q_B)/Δt − u_B, which flips sign every step
    // and never decays. Others keep u_E.
    virtual void finish_step(const Eigen::VectorXd & /*q_B*/, const Eigen::VectorXd & /*q_E*/, double /*dt*/,
                             Eigen::VectorXd & /*u_E*/) const
    {}

  private:
    friend class BeamStep;
    unsigned long step_serial_ = 0;
    mutable BeamPointKinematics displacement_scratch_; // evaluate_displacement's default, allocation-free after its first call
  };

  // w, w' from evaluate at n_samples equidistant points (n_samples ≥ 3), w''
  // by central differences of w' (one-sided at the ends), u = 0 and the axial
  // force NaN (a model that knows it fills it in).
  BeamFieldSamples sample_by_evaluation(const BeamSystem &beam, const Eigen::VectorXd &q, unsigned int n_samples);

  inline void BeamStep::check_current() const
  {
    if (serial_ != beam_->step_serial_)
      throw std::logic_error("BeamStep used after its beam began another step (call free_velocity once per step "
                             "and use the step it returns)");
  }

  inline void BeamStep::solve_iteration_matrix(const Eigen::Ref<const Eigen::MatrixXd> &B,
                                               Eigen::Ref<Eigen::MatrixXd> X) const
  {
    check_current();
    beam_->apply_inverse_iteration_matrix(B, X);
  }

  inline bool BeamStep::iteration_matrix_is_identity() const
  {
    check_current();
    return beam_->iteration_matrix_is_identity();
  }

  inline void BeamStep::inverse_iteration_matrix_block(const unsigned int *index, const unsigned int k,
                                                       Eigen::Ref<Eigen::MatrixXd> out) const
  {
    check_current();
    beam_->inverse_iteration_matrix_block(index, k, out);
  }

  inline void BeamStep::add_inverse_iteration_matrix_times(const unsigned int *index, const unsigned int k,
                                                           const double *y, Eigen::VectorXd &u) const
  {
    check_current();
    beam_->add_inverse_iteration_matrix_times(index, k, y, u);
  }

  inline void BeamStep::work(const Eigen::VectorXd &u_E, double &damping_work, double &excitation_work) const
  {
    check_current();
    beam_->compute_step_work(u_E, damping_work, excitation_work);
  }

  inline void BeamStep::finish(const Eigen::VectorXd &q_B, const Eigen::VectorXd &q_E, Eigen::VectorXd &u_E) const
  {
    check_current();
    beam_->finish_step(q_B, q_E, dt_, u_E);
  }
} // namespace beamslider
