// The one Newton driver of the project, and the one load-stepping driver on
// top of it. Every nonlinear solve (the FE beam's and the solid's statics,
// relaxed STEP, the implicit time steps of the FE and reduced models, the
// harmonic-balance corrector) is a `Problem` handed to solve_newton(): the
// problem knows its residual, its iteration matrix and its norms; the driver
// owns the iteration itself: how many corrections, when a modified Newton
// iteration refreshes its matrix, when the corrections say it has converged
// or diverged, and what it reports when it stops.
//
// A Problem is any type with these members (the driver is a template, so
// the hot implicit steps pay no virtual call):
//
//   NewtonState evaluate(bool refresh);  // the residual at the iterate (and the
//                                        // matrix when refresh); converged or
//                                        // diverged if the residual says so
//   void factorise();                    // the iteration matrix just evaluated
//   double correct();                    // solve, update the iterate, return the
//                                        // correction's norm (inf or NaN: diverged)
//   bool small(double correction) const; // is a correction this size converged?
//
// Header-only and free of any linear-algebra library: the problems bring
// their own vectors (deal.II's, PETSc's or Eigen's).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace beamslider
{
  // What an evaluation of the residual says about the iteration.
  enum class NewtonState
  {
    go_on,
    converged, // the residual is small enough
    diverged   // the residual is out of bounds
  };

  // How a Newton solve is run.
  struct NewtonControl
  {
    // Corrections at most (the residual is evaluated before each).
    unsigned int max_iterations = 30;
    // Modified Newton: the matrix is refreshed when a correction shrinks by
    // less than this factor against the one before (∞: never for that
    // reason), after this many corrections on one matrix, and the solve
    // gives up rather than factorise more than max_factorisations times.
    // Full Newton: every iteration refreshes.
    bool modified                                 = false;
    double max_contraction                        = std::numeric_limits<double>::infinity();
    unsigned int max_iterations_per_factorisation = std::numeric_limits<unsigned int>::max();
    unsigned int max_factorisations               = std::numeric_limits<unsigned int>::max();
    // Accept on the contraction estimate of the remaining error, c/(1 − c)
    // times the correction for c = ‖δ_k‖/‖δ_{k−1}‖ < ½ (Hairer & Wanner,
    // Solving ODEs II, §IV.8): it saves the iteration that would only
    // confirm convergence.
    bool accept_on_contraction_estimate = false;
    // Whether the contraction is measured afresh after a refresh (the first
    // correction on a new matrix is compared with nothing), or across it
    // (with the old matrix's last correction).
    bool restart_contraction_at_refresh = true;
  };

  // The modified Newton iteration's matrix outlives one solve: the driver
  // counts the corrections made on it and the caller says when it is stale
  // (never factorised, or factorised for another step size).
  struct NewtonMatrixAge
  {
    bool stale                         = true;
    unsigned int corrections_on_matrix = 0;
  };

  enum class NewtonStop
  {
    converged,
    iteration_limit,     // max_iterations corrections made
    diverged,            // a residual out of bounds or a correction not finite
    factorisation_limit  // a refresh was due after max_factorisations
  };

  struct NewtonOutcome
  {
    NewtonStop stop             = NewtonStop::iteration_limit;
    unsigned int iterations     = 0; // corrections made
    unsigned int factorisations = 0;
    double correction           = 0; // the last correction's norm

    bool converged() const { return stop == NewtonStop::converged; }

    // Why it stopped, in words for an error message.
    std::string reason() const
    {
      switch (stop)
        {
          case NewtonStop::converged:
            return "converged";
          case NewtonStop::iteration_limit:
            return "iteration limit reached";
          case NewtonStop::diverged:
            return "diverged";
          case NewtonStop::factorisation_limit:
            return "factorisation limit reached";
        }
      return "";
    }
  };

  template <class Problem>
  NewtonOutcome solve_newton(Problem &problem, const NewtonControl &control, NewtonMatrixAge &age)
  {
    constexpr double none = std::numeric_limits<double>::infinity();
    NewtonOutcome out;
    // The correction the last one is measured against (none: no contraction
    // known yet, which neither refreshes nor accepts anything).
    double before_last = none;
    for (unsigned int it = 1; it <= control.max_iterations; ++it)
      {
        const bool refresh = !control.modified || age.stale ||
                             age.corrections_on_matrix >= control.max_iterations_per_factorisation ||
                             out.correction > control.max_contraction * before_last;
        const NewtonState state = problem.evaluate(refresh);
        if (state != NewtonState::go_on)
          {
            out.stop = state == NewtonState::converged ? NewtonStop::converged : NewtonStop::diverged;
            return out;
          }
        double base = it == 1 ? none : out.correction;
        if (refresh)
          {
            if (out.factorisations == control.max_factorisations)
              {
                out.stop = NewtonStop::factorisation_limit;
                return out;
              }
            problem.factorise();
            ++out.factorisations;
            age.stale                 = false;
            age.corrections_on_matrix = 0;
            if (control.restart_contraction_at_refresh)
              base = none;
          }
        out.correction = problem.correct();
        ++out.iterations;
        if (age.corrections_on_matrix < std::numeric_limits<unsigned int>::max())
          ++age.corrections_on_matrix;
        before_last = base;
        if (!std::isfinite(out.correction))
          {
            out.stop = NewtonStop::diverged;
            return out;
          }
        const double c = out.correction / base;
        if (problem.small(out.correction) || (control.accept_on_contraction_estimate && base != none && c < 0.5 &&
                                              problem.small(c / (1. - c) * out.correction)))
          {
            out.stop = NewtonStop::converged;
            return out;
          }
      }
    out.stop = NewtonStop::iteration_limit;
    return out;
  }

  // Load stepping: the load is applied in increments, each solved by
  // Newton's method from the last converged state; an increment that fails
  // is cut in half and tried again, one that converges lets the next double.
  struct LoadSteps
  {
    double initial = 1.;   // fraction of the full load
    double min     = 1e-4; // give up below this increment
  };

  // The load of an increment: F_start + fraction (F − F_start), or fraction
  // F from zero (F_start null). Vector: deal.II's or PETSc's.
  template <class Vector>
  void load_at_fraction(const Vector &F, const Vector *F_start, const double fraction, Vector &load)
  {
    load = F;
    if (F_start)
      load.sadd(fraction, 1. - fraction, *F_start);
    else
      load *= fraction;
  }

  // A load-stepped problem has
  //   void begin_increment(double fraction);   // the load at this fraction; keep the start
  //   NewtonOutcome solve_increment();         // Newton from the kept start
  //   void restore();                          // back to the start after a failure
  //   void give_up(double fraction, const NewtonOutcome &last);  // throws: stuck at fraction
  // and solve_load_stepped() returns the corrections made in all.
  template <class Stepped>
  unsigned int solve_load_stepped(Stepped &problem, const LoadSteps &steps)
  {
    double lambda = 0, step = steps.initial;
    unsigned int total = 0;
    while (lambda < 1.)
      {
        const double target = std::min(1., lambda + step);
        problem.begin_increment(target);
        const NewtonOutcome out = problem.solve_increment();
        total += out.iterations;
        if (out.converged())
          {
            lambda = target;
            step   = std::min(2 * step, 1. - lambda + 1e-15);
          }
        else
          {
            problem.restore();
            step *= 0.5;
            if (step < steps.min)
              problem.give_up(lambda, out);
          }
      }
    return total;
  }

  // Full Newton, or a modified one whose matrix lives for this solve only.
  template <class Problem>
  NewtonOutcome solve_newton(Problem &problem, const NewtonControl &control)
  {
    NewtonMatrixAge age;
    return solve_newton(problem, control, age);
  }
} // namespace beamslider
