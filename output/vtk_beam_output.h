// VTK output of beam shapes for ParaView. The beam is drawn as a 2D strip
// with its thickness, in the x–z plane (x along the beam, z transverse):
// points (x, 0, z) for z = ±h/2 at several x per element, quads between them.
// A displacement field (u − z w', 0, w) per shape is attached as point data,
// so that ParaView's "Warp By Vector" shows the deformed beam (Euler–Bernoulli
// kinematics: plane sections stay normal to the axis).
#pragma once

#include "fem/fe_beam.h"

#include <deal.II/lac/vector.h>

#include <string>
#include <vector>

namespace beamslider
{
  struct NamedShape
  {
    std::string name;             // the point-data array name, e.g. "mode_1"
    dealii::Vector<double> shape; // FE DoF vector
    double scale = 1.;            // multiplies the displacement (written to the file)
  };

  // Writes `filename` (.vtu) with one displacement array per shape and field
  // data "scale_<name>" holding the scale factor applied, plus any extra
  // field data (name, value) given.
  void write_beam_shapes_vtu(const FEBeam &beam, const std::vector<NamedShape> &shapes, const std::string &filename,
                             const std::vector<std::pair<std::string, double>> &field_data = {},
                             unsigned int samples_per_element = 8);
} // namespace beamslider
