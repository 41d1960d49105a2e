// One smooth step of a beam model without contact, in the Moreau stepper's
// structure, from time t: q_M = q + (1 − θ)Δt u, u ← u_free,
// q ← q_M + θΔt u (θ = 1/2: the midpoint), then the step's finish (massless
// coordinates take the step's mean velocity). Shared by the tests that
// integrate a beam alone.
#pragma once

#include "contact/beam_system.h"

namespace beamslider::testing
{
  inline void free_step(BeamSystem &beam, const double t, const double dt, Eigen::VectorXd &q, Eigen::VectorXd &u)
  {
    const double theta        = beam.theta();
    const Eigen::VectorXd q_B = q, q_M = q + (1. - theta) * dt * u;
    Eigen::VectorXd u_E;
    const BeamStep step = beam.free_velocity(t + (1. - theta) * dt, q_M, u, dt, u_E);
    q                   = q_M + theta * dt * u_E;
    u                   = u_E;
    step.finish(q_B, q, u);
  }
} // namespace beamslider::testing
