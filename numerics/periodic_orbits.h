// Periodic orbits of a periodically forced system by shooting, and their
// continuation in a parameter λ by pseudo-arclength (doc/physics.md §11).
//
// The system is seen only through its stroboscopic map y ↦ Φ(y; λ): the state
// after one forcing period (or k of them) started from y at the period's
// phase zero. A periodic orbit is a fixed point, Φ(y; λ) = y; its Floquet
// multipliers are the eigenvalues of the monodromy matrix ∂Φ/∂y, which here
// is taken by finite differences of whole periods (each column one more
// period), so the map may be any time-stepping scheme, smooth or not. Where
// the map is only piecewise smooth (a contact's active set changes within the
// period), the differences straddle the switching surface; the Jacobian check
// (ShootingOutcome::jacobian_change) says how far two difference steps
// disagree, which tells whether Newton's matrix and the multipliers there
// can be trusted.
//
// The unknowns are scaled (ShootingSettings::scale): z = y / s, so that one
// tolerance and one difference step fit states whose components have
// different units. Everything is Eigen only, like the rest of numerics/.
#pragma once

#include <Eigen/Dense>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // Φ(y; λ) and what the caller wants to see along a branch (amplitude, mean
  // force: quantities of the period started from y).
  struct PeriodMapValue
  {
    Eigen::VectorXd end;
    Eigen::VectorXd observables;
  };

  // Thrown by a map that cannot complete its period (its solver failed, the
  // state left the model's range); its message says where and why.
  class PeriodMapFailure : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  using PeriodMap = std::function<PeriodMapValue(const Eigen::VectorXd &y, double lambda)>;

  struct ShootingSettings
  {
    Eigen::VectorXd scale;          // typical size of each unknown, > 0 (same length as y)
    double tolerance         = 1e-8; // accepted ‖(Φ(y) − y) / s‖∞ [-]
    unsigned int max_iterations = 30;
    double difference_step   = 1e-6; // forward-difference step, in scaled unknowns [-]
    // Damped Newton: a step is halved while it does not reduce the scaled
    // residual, at most this many times.
    unsigned int max_halvings = 6;
  };

  struct OrbitPoint
  {
    double lambda = 0;
    Eigen::VectorXd y;            // the orbit's state at phase zero
    Eigen::VectorXd observables;  // of the period from y
    Eigen::VectorXcd multipliers; // Floquet multipliers, by decreasing modulus
    double residual       = 0;    // scaled ‖Φ(y) − y‖∞ at acceptance
    unsigned int iterations = 0;  // Newton corrections it took
    double jacobian_change = 0;   // see ShootingOutcome; NaN if not checked

    double largest_multiplier() const { return multipliers.size() ? std::abs(multipliers[0]) : 0.; }
    bool stable() const { return largest_multiplier() < 1.; }
  };

  struct ShootingOutcome
  {
    bool converged = false;
    std::string reason; // why not ("" when converged)
    OrbitPoint point;   // the last iterate (the orbit when converged)
  };

  // The monodromy matrix in scaled unknowns, M̃_ij = (∂Φ_i/∂y_j) s_j / s_i, by
  // forward differences of step h (scaled), given Φ at y. Its eigenvalues
  // are the Floquet multipliers (a similarity transform of ∂Φ/∂y).
  Eigen::MatrixXd scaled_monodromy(const PeriodMap &map, const Eigen::VectorXd &y, double lambda,
                                   const Eigen::VectorXd &phi_y, const Eigen::VectorXd &scale, double h);

  // Eigenvalues of M, sorted by decreasing modulus.
  Eigen::VectorXcd floquet_multipliers(const Eigen::MatrixXd &monodromy);

  // Damped Newton on Φ(y; λ) − y = 0 at fixed λ from y. Converged: the
  // multipliers and the Jacobian check (the largest entry of the difference
  // between the monodromy matrices at h and 10 h, over the largest entry of
  // the first) are filled in. Not converged: `reason` says why (the
  // iteration limit with the last residual; a step that no damping makes
  // reduce the residual; the map's own failure).
  ShootingOutcome shoot(const PeriodMap &map, const Eigen::VectorXd &y, double lambda, const ShootingSettings &settings);

  // The smallest k ≤ max_k for which Φᵏ(y) returns to y within `tolerance`
  // (scaled, ∞-norm), after `transient` periods from y; 0 when none does.
  // The stroboscopic points of the last max_k periods are returned in
  // `section` (a Poincaré section of the attractor reached).
  unsigned int detect_period_count(const PeriodMap &map, Eigen::VectorXd &y, double lambda,
                                   const Eigen::VectorXd &scale, unsigned int transient, unsigned int max_k,
                                   double tolerance, std::vector<Eigen::VectorXd> *section = nullptr);

  // The largest Lyapunov exponent of the map [per period], by the growth of
  // a small separation (`separation`, scaled) renormalised after every
  // period (Benettin et al. 1980), averaged over `periods` periods from y
  // after `discard` more (in which the separation turns toward the fastest
  // growing direction). Positive: nearby states part exponentially (chaos),
  // no periodic orbit to shoot for; started on a periodic orbit it is
  // ln |μ₁|: the cross-check of its multipliers by time integration.
  double largest_lyapunov_exponent(const PeriodMap &map, Eigen::VectorXd y, double lambda,
                                   const Eigen::VectorXd &scale, unsigned int periods, double separation = 1e-8,
                                   unsigned int discard = 0);

  // Bifurcations met along a branch, between two computed points.
  enum class BranchEvent
  {
    turning_point,   // λ reverses (a multiplier through +1)
    period_doubling, // a real multiplier through −1
    torus            // a complex pair through the unit circle (Neimark–Sacker)
  };
  std::string to_string(BranchEvent event);

  struct BranchEventRecord
  {
    BranchEvent kind = BranchEvent::turning_point;
    std::size_t after_point = 0;   // between points after_point and after_point + 1
    double lambda = 0;             // estimated (turning point: the extremum of λ along the arclength)
    Eigen::VectorXd observables;   // interpolated there
  };

  struct ContinuationSettings
  {
    ShootingSettings shooting;
    double lambda_scale = 1.;  // the size of a unit step in λ against one in the scaled state
    double lambda_min = -1e300, lambda_max = 1e300; // the branch ends where λ leaves [min, max]
    double initial_step = 0.02, min_step = 1e-5, max_step = 0.1; // arclength, scaled [-]
    int direction = +1;        // the first step's sign in λ
    unsigned int max_points = 1000;
    // The corrector's chord iteration contracts slowly where a multiplier is
    // near 1 (light damping): a corrector that converged within half of
    // these lets the step grow by 1.5.
    unsigned int max_corrector_iterations = 12;
    // Optional: the scale of the unknowns around an accepted orbit (e.g. the
    // model's own typical sizes), taken again at every point, so that the
    // tolerance, the difference step and the metric follow an orbit whose
    // size changes by orders of magnitude along the branch. Empty: the
    // shooting scale throughout.
    std::function<Eigen::VectorXd(const Eigen::VectorXd &y)> rescale;
    std::function<bool()> stop_requested;             // polled between points
    std::function<void(const OrbitPoint &)> on_point; // each accepted point (progress, writing)
  };

  struct Branch
  {
    std::vector<OrbitPoint> points;
    std::vector<BranchEventRecord> events;
    std::string end_reason; // why the continuation stopped
  };

  // Pseudo-arclength continuation of the fixed points of Φ(·; λ) from a
  // converged orbit: tangent predictor, corrector (chord Newton on the
  // fixed-point equations and the arclength condition, the Jacobian of the
  // predicted point), step halved on failure and grown after an easy
  // corrector; multipliers at each point, events between points. The
  // arclength metric weighs the state by 1/√n against λ / lambda_scale, so
  // that a branch along which the state changes a lot still advances in λ.
  Branch continue_branch(const PeriodMap &map, const OrbitPoint &start, const ContinuationSettings &settings);
} // namespace beamslider
