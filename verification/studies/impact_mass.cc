// The beam mass an impact moves, on every beam model through the
// BeamSystem interface (contact/beam_system.h).
#include "verification/studies/impact_mass.h"

#include "contact/beam_system.h"
#include "verification/studies/fe_rom_study.h"

#include <cmath>
#include <limits>

namespace beamslider
{
  namespace
  {
    // 1/(wᵀ S⁻¹ w) at x for the model of `setting`, with the corners at
    // x_left, x_right (a redistributed FE mass follows them).
    double mass_under(const Scene &scene, const ModelSetting &setting, const double x_left, const double x_right)
    {
      const std::unique_ptr<BeamSystem> beam = make_beam_model(scene, setting);
      const unsigned int n                   = beam->n_dofs();
      beam->set_contact_abscissae(x_left, x_right);
      Eigen::VectorXd q = Eigen::VectorXd::Zero(n), u = Eigen::VectorXd::Zero(n), u_free(n);
      BeamPointKinematics point;
      point.grad_w.resize(n);
      point.grad_dw.resize(n);
      beam->evaluate(x_left, q, point);
      const double dt     = setting.time_step;
      const BeamStep step = beam->free_velocity(0.5 * dt, q, u, dt, u_free);
      Eigen::MatrixXd X(n, 1);
      step.solve_iteration_matrix(point.grad_w, X);
      return 1. / point.grad_w.dot(X.col(0));
    }
  } // namespace

  std::vector<ImpactMass> impact_masses(const Scene &scene, const ImpactMassSettings &settings)
  {
    const double L       = scene.beam.length;
    const double x_C     = scene.initial.slider_position_over_L * L;
    const double x_left  = x_C - 0.5 * scene.slider.window_width;
    const double x_right = x_C + 0.5 * scene.slider.window_width;
    std::vector<ImpactMass> out;
    for (const std::string &formulation : settings.formulations)
      for (const unsigned int elements : settings.elements)
        for (const double dt : settings.time_steps)
          {
            Scene fe_scene                     = scene;
            fe_scene.time_stepping.fe_impulses = formulation;
            ModelSetting fe                    = scene_model(fe_scene, "fe");
            fe.n_elements                      = elements;
            fe.time_step                       = dt;
            out.push_back({formulation, elements, 0, dt, mass_under(fe_scene, fe, x_left, x_right)});
          }
    for (const unsigned int N : settings.modes)
      {
        // The explicit step's S is the identity: m = 1/Σφ_n(x)² at any Δt;
        // one below every N's stability limit here lets the model be built.
        ModelSetting rom = scene_model(scene, "rom");
        rom.n_modes      = N;
        rom.time_step    = 1e-8;
        out.push_back({"ROM explicit", 0, N, 0., mass_under(scene, rom, x_left, x_right)});
      }
    return out;
  }

  double observed_order(const double m_h, const double m_h2, const double m_h4)
  {
    const double d1 = std::abs(m_h - m_h2), d2 = std::abs(m_h2 - m_h4);
    if (d1 <= 1e-9 * std::abs(m_h4) && d2 <= 1e-9 * std::abs(m_h4))
      return std::numeric_limits<double>::quiet_NaN();
    return std::log2(d1 / d2);
  }
} // namespace beamslider
