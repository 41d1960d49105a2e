// Loads on the FE beam that several tests share.
#pragma once

#include "fem/fe_beam.h"
#include "scene/scene.h"

#include <deal.II/lac/vector.h>

namespace beamslider::testing
{
  // The slider's weight m g, shared equally by its two upper window corners
  // at x_C ± B/2, as consistent nodal forces of the FE beam [N, N m] (zero on
  // the constrained DoFs): the static load of a slider resting on the beam.
  inline dealii::Vector<double> slider_weight_load(const FEBeam &beam, const Scene &scene, const double x_C)
  {
    dealii::Vector<double> F(beam.n_dofs());
    const double weight = scene.slider_mass() * scene.contact.gravity, B = scene.slider.window_width;
    for (const double xp : {x_C - 0.5 * B, x_C + 0.5 * B})
      {
        const FEPointShape p = beam.point_shape(xp);
        for (unsigned int a = 0; a < 4; ++a)
          F[p.w_dofs[a]] -= 0.5 * weight * p.w_values[a];
      }
    beam.constraints().set_zero(F);
    return F;
  }
} // namespace beamslider::testing
