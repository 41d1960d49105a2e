// Reading a beam's elements from a Gmsh mesh (.msh, format 2 or 4, as
// deal.II's GridIn reads it): straight line elements along the x axis from
// x = 0 to x = L, each with the physical tag of its section.
#pragma once

#include "scene/scene.h"

#include <string>
#include <vector>

namespace beamslider
{
  // The text of a mesh file (beam or solid) through the guarded reader
  // (io/input_file.h: a regular file of at most InputLimits::mesh bytes);
  // InputError "<where> cannot be read: …" otherwise.
  std::string read_mesh_text(const std::string &path, const std::string &where);

  // The elements of the mesh in `path`, ordered from x = 0 to x = L.
  // Throws InputError naming the file and the defect when the file is
  // missing or unreadable, has elements other than lines (a 2D mesh), a node
  // off the x axis, an element whose x does not increase from its first node
  // to its second, a gap or an overlap between elements, or does not start
  // at x = 0.
  std::vector<BeamMeshCell> read_beam_mesh(const std::string &path);
} // namespace beamslider
