// Slider corners, gaps and force directions: see slider_contact.h for the
// model (doc/physics.md §4).
#include "contact/slider_contact.h"

#include "numerics/spring_dashpot_restitution.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  SliderParameters SliderParameters::from_scene(const Scene &scene)
  {
    SliderParameters p;
    p.mass          = scene.slider_mass();
    p.inertia       = scene.slider_inertia();
    p.window_width  = scene.slider.window_width;
    p.window_height = scene.window_height();
    p.com_offset    = scene.slider.com_offset;
    p.gravity       = scene.contact.gravity;
    return p;
  }

  ContactLaw ContactLaw::from_scene(const Scene &scene)
  {
    ContactLaw law;
    law.friction_coefficient = scene.contact.friction_coefficient;
    law.restitution          = scene.contact.restitution;
    law.normal_stiffness     = scene.contact.normal_stiffness;
    if (law.compliant())
      {
        // Half the slider's mass on each of the two corners it lands on.
        const double zeta   = pushing_spring_dashpot_damping_ratio(law.restitution);
        law.normal_damping = 2. * zeta * std::sqrt(law.normal_stiffness * 0.5 * scene.slider_mass());
      }
    return law;
  }

  void SliderParameters::validate(const double beam_thickness) const
  {
    auto require = [](const bool ok, const char *name, const double value, const char *range) {
      if (!ok)
        {
          std::ostringstream m;
          m << "slider parameter " << name << " = " << value << " is outside the allowed range " << range;
          throw std::invalid_argument(m.str());
        }
    };
    require(mass > 0, "mass m [kg]", mass, "(0, inf)");
    require(inertia > 0, "inertia J_C [kg m^2]", inertia, "(0, inf)");
    require(window_width > 0, "window width B [m]", window_width, "(0, inf)");
    require(window_height > beam_thickness, "window height R [m]", window_height,
            "(h, inf), the window must be taller than the beam thickness h");
    require(std::isfinite(com_offset), "centre of mass offset d [m]", com_offset, "finite");
    require(gravity >= 0, "gravity g [m/s^2]", gravity, "[0, inf)");
  }

  SliderGeometry::SliderGeometry(const SliderParameters &slider, const double beam_thickness)
    : slider_(slider)
  {
    slider_.validate(beam_thickness);
  }

  SliderFrame SliderGeometry::frame(const double t, const BaseExcitation &base, const double beta)
  {
    SliderFrame f;
    f.beta              = beta;
    f.cos_beta          = std::cos(beta);
    f.sin_beta          = std::sin(beta);
    base.displacement_and_velocity(t, f.base_displacement, f.base_velocity);
    return f;
  }

  Eigen::Vector2d SliderGeometry::corner_offset(const unsigned int k, const double beta) const
  {
    SliderFrame f;
    f.cos_beta = std::cos(beta);
    f.sin_beta = std::sin(beta);
    return corner_offset(k, f);
  }

  Eigen::Vector2d SliderGeometry::corner_offset(const unsigned int k, const SliderFrame &f) const
  {
    // Corner in the slider frame, measured from the centre of mass C = S − (0, d).
    const double px = corner_side(k) * 0.5 * slider_.window_width;
    const double pz = corner_zeta(k) * 0.5 * slider_.window_height + slider_.com_offset;
    const double cb = f.cos_beta, sb = f.sin_beta;
    return {cb * px - sb * pz, sb * px + cb * pz};
  }

  void SliderGeometry::evaluate(const unsigned int k, const double t, const BeamSystem &beam,
                                const BaseExcitation &base, const Eigen::VectorXd &q, const Eigen::Vector3d &s,
                                CornerKinematics &out) const
  {
    evaluate(k, frame(t, base, s[2]), beam, q, s, out);
  }

  void SliderGeometry::evaluate(const unsigned int k, const SliderFrame &f, const BeamSystem &beam,
                                const Eigen::VectorXd &q, const Eigen::Vector3d &s, CornerKinematics &out,
                                const CornerDetail detail) const
  {
    const double zeta        = corner_zeta(k);
    const Eigen::Vector2d r  = corner_offset(k, f);
    const double x_P         = s[0] + r[0];
    const double z_P         = s[1] + r[1];
    // w and w' first: an open corner needs no gradients. A model with local
    // kinematics gives them with their few gradient entries at once.
    const bool local = beam.has_local_kinematics();
    double w = 0, dw = 0;
    if (local)
      {
        beam.evaluate_local(x_P, q, local_point_);
        w  = local_point_.w;
        dw = local_point_.dw;
      }
    else
      beam.evaluate_displacement(x_P, q, w, dw);
    // The surface the corner meets is at ±h(x_P)/2; h is constant on each
    // element, so its slope does not enter the force directions.
    const double thickness = beam.thickness_at(x_P);

    const CornerContactGeometry g(zeta, z_P, f.base_displacement, w, dw, thickness);
    out.x         = x_P;
    out.thickness = thickness;
    out.gap       = g.gap();
    out.n_local   = 0;
    if (detail == CornerDetail::for_step && out.gap > 0.)
      return;

    const double n_x = g.normal_x(), n_z = g.normal_z();
    const double t_x = g.tangent_x(), t_z = g.tangent_z();
    const double dg_dw = g.dgap_dw(), dg_ddw = g.dgap_ddw();
    const double dt_dw = g.dtangent_dw(), dt_ddw = g.dtangent_ddw();
    if (local)
      {
        out.n_local = local_point_.n;
        for (unsigned int a = 0; a < local_point_.n; ++a)
          {
            out.local_index[a]   = local_point_.index[a];
            out.local_normal[a]  = dg_dw * local_point_.grad_w[a] + dg_ddw * local_point_.grad_dw[a];
            out.local_tangent[a] = dt_ddw * local_point_.grad_dw[a] + dt_dw * local_point_.grad_w[a];
          }
        if (detail == CornerDetail::full)
          {
            out.beam_normal.setZero(beam.n_dofs());
            out.beam_tangent.setZero(beam.n_dofs());
            for (unsigned int a = 0; a < out.n_local; ++a)
              {
                out.beam_normal[out.local_index[a]] += out.local_normal[a];
                out.beam_tangent[out.local_index[a]] += out.local_tangent[a];
              }
          }
      }
    else
      {
        // The gradients (the w and w' above are the ones the gap used).
        beam.evaluate(x_P, q, point_);
        out.beam_normal  = dg_dw * point_.grad_w + dg_ddw * point_.grad_dw;
        out.beam_tangent = dt_ddw * point_.grad_dw + dt_dw * point_.grad_w;
      }

    // Slider part: v_P = (ẋ_C − β̇ r_z, ż_C + β̇ r_x).
    out.slider_normal  = Eigen::Vector3d(n_x, n_z, -r[1] * n_x + r[0] * n_z);
    out.slider_tangent = Eigen::Vector3d(t_x, t_z, -r[1] * t_x + r[0] * t_z);

    out.imposed_normal  = -n_z * f.base_velocity;
    out.imposed_tangent = -t_z * f.base_velocity;
  }

  Eigen::Vector3d SliderGeometry::resting_position(const double x_C, const double t, const BeamSystem &beam,
                                                   const BaseExcitation &base, const Eigen::VectorXd &q) const
  {
    beam.evaluate(x_C, q, point_);
    Eigen::Vector3d s(x_C, 0., std::atan(point_.dw));
    // The gap of an upper corner grows like c·z_C with the slider's height, so
    // each upper corner asks for z_C − g/c; the higher demand wins.
    CornerKinematics corner;
    double z_C = -std::numeric_limits<double>::infinity();
    for (unsigned int k = 0; k < 2; ++k)
      {
        evaluate(k, t, beam, base, q, s, corner);
        z_C = std::max(z_C, -corner.gap / corner.slider_normal[1]);
      }
    s[1] = z_C;
    // "Resting" means in contact: round-off may leave a gap of +1e-19 m, which
    // the Moreau step would treat as open for one free-fall step. Lower the
    // slider by a few ulps until both upper gaps are ≤ 0.
    for (unsigned int it = 0; it < 64; ++it)
      {
        double max_gap = -std::numeric_limits<double>::infinity();
        for (unsigned int k = 0; k < 2; ++k)
          {
            evaluate(k, t, beam, base, q, s, corner);
            max_gap = std::max(max_gap, corner.gap);
          }
        if (max_gap <= 0.)
          break;
        s[1] = std::nextafter(s[1], -std::numeric_limits<double>::infinity());
      }
    return s;
  }
} // namespace beamslider
