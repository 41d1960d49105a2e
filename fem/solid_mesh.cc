#include "fem/solid_mesh.h"

#include "scene/beam_mesh.h"
#include "scene/deal_ii_message.h"
#include "scene/number_with_digits.h"
#include "scene/printable.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace beamslider
{
  using namespace dealii;

  SolidMaterial SolidMaterial::from(const double E, const double nu, const double rho, const int dim)
  {
    SolidMaterial m;
    m.mu      = E / (2 * (1 + nu));
    m.lambda  = dim == 2 ? E * nu / (1 - nu * nu) : E * nu / ((1 + nu) * (1 - 2 * nu));
    m.density = rho;
    return m;
  }

  std::map<std::string, std::pair<int, unsigned int>> gmsh_physical_names(const std::string &path)
  {
    std::map<std::string, std::pair<int, unsigned int>> names;
    std::istringstream in(read_mesh_text(path, "Solid mesh '" + path + "'"));
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("$PhysicalNames", 0) == 0)
        {
          std::size_t n = 0;
          in >> n;
          for (std::size_t i = 0; i < n && in; ++i)
            {
              // Signed: an unsigned read would take -1 for 4294967295.
              int d = 0, tag = 0;
              in >> d >> tag;
              std::getline(in, line);
              const auto a = line.find('"'), b = line.rfind('"');
              if (in && tag < 0)
                throw InputError("Solid mesh '" + path + "': $PhysicalNames gives the group '" +
                                 printable(a != std::string::npos && b > a ? line.substr(a + 1, b - a - 1) : line, 80) +
                                 "' the tag " + std::to_string(tag) + "; a physical tag is a number >= 0");
              if (a != std::string::npos && b > a)
                names[line.substr(a + 1, b - a - 1)] = {d, static_cast<unsigned int>(tag)};
            }
          break;
        }
    return names;
  }

  namespace
  {
    std::string number(const double x) { return number_with_digits(x, 6); }

    template <int dim>
    std::string at(const Point<dim> &p)
    {
      std::string text = "(";
      for (unsigned int d = 0; d < dim; ++d)
        text += (d ? ", " : "") + number(p[d]);
      return text + ") m";
    }

    // The generated strip, clamped faces x = 0 and x = L (ids 0, 1), top
    // face id 2 dim − 1 (colorize); an arch lifts every point by z₀(x).
    template <int dim>
    void make_strip(Triangulation<dim> &tria, const BeamData &beam, const SolidData &solid)
    {
      std::vector<unsigned int> cells{solid.elements_along_length};
      Point<dim> lower, upper;
      lower[0] = 0;
      upper[0] = beam.length;
      if (dim == 3)
        {
          cells.push_back(solid.elements_across_width);
          lower[1] = -0.5 * beam.width;
          upper[1] = 0.5 * beam.width;
        }
      cells.push_back(solid.elements_through_thickness);
      lower[dim - 1] = -0.5 * beam.thickness;
      upper[dim - 1] = 0.5 * beam.thickness;
      GridGenerator::subdivided_hyper_rectangle(tria, cells, lower, upper, true);
      for (const auto &cell : tria.active_cell_iterators()) // colorize numbers the cells too
        cell->set_material_id(0);
      if (solid.arch_rise > 0)
        {
          // Vertical shift: every cross-section x = const stays a section
          // of thickness h, so the mid-span section and the top-face load
          // keep their meaning on the arch.
          const double rise = solid.arch_rise, L = beam.length;
          GridTools::transform(
            [rise, L](const Point<dim> &p) {
              Point<dim> q = p;
              q[dim - 1] += rise * std::sin(M_PI * p[0] / L);
              return q;
            },
            tria);
        }
    }

    // A group given by name or by tag → its tag; InputError if unknown.
    unsigned int resolve_group(const std::string &spec, const int group_dim,
                               const std::map<std::string, std::pair<int, unsigned int>> &names,
                               const std::string &parameter, const std::string &mesh)
    {
      if (!spec.empty() && spec.find_first_not_of("0123456789") == std::string::npos)
        return static_cast<unsigned int>(std::stoul(spec));
      const auto it = names.find(spec);
      if (it != names.end() && it->second.first == group_dim)
        return it->second.second;
      std::string known;
      for (const auto &[name, entry] : names)
        if (entry.first == group_dim)
          known += (known.empty() ? "" : ", ") + ("'" + name + "' (tag " + std::to_string(entry.second) + ")");
      throw InputError("Parameter '" + parameter + "' names the physical group '" + spec + "', which the mesh '" +
                       mesh + "' does not have among its " + std::to_string(group_dim) + "D groups (" +
                       (known.empty() ? std::string("it has no named ones; give tags") : "it has " + known) + ")");
    }

    // Every cell's Jacobian determinant must be positive at its vertices
    // and its Gauss points (GridIn has already turned cells whose vertices
    // were listed in the mirrored order; what is left is a cell folded over
    // itself or flat). J(ξ) = Σ_v x_v ⊗ ∇N_v(ξ) with the linear element's
    // shape functions, whose v-th belongs to vertex v.
    template <int dim>
    void check_cells(const Triangulation<dim> &tria, const std::string &where)
    {
      const bool simplex = tria.all_reference_cells_are_simplex();
      std::unique_ptr<FiniteElement<dim>> fe;
      std::vector<Point<dim>> points;
      if (simplex)
        {
          fe     = std::make_unique<FE_SimplexP<dim>>(1);
          points = QGaussSimplex<dim>(1).get_points(); // affine: one point tells
        }
      else
        {
          fe     = std::make_unique<FE_Q<dim>>(1);
          points = fe->get_unit_support_points(); // the vertices
          const QGauss<dim> gauss(2);
          points.insert(points.end(), gauss.get_points().begin(), gauss.get_points().end());
        }
      unsigned int index = 0;
      for (const auto &cell : tria.active_cell_iterators())
        {
          const double scale = std::pow(cell->diameter(), dim);
          for (const Point<dim> &xi : points)
            {
              Tensor<2, dim> J;
              for (unsigned int v = 0; v < cell->n_vertices(); ++v)
                J += outer_product(Tensor<1, dim>(cell->vertex(v)), fe->shape_grad(v, xi));
              const double det = determinant(J);
              if (!(det > 1e-8 * scale))
                throw InputError(where + ": cell " + std::to_string(index) + " (centre " + at(cell->center()) +
                                 ") is " + (det < -1e-8 * scale ? "inverted (folded over itself)" : "degenerate (flat)") +
                                 ": its Jacobian determinant is " + number(det) + " at a point where a valid cell has > 0");
            }
          ++index;
        }
    }

    // The text deal.II's Abaqus reader printed before it threw: the lines
    // after "Additional information:" up to the first blank one, joined.
    std::string reader_explanation(const std::string &reader_output)
    {
      std::string inner;
      std::istringstream printed(reader_output);
      bool explanation = false;
      for (std::string line; std::getline(printed, line);)
        {
          const auto b = line.find_first_not_of(" \t");
          if (explanation && b == std::string::npos && !inner.empty())
            break;
          if (explanation && b != std::string::npos)
            inner += (inner.empty() ? "" : " ") + line.substr(b);
          explanation = explanation || line.find("Additional information:") != std::string::npos;
        }
      return printable(inner, 300);
    }

    // Reads the Gmsh or Abaqus file at `path` into `tria` with GridIn; a
    // file it does not take is an InputError (`where`: the file, `kind`: the
    // mesh the scene expects).
    template <int dim>
    void read_with_grid_in(const std::string &path, const bool abaqus, const std::string &where,
                           const std::string &kind, Triangulation<dim> &tria)
    {
      // GridIn reads into a serial triangulation; the caller distributes it.
      std::istringstream in(read_mesh_text(path, where));
      // deal.II's Abaqus reader prints the exception of its inner UCD step,
      // stack trace and all, to std::cerr before it throws a generic one:
      // kept here, and its "Additional information" goes into the one line.
      std::ostringstream reader_output;
      struct RestoreCerr
      {
        std::streambuf *buffer;
        ~RestoreCerr() { std::cerr.rdbuf(buffer); }
      } restore{std::cerr.rdbuf(reader_output.rdbuf())};
      try
        {
          GridIn<dim> reader;
          reader.attach_triangulation(tria);
          if (abaqus)
            reader.read_abaqus(in);
          else
            reader.read_msh(in);
        }
      catch (const ExceptionBase &e)
        {
          const std::string inner = reader_explanation(reader_output.str());
          // (The Abaqus reader's own text points to the message "printed above".)
          const std::string reason =
            abaqus && !inner.empty() ? "converting the deck failed: " + inner + " (a truncated or incomplete deck?)"
                                     : deal_ii_message(e);
          throw InputError(where + " is not a " + kind + " solid mesh that deal.II's " +
                           (abaqus ? "Abaqus" : "Gmsh") + " reader accepts: " + reason);
        }
      catch (const std::exception &e)
        {
          throw InputError(where + " cannot be read: " + e.what());
        }
    }

    using PhysicalNames = std::map<std::string, std::pair<int, unsigned int>>;

    // The physical tags a mesh carries: on its boundary faces, on its cells.
    struct MeshTags
    {
      std::set<types::boundary_id> faces;
      std::set<types::material_id> cells;
    };

    template <int dim>
    MeshTags collect_physical_tags(const Triangulation<dim> &tria, const std::string &where)
    {
      MeshTags tags;
      // GridIn reads a physical tag as unsigned: -1 arrives as 4294967295.
      const auto require_tag = [&where](const unsigned int id, const std::string &of) {
        if (id > static_cast<unsigned int>(std::numeric_limits<int>::max()))
          throw InputError(where + ": " + of + " has the physical tag " + std::to_string(static_cast<int>(id)) +
                           "; a physical tag is a number >= 0");
      };
      for (const auto &cell : tria.active_cell_iterators())
        {
          require_tag(cell->material_id(), "the cell at " + at(cell->center()));
          tags.cells.insert(cell->material_id());
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              {
                require_tag(face->boundary_id(), "the boundary face at " + at(face->center()));
                tags.faces.insert(face->boundary_id());
              }
        }
      return tags;
    }

    // The clamped faces (each must be on the mesh's boundary) and the loaded face, if any.
    template <int dim>
    void resolve_boundary_groups(const SolidData &solid, const PhysicalNames &names, const MeshTags &tags,
                                 SolidMeshGroups &groups)
    {
      const std::string &path = solid.mesh_file;
      for (const std::string &spec : solid.clamped_boundaries)
        {
          const unsigned int tag = resolve_group(spec, dim - 1, names, "Solid/Clamped boundaries", path);
          if (tag == 0 || !tags.faces.count(tag))
            throw InputError("Parameter 'Solid/Clamped boundaries': no boundary face of the mesh '" + path +
                             "' carries the group '" + spec + "' (tag " + std::to_string(tag) +
                             "); a solid mesh needs its clamped faces in a physical group");
          groups.clamped.push_back(tag);
        }
      // The loaded face only matters to statics, which says so if it is missing.
      if (!solid.loaded_boundary.empty())
        try
          {
            const unsigned int tag = resolve_group(solid.loaded_boundary, dim - 1, names, "Solid/Loaded boundary", path);
            if (tag != 0 && tags.faces.count(tag))
              groups.loaded = tag;
          }
        catch (const InputError &)
          {}
    }

    // Each cell region's material: the Materials entry of its group, or
    // without entries the Beam's E and rho with the solid's nu.
    template <int dim>
    void assign_materials(const Scene &scene, const PhysicalNames &names, const MeshTags &tags,
                          SolidMeshGroups &groups)
    {
      const SolidData &solid = scene.solid;
      const std::string &path = solid.mesh_file;
      if (solid.materials.empty())
        {
          for (const types::material_id id : tags.cells)
            groups.materials[id] = SolidMaterial::from(scene.beam.youngs_modulus, solid.poissons_ratio,
                                                       scene.beam.density, dim);
          return;
        }
      // The entries are checked (numbers, ranges, no group twice) with the
      // scene; here a name and a tag may still give one region twice.
      std::map<types::material_id, std::string> given_as;
      for (const SolidMaterialEntry &m : solid_material_entries(solid.materials))
        {
          const unsigned int tag = resolve_group(m.group, dim, names, "Solid/Materials", path);
          if (!tags.cells.count(tag))
            throw InputError("Parameter 'Solid/Materials' gives the region '" + printable(m.group) + "' (tag " +
                             std::to_string(tag) + "), which no cell of the mesh '" + path + "' carries");
          if (const auto [it, inserted] = given_as.emplace(tag, m.group); !inserted)
            throw InputError("Parameter 'Solid/Materials' gives the region of tag " + std::to_string(tag) +
                             " twice, as '" + printable(it->second) + "' and as '" + printable(m.group) +
                             "'; give each region once");
          groups.materials[tag] = SolidMaterial::from(m.youngs_modulus, m.poissons_ratio, m.density, dim);
        }
      for (const types::material_id id : tags.cells)
        if (!groups.materials.count(id))
          throw InputError("Solid mesh '" + path + "': cells of region " + std::to_string(id) +
                           " have no material: 'Solid/Materials' = '" + solid.materials +
                           "' lists no 'group: E nu rho' entry for that region's name or tag");
    }

    template <int dim>
    SolidMeshGroups read_mesh_file(const Scene &scene, Triangulation<dim> &tria)
    {
      const SolidData &solid = scene.solid;
      const std::string &path = solid.mesh_file;
      const std::string where = "Solid mesh '" + path + "'";
      const bool abaqus = path.size() > 4 && path.compare(path.size() - 4, 4, ".inp") == 0;
      const std::string kind = dim == 3 ? "3D (hexahedra or tetrahedra, for Continuum = 3d)"
                                        : "2D (quadrilaterals or triangles, for Continuum = plane stress)";
      read_with_grid_in(path, abaqus, where, kind, tria);
      if (tria.n_active_cells() == 0)
        throw InputError(where + " has no " + kind + " cells: a mesh of another dimension?");
      if (!tria.all_reference_cells_are_hyper_cube() && !tria.all_reference_cells_are_simplex())
        throw InputError(where + " mixes cell types (hexahedra with tetrahedra, or prisms/pyramids): give one "
                                 "kind, all " + std::string(dim == 3 ? "hexahedra or all tetrahedra" :
                                                                        "quadrilaterals or all triangles"));
      check_cells(tria, where);

      const auto names = abaqus ? PhysicalNames() : gmsh_physical_names(path);
      const MeshTags tags = collect_physical_tags(tria, where);
      SolidMeshGroups groups;
      resolve_boundary_groups<dim>(solid, names, tags, groups);
      assign_materials<dim>(scene, names, tags, groups);
      return groups;
    }
  } // namespace

  template <int dim>
  SolidMeshGroups make_solid_mesh(const Scene &scene, Triangulation<dim> &tria)
  {
    if (scene.solid.from_mesh())
      return read_mesh_file(scene, tria);
    make_strip(tria, scene.beam, scene.solid);
    SolidMeshGroups groups;
    groups.clamped = {0, 1};
    groups.loaded  = 2 * dim - 1;
    groups.materials[0] =
      SolidMaterial::from(scene.beam.youngs_modulus, scene.solid.poissons_ratio, scene.beam.density, dim);
    return groups;
  }

  template SolidMeshGroups make_solid_mesh(const Scene &, Triangulation<2> &);
  template SolidMeshGroups make_solid_mesh(const Scene &, Triangulation<3> &);
} // namespace beamslider
