// The solid's coarse mesh: the generated strip (flat, or lifted into a
// shallow arch), or a mesh file a user brings (Gmsh .msh format 2 or 4,
// Abaqus .inp) read by deal.II's GridIn, with its physical groups resolved
// into the clamped faces, the loaded face and the material regions.
//
// A mesh file is checked before anything is built on it, and each problem
// is an InputError naming it: no cells of the scene's dimension (a surface
// mesh given to a 3d scene), hexahedra mixed with tetrahedra, an inverted
// or degenerate cell (a Jacobian determinant ≤ 0 somewhere in it), a clamped
// group no face carries, a cell region the Materials entry does not list, a
// Materials group no cell carries.
//
// Groups are named by Gmsh physical name (from the file's $PhysicalNames)
// or by tag (a number, the only way for .inp files, whose sets deal.II
// numbers). GridIn gives boundary faces their group's tag as boundary id
// (faces in no group get 0) and cells theirs as material id.
#pragma once

#include "scene/scene.h"

#include <deal.II/base/types.h>
#include <deal.II/grid/tria.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace beamslider
{
  // The SVK law's constants in one cell region.
  struct SolidMaterial
  {
    double lambda  = 0; // λ [Pa]: E ν / ((1 + ν)(1 − 2ν)) in 3D, E ν / (1 − ν²) in plane stress
    double mu      = 0; // μ = E / (2 (1 + ν)) [Pa]
    double density = 0; // ρ [kg/m^3]

    static SolidMaterial from(double youngs_modulus, double poissons_ratio, double density, int dim);
  };

  struct SolidMeshGroups
  {
    std::vector<dealii::types::boundary_id> clamped;   // faces held at u = 0
    std::optional<dealii::types::boundary_id> loaded;  // the top face of the line load, if the mesh has it
    std::map<dealii::types::material_id, SolidMaterial> materials; // by cell region
  };

  // Builds the scene's coarse mesh into `tria` (an empty serial or p4est
  // triangulation) and returns its groups. Generated strip: faces x = 0 and
  // x = L clamped (ids 0, 1), the top face loaded (id 2 dim − 1), material
  // id 0. Throws InputError for a mesh file that cannot serve (see above).
  template <int dim>
  SolidMeshGroups make_solid_mesh(const Scene &scene, dealii::Triangulation<dim> &tria);

  // The $PhysicalNames of a Gmsh file: name → (dimension, tag); empty for
  // a file without names (or an Abaqus file).
  std::map<std::string, std::pair<int, unsigned int>> gmsh_physical_names(const std::string &path);
} // namespace beamslider
