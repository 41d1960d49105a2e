// Backbone curves (nonlinear normal modes) of a conservative second-order system
//
//   M q̈ + K q + f(q) = 0 ,          q ∈ Rⁿ, M, K symmetric dense,
//
// by harmonic balance (HB) with alternating frequency/time (AFT) evaluation of
// f, and continuation from the linear mode upward in amplitude. The same code
// serves the reduced model (M = I, K = diag ω_n², f = cubic, n = N ≤ 10) and a
// condensed finite-element model (n ≈ 70–300, dense).
//
// Ansatz (undamped, f depending on q only ⇒ motions symmetric in time, so a
// cosine series with the time origin at a turning point fixes the phase):
//
//   q(τ) = Σ_{h∈𝓗} Q_h cos(h τ),  τ = ω t,   𝓗 = {0, 1, …, H}  or  {1, 3, …}
//
// Odd harmonics only are consistent when f is odd, f(−q) = −f(q) (the cubic
// ROM): a product of three odd harmonics is an odd harmonic, so the residual
// has no even part. A von Kármán FE model with axial DOFs is NOT odd (u is
// even under w → −w: it carries the 0th and even harmonics), so use the full
// set there unless the in-plane DOFs are condensed out.
//
// HB residual (Galerkin on cos hτ):  R_h = (K − (hω)² M) Q_h + F_h(Q),
// F_h = (2/N_t) Σ_i f(q(τ_i)) cos(h τ_i) (1/N_t for h = 0), τ_i = 2π i / N_t.
// For cubic f, f(q(τ)) cos(hτ) contains harmonics up to 4H, so N_t ≥ 4H + 1
// samples make F_h and its Jacobian exact (no aliasing). Default N_t = 4H + 1.
//
// Unknowns: the Q_h (n·|𝓗|) and ω. Closure: either an amplitude constraint
// cᵀQ_1 = a (the first-harmonic amplitude of the output y = cᵀq, e.g. w(L/2)
// [m]) or the pseudo-arclength condition (Keller 1977; Seydel, "Practical
// Bifurcation and Stability Analysis", 2010), which follows folds and loops
// of the backbone in amplitude. The method is the one of Krack & Gross,
// "Harmonic Balance for Nonlinear Vibration Problems" (Springer 2019); the
// seed computed its NMA with their tool NLvib (H = 10, N = 7). This code is
// checked against exact Duffing periods and the seed's published backbone
// numbers (tests/test_reduced_backbone.cc), not against NLvib itself.
//
// Cost: the Newton matrix has size n|𝓗|+1; for n = 300, H = 10 (full set)
// that is 3301². A modal system's is dense and one LU of that size is
// seconds: use odd harmonics, the per-DoF half-period symmetry
// (HarmonicBalanceSettings::even_harmonic_dofs), or fewer. An FE system's
// is sparse (every block is the tangent's band) and is factorised as such.
//
// Internal resonances: where kω of the backbone meets another mode's
// frequency (k ≤ H), the branch turns into a "tongue" along which that mode's
// k-th harmonic grows. The continuation detects this (the first harmonic
// falls, or ω leaves the backbone extrapolated from below) and either stops
// with a message or restarts beyond the tongue from the extrapolated backbone
// (BackboneSettings::restart_past_tongues); Backbone::gaps records what was
// jumped over. The heuristics (the extrapolation, the restart guesses) are in
// backbone_tongues.h; where the tongues of the mueller2023 beam lie is in
// doc/physics.md.
//
// This file is generic: any M, K, f. The beam's mode-1 backbone as the
// reports use it (output w(L/2), amplitudes in thicknesses) and the
// single-mode formulas of the seed (Eqs. 4 and 5) are in beam_backbone.h.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  // M q̈ + K q + f(q) = 0 with f and its tangent ∂f/∂q as callbacks.
  struct ConservativeSystem
  {
    Eigen::MatrixXd mass;      // M [kg] (ROM: I)
    Eigen::MatrixXd stiffness; // K [N/m] (ROM: diag ω² [1/s²])
    std::function<Eigen::VectorXd(const Eigen::VectorXd &q)> force;   // f(q) [N]
    std::function<Eigen::MatrixXd(const Eigen::VectorXd &q)> tangent; // ∂f/∂q [N/m]

    unsigned int n_dofs() const { return stiffness.rows(); }
  };

  struct HarmonicBalanceSettings
  {
    unsigned int n_harmonics = 10;  // H ≥ 1
    bool odd_harmonics_only  = false; // only for odd f (see the file header)
    unsigned int n_time_samples = 0; // N_t; 0 → 4H + 1 (exact for cubic f)
    // Half-period symmetry per DoF, q_i(τ + π) = ±q_i(τ): if not empty (one
    // entry per DoF), DoF i carries only the even harmonics 0, 2, 4, … when
    // true and only the odd ones 1, 3, 5, … when false. Consistent when f
    // maps this pattern onto itself, as the von Kármán FE beam does with
    // w, θ odd and u even (u ↦ u, w ↦ −w leaves ε = u' + ½w'² unchanged):
    // the mode-1 backbone lies in this invariant subspace, and the Newton
    // matrix has about half the rows (an LU ~8× cheaper) with no loss of
    // accuracy. Cannot be combined with odd_harmonics_only.
    std::vector<bool> even_harmonic_dofs;
  };

  struct BackboneSettings
  {
    HarmonicBalanceSettings hb;
    Eigen::VectorXd output;       // c: amplitude functional y = cᵀq (size n)
    unsigned int mode = 0;        // linear mode (0-based, by ascending ω) the backbone starts from
    double start_amplitude = 0;   // first-harmonic amplitude of y at the first point [m]; > 0
    double end_amplitude   = 0;   // stop when reached [m]; > start_amplitude
    enum class Method
    {
      arclength, // pseudo-arclength in (Q, ω): follows folds/loops
      amplitude  // natural continuation in a: stops (reported) at a fold
    } method = Method::arclength;
    // Step sizes as fractions of end_amplitude (arclength: of the scaled
    // arclength, where Q is scaled by end_amplitude and ω by ω_mode).
    double initial_step = 0.02, min_step = 1e-6, max_step = 0.05;
    // Scale of Q in the continuation: false: end_amplitude (then the step
    // measured in the amplitude depends on the coordinates: large modal
    // steps for the ROM, tiny ones for the FE, whose slopes θ dominate the
    // norm); true: end_amplitude ‖φ‖ with the linear mode normalised to
    // cᵀφ = 1, so that a step is the same fraction of the amplitude range in
    // any coordinates.
    bool normalise_by_mode = false;
    // Arclength: stop (reported, not completed) when the first-harmonic
    // amplitude falls below this fraction of the largest one reached so far,
    // i.e. the branch has left along an internal-resonance tongue rather than
    // making a loop. 0 follows it until the first harmonic changes sign.
    // Jumping over the tongue to the continuation of the mode-1 backbone:
    // restart_past_tongues.
    double tongue_exit_fraction = 0.5;
    // Arclength: also stop (or restart) when ω departs by more than this
    // fraction from the backbone extrapolated from below (ω² = α + β a² +
    // γ a⁴ through the points at 0.4…0.85 of the largest amplitude): a tongue
    // can leave at almost constant first-harmonic amplitude (the FE model at
    // the 3:1 interaction creeps along it at tiny steps). 0: off.
    double tongue_frequency_deviation = 0;
    // Arclength only: when the branch leaves along a tongue, restart on the
    // far side. ω² = α + β a² + γ a⁴ is fitted to the backbone points in
    // [0.4, 0.85] a_last (a_last: the last amplitude before the branch turned
    // into the tongue), and an
    // amplitude-controlled Newton solve is tried at a = (1 + δ) a_last with
    // δ = 0.02, 0.05, 0.1, 0.2, 0.3, 0.5 from the predicted ω and the
    // first-harmonic shape of the reference point. A solution is accepted as
    // the continuation of the backbone if its ω is within 3 % of the
    // prediction; then the arclength continuation goes on from there as a new
    // segment. The skipped amplitude range is recorded in Backbone::gaps.
    bool restart_past_tongues = false;
    // On SIGINT/SIGTERM: keep the converged points and return them
    // (Backbone::interrupted; the `backbone` command), or throw Interrupted
    // (a study that needs the whole curve).
    bool keep_points_when_interrupted = false;
    unsigned int max_restarts = 3;
    // Arclength: amplitudes [m] (ascending) at which extra points are solved
    // for exactly (amplitude-controlled Newton from the interpolated step)
    // whenever a step crosses them upwards, so that backbones can be compared
    // at given amplitudes without interpolation error.
    std::vector<double> landing_amplitudes;
    unsigned int max_points            = 2000;
    unsigned int max_newton_iterations = 12;
    double tolerance = 1e-10; // on the scaled Newton correction
  };

  struct BackbonePoint
  {
    double amplitude = 0; // first-harmonic amplitude of y = cᵀq [m]
    double peak      = 0; // max_τ |y(τ)| [m]
    double omega     = 0; // [rad/s]
    Eigen::VectorXd harmonics; // Q_h stacked in the order of Backbone::harmonics
    unsigned int newton_iterations = 0;
    double relative_residual = 0; // ‖R‖ / (‖K Q‖ + ‖F‖) at the converged point
    unsigned int segment = 0; // 0, then +1 after each restart past a tongue
    // Past the segment's largest amplitude on the way out along an internal-
    // resonance tongue (set when the tongue exit is detected): a solution,
    // but no longer the mode-1 backbone.
    bool tongue = false;
  };

  // An amplitude range the continuation jumped over (restart_past_tongues).
  struct BackboneGap
  {
    double last_amplitude = 0, last_omega = 0;   // the largest amplitude before the exit [m], its ω [rad/s]
    double restart_amplitude = 0, restart_omega = 0; // first point of the next segment
    double predicted_omega = 0;                  // the extrapolated ω at the restart amplitude
  };

  struct Backbone
  {
    std::vector<unsigned int> harmonics; // the set 𝓗
    unsigned int n_time_samples = 0;
    std::vector<BackbonePoint> points;
    bool completed = false;  // end_amplitude reached
    bool interrupted = false; // stopped by SIGINT/SIGTERM (io/interruption.h)
    std::string message;     // why it stopped (always set)
    std::vector<BackboneGap> gaps; // ranges jumped over (restart_past_tongues)
    unsigned int n_newton_iterations = 0; // total, all points and retries
    double seconds = 0;      // wall time
  };

  // Continuation of the backbone from the linear mode `mode` at start_amplitude
  // up to end_amplitude. Never throws for a Newton failure during continuation:
  // it stops, keeps the converged points and says where and why in `message`
  // (amplitude, ω, residual); the same when SIGINT or SIGTERM arrives
  // (Backbone::interrupted). Throws std::invalid_argument for bad settings and
  // std::runtime_error if even the first point fails.
  Backbone compute_backbone(const ConservativeSystem &system, const BackboneSettings &settings);

  // Folds in amplitude along a computed backbone: the points where the
  // first-harmonic amplitude turns from growing to shrinking or back, within
  // each segment (a restart past a tongue is not a fold). A loop of the
  // backbone has two. With include_tongues = false the points past a
  // tongue's exit (BackbonePoint::tongue) are left out: the folds of the
  // mode-1 backbone itself.
  unsigned int count_amplitude_folds(const Backbone &backbone, bool include_tongues = true);

  // Evaluate y(τ) = cᵀq(τ) of a backbone point at n_samples equispaced τ in [0, 2π).
  Eigen::VectorXd output_time_history(const Backbone &backbone, const BackbonePoint &point,
                                      const Eigen::VectorXd &output, unsigned int n_samples);

} // namespace beamslider
