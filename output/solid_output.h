// ParaView output of the solid strip: displacement fields (modes, static
// deformations) as one .vtu piece per MPI rank and a .pvtu record that
// ParaView opens as one data set.
#pragma once

#include "fem/solid_model.h"

#include <string>
#include <utility>
#include <vector>

namespace beamslider
{
  // Writes folder/basename.pvtu (and basename_NNNN.vtu pieces) with one
  // displacement vector field per (name, ghosted vector) pair, each scaled
  // by its factor (the caller says which in its CSV), and the cells' owning
  // rank. Collective: every
  // rank calls it. Returns the .pvtu path; throws OutputError when a file
  // cannot be written.
  struct SolidField
  {
    std::string name;
    const dealii::PETScWrappers::MPI::Vector *displacement; // ghosted
    double scale = 1.;
  };
  template <int dim>
  std::string write_solid_fields(const SolidModel<dim> &model, const std::vector<SolidField> &fields,
                                 const std::string &folder, const std::string &basename);
} // namespace beamslider
