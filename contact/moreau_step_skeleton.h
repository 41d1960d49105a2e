// The one Moreau step of moreau_stepper.h, written once for its two forms:
// the general step through the BeamSystem interface (moreau_stepper.cc) and
// the explicit modal step on the reduced model's own data
// (explicit_modal_step.cc). The skeleton holds the order of the stages and
// what both compute alike; a form supplies the stages whose arithmetic
// differs, as the non-virtual members of its MoreauStepper::Stages<Form>.
// Form is a tag local to the form's file, so that its stages are local
// functions, each called once, which the compiler inlines into the step as
// the single function it was (the explicit modal step is the reduced
// model's hot loop; an extern stage would be a call per stage and corner).
// A form's stages have
//
//   dt_B, dt_E                      the step's parts before and after the
//                                   detection configuration [s]
//   detection_frame(t_M, s_M)       the slider frame at the midpoint
//   free_velocity(t_M, s_M, frame)  u_free_ from q_M_ and the start state
//   closed_corner(k, frame, s_M, t_B, m)
//                                   true if corner k is closed, its
//                                   directions then in columns 2m, 2m + 1
//   contact_problem(m2, v_B, v_free, inv_mass)
//                                   G_, c_ (free relative velocities) and
//                                   gamma_B_ (those at the start)
//   add_beam_impulse(m2)            u_E_ += S⁻¹ W_b P
//   contact_work(m2, v_B, v_E)      the impulses' normal and tangential works
//   finish_beam()                   the beam's works over the step, and what
//                                   the beam model does at its end
//
// Private to the two files that instantiate it.
#pragma once

#include "contact/moreau_stepper.h"

namespace beamslider
{
  template <typename FormStages>
  const StepReport &MoreauStepper::take_step(FormStages &stages)
  {
    const double t_B = state_.t;
    const double t_M = t_B + stages.dt_B;
    report_          = StepReport();

    // Midpoint configuration; no beam evaluation before the corners are known
    // to lie on the beam.
    Eigen::Vector3d v_B = state_.v;
    if (prescribed_x_)
      v_B[0] = 0.;
    const Eigen::Vector3d s_M = state_.s + stages.dt_B * v_B;
    const SliderFrame frame   = stages.detection_frame(t_M, s_M);
    check_corners_on_beam(t_B, s_M, frame);
    q_M_ = state_.q + stages.dt_B * state_.u;

    // Free motion.
    stages.free_velocity(t_M, s_M, frame);
    const Eigen::Vector3d v_free = v_B + dt_ * Eigen::Vector3d(0., -slider_.gravity, 0.);
    const Eigen::Vector3d inv_mass(prescribed_x_ ? 0. : 1. / slider_.mass, 1. / slider_.mass, 1. / slider_.inertia);

    // Active set and force directions at the midpoint. All storage is sized
    // once for the four corners (constructor); a step works on its leading
    // blocks and allocates nothing.
    std::array<unsigned int, n_slider_corners> active{};
    unsigned int m = 0;
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      if (stages.closed_corner(k, frame, s_M, t_B, m))
        active[m++] = k;
    report_.n_active = m;

    std::array<Eigen::Vector2d, n_slider_corners> new_warm;
    for (auto &p : new_warm)
      p.setZero();
    u_E_                = u_free_;
    Eigen::Vector3d v_E = v_free;
    if (m > 0)
      {
        const Eigen::Index m2 = 2 * m;
        stages.contact_problem(m2, v_B, v_free, inv_mass);
        solve_contact_impulses(t_B, active, m, gamma_B_);
        const auto P = P_.head(m2);

        // u_E = u_free + S⁻¹ W_b P, v_E = v_free + M_s⁻¹ W_s P.
        stages.add_beam_impulse(m2);
        report_.slider_impulse.noalias() = W_s_.leftCols(m2).lazyProduct(P);
        v_E += inv_mass.cwiseProduct(report_.slider_impulse);
        for (unsigned int i = 0; i < m; ++i)
          new_warm[active[i]] = P.segment<2>(2 * i);

        // Contact work: impulse × mean relative velocity, per direction.
        stages.contact_work(m2, v_B, v_E);
        report_.work_base_contact = -P.dot(imposed_.head(m2));
      }

    // The end state, checked before it replaces the old one.
    q_next_ = q_M_ + stages.dt_E * u_E_;
    const Eigen::Vector3d s_E = s_M + stages.dt_E * v_E;
    if (!q_next_.allFinite() || !u_E_.allFinite() || !s_E.allFinite() || !v_E.allFinite())
      throw_non_finite_end(t_B);

    report_.work_gravity = -slider_.mass * slider_.gravity * (s_E[1] - state_.s[1]);
    stages.finish_beam();

    accept_step(s_E, v_E, new_warm);
    return report_;
  }
} // namespace beamslider
