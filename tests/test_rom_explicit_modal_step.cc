// The explicit modal step (contact/explicit_modal_step.cc): the Moreau step
// of the explicit reduced model taken on the model's own data instead of
// through the BeamSystem interface. It is the same scheme with its
// arithmetic in another order, so it must follow the general step to
// round-off: compared step by step over the first periods of the signature
// move, with the slider rattling, sticking and sliding on the beam (the
// trajectories of this chaotic system part after a few dozen periods, so
// the comparison stops well before).
#include "contact/moreau_stepper.h"
#include "scene/scene.h"
#include "reduced/rom_beam_system.h"
#include "verification/studies/fe_rom_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>

using namespace beamslider;

namespace
{
  Scene published_scene() { return read_scene(BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm"); }

  std::unique_ptr<BeamSystem> rom(const Scene &scene, const unsigned int n_modes, const std::string &integrator)
  {
    ModelSetting setting;
    setting.n_modes    = n_modes;
    setting.integrator = integrator;
    setting.time_step  = scene.time_stepping.time_step;
    return make_beam_model(scene, setting);
  }

  double time_step(const Scene &scene, const BeamSystem &beam)
  {
    double dt = scene.time_stepping.time_step;
    while (dt > beam.max_stable_time_step())
      dt /= 2;
    return dt;
  }
} // namespace

// The scene's ROM (FE modes on their Hermite table, the membrane force)
// takes the explicit modal step; the implicit ROM, whose step is another,
// and any other model derived from the ROM do not.
TEST(ExplicitModalStep, IsTakenByTheExplicitRomOnAModeTableOnly)
{
  const Scene scene = published_scene();
  const SliderParameters slider = SliderParameters::from_scene(scene);
  const ContactLaw law          = ContactLaw::from_scene(scene);
  const BaseExcitation base     = BaseExcitation::from_scene(scene.excitation);

  auto explicit_rom = rom(scene, 5, "explicit");
  ASSERT_NE(explicit_rom->explicit_modal_form(), nullptr);
  MoreauStepper stepper(*explicit_rom, slider, law, base, time_step(scene, *explicit_rom));
  EXPECT_TRUE(stepper.takes_explicit_modal_step());
  stepper.use_general_step();
  EXPECT_FALSE(stepper.takes_explicit_modal_step());

  // A model derived from the ROM may step otherwise (here it only says so):
  // the form would bypass its overrides, so it has none.
  class DerivedRom : public RomBeamSystem
  {
  public:
    explicit DerivedRom(const RomBeamSystem &rom)
      : RomBeamSystem(rom)
    {}
  };
  const DerivedRom derived(dynamic_cast<const RomBeamSystem &>(*explicit_rom));
  EXPECT_EQ(derived.explicit_modal_form(), nullptr);

  auto implicit_rom = rom(scene, 5, "implicit");
  EXPECT_EQ(implicit_rom->explicit_modal_form(), nullptr);
  MoreauStepper implicit_stepper(*implicit_rom, slider, law, base, scene.time_stepping.time_step);
  EXPECT_FALSE(implicit_stepper.takes_explicit_modal_step());
}

// Step by step against the general step on the signature move's start
// (N = 5, the published ROM, and N = 10), the slider free and with x_C
// held (seed §4.2), after 0.1 s in which the beam's amplitude has grown
// and the slider rattles: the states after each step agree to round-off,
// and so do the step's works, which the explicit step forms differently
// (the contact works from G P); with rigid and with compliant corners.
TEST(ExplicitModalStep, FollowsTheGeneralStepToRoundOff)
{
  const Scene scene = published_scene();
  const SliderParameters slider = SliderParameters::from_scene(scene);
  const BaseExcitation base     = BaseExcitation::from_scene(scene.excitation);
  const double L = scene.beam.length, h = scene.beam.thickness;

  // Rigid corners (Newton's law) and compliant ones (k_N = 1e7 N/m: the
  // spring's terms in the contact solve, physics.md §7).
  std::map<double, unsigned long> two_corner_steps_by_law; // coupled corners in the solve, per law
  for (const double k_N : {0., 1e7})
  for (const unsigned int N : {5u, 10u})
    for (const bool held : {false, true})
      {
        Scene law_scene                    = scene;
        law_scene.contact.normal_stiffness = k_N;
        const ContactLaw law               = ContactLaw::from_scene(law_scene);
        auto beam      = rom(scene, N, "explicit");
        const double dt = time_step(scene, *beam);
        MoreauStepper fast(*beam, slider, law, base, dt), general(*beam, slider, law, base, dt);
        general.use_general_step();
        ASSERT_TRUE(fast.takes_explicit_modal_step());
        fast.set_state(fast.resting_state(scene.initial.slider_position_over_L * L));
        fast.set_prescribed_horizontal_position(held);
        general.set_prescribed_horizontal_position(held);
        // 0.1 s first with the explicit step alone: from rest, the beam's
        // amplitude has grown and the slider rattles.
        for (long k = 0; k < std::lround(0.1 / dt); ++k)
          fast.step();
        // Both from this state, with the same time origin (set_state).
        const SystemState start = fast.state();
        fast.set_state(start);
        general.set_state(start);

        // 0.1 s (12 periods) side by side; 0.003 s with compliant corners,
        // whose rattling parts two states apart at about 440 /s (measured:
        // the forms' 1e-17 differences of summation order reach 1e-14 after
        // 0.016 s, 1e-13 of the velocities after 0.005 s), where rigid
        // corners with e_N < 1 and sticking friction reset such
        // differences at every impact.
        const unsigned long n_steps = std::lround((k_N > 0. ? 0.003 : 0.1) / dt);
        double max_dq = 0, max_q = 0, max_du = 0, max_u = 0, max_ds = 0, max_dv = 0, max_v = 0, max_dwork = 0, max_work = 0;
        unsigned long contact_steps = 0, two_corner_steps = 0, active_differs = 0;
        for (unsigned long k = 0; k < n_steps; ++k)
          {
            const StepReport a = fast.step();
            const StepReport b = general.step();
            contact_steps += a.n_active > 0;
            two_corner_steps += a.n_active > 1;
            active_differs += a.n_active != b.n_active;
            const SystemState &x = fast.state(), &y = general.state();
            ASSERT_EQ(x.t, y.t);
            max_dq = std::max(max_dq, (x.q - y.q).cwiseAbs().maxCoeff());
            max_q  = std::max(max_q, y.q.cwiseAbs().maxCoeff());
            max_du = std::max(max_du, (x.u - y.u).cwiseAbs().maxCoeff());
            max_u  = std::max(max_u, y.u.cwiseAbs().maxCoeff());
            max_ds = std::max(max_ds, (x.s - y.s).head<2>().cwiseAbs().maxCoeff());
            max_dv = std::max(max_dv, (x.v - y.v).head<2>().cwiseAbs().maxCoeff());
            max_v  = std::max(max_v, y.v.head<2>().cwiseAbs().maxCoeff());
            for (const auto &[wa, wb] : {std::pair{a.work_damping, b.work_damping},
                                         {a.work_excitation, b.work_excitation},
                                         {a.work_impact, b.work_impact},
                                         {a.work_friction, b.work_friction},
                                         {a.work_base_contact, b.work_base_contact},
                                         {a.work_gravity, b.work_gravity}})
              {
                max_dwork = std::max(max_dwork, std::abs(wa - wb));
                max_work  = std::max(max_work, std::abs(wb));
              }
          }
        std::cout << "k_N = " << k_N << " N/m, N = " << N << (held ? ", x_C held" : ", free") << ": " << n_steps << " steps, "
                  << contact_steps << " with contact, " << two_corner_steps << " with two or more corners; max |dq| "
                  << max_dq << " of " << max_q << ", |du| " << max_du << " of " << max_u << ", |ds| " << max_ds
                  << " m, |dv| " << max_dv << " of " << max_v << " m/s, |dwork| " << max_dwork << " of " << max_work << " J; "
                  << active_differs << " steps with another active set" << std::endl;
        // The slider must rattle for the comparison to mean anything (in
        // the short compliant window: at least 20 steps with contact).
        EXPECT_GT(contact_steps, k_N > 0. ? 20ul : n_steps / 2);
        two_corner_steps_by_law[k_N] += two_corner_steps;
        EXPECT_EQ(active_differs, 0u);
        EXPECT_LT(max_dq, 1e-12 * max_q);
        EXPECT_LT(max_du, 1e-12 * max_u);
        EXPECT_LT(max_ds, 1e-12 * h);
        EXPECT_LT(max_dv, 1e-12 * max_v);
        // The works with compliant corners: 1.01e-12 of the largest on the
        // portable (sanitizer) build, 3e-14 on the native one; their
        // window is 3 ms, so the largest work is a few steps' worth.
        EXPECT_LT(max_dwork, (k_N > 0. ? 1e-11 : 1e-12) * max_work);
      }
  for (const auto &[k_N, steps] : two_corner_steps_by_law)
    EXPECT_GT(steps, 0u) << "k_N = " << k_N;
}
