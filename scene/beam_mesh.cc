// Beam meshes from Gmsh: deal.II's GridIn reads the file into a line mesh in
// 3D space (so that a node off the x axis shows up instead of being dropped);
// the checks below turn what a beam mesh must be into clear errors.
#include "scene/beam_mesh.h"

#include "io/input_file.h"
#include "scene/number_with_digits.h"
#include "scene/printable.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

namespace beamslider
{
  namespace
  {
    std::string number(const double x) { return number_with_digits(x, 10); }

    // The first line of a deal.II exception's explanation, without the
    // banner of source files and line numbers.
    std::string reason(const dealii::ExceptionBase &e)
    {
      std::ostringstream s;
      e.print_info(s);
      std::string text = s.str();
      const auto b = text.find_first_not_of(" \n\t");
      text         = b == std::string::npos ? std::string() : text.substr(b);
      const auto dot = text.find('\n');
      std::string line = text.substr(0, dot);
      // deal.II breaks its sentences over lines: take the first sentence whole.
      for (std::size_t i = dot; i != std::string::npos && line.find('.') == std::string::npos;)
        {
          const auto next = text.find('\n', i + 1);
          const std::string part = text.substr(i + 1, next == std::string::npos ? std::string::npos : next - i - 1);
          const auto pb          = part.find_first_not_of(" \t");
          if (pb == std::string::npos)
            break;
          line += " " + part.substr(pb);
          i = next;
        }
      // The reader quotes what it read: a binary file's bytes.
      return printable(line, 200);
    }
  } // namespace

  std::string read_mesh_text(const std::string &path, const std::string &where)
  {
    try
      {
        return read_text_file(path, InputLimits::mesh);
      }
    catch (const FileReadError &e)
      {
        throw InputError(where + " cannot be read: " + e.what());
      }
  }

  std::vector<BeamMeshCell> read_beam_mesh(const std::string &path)
  {
    namespace fs = std::filesystem;
    const std::string where = "Mesh file '" + path + "'";
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
      throw InputError(where + (fs::exists(path, ec) ? " is not a regular file" : " does not exist") +
                       " (Beam/Mesh file, a path relative to the scene file)");
    std::istringstream in(read_mesh_text(path, where));

    dealii::Triangulation<1, 3> mesh;
    try
      {
        dealii::GridIn<1, 3> reader;
        reader.attach_triangulation(mesh);
        reader.read_msh(in);
      }
    catch (const dealii::ExceptionBase &e)
      {
        throw InputError(where + " is not a beam mesh that deal.II's Gmsh reader accepts: " + reason(e) +
                         " A beam mesh has line elements (Gmsh type 1) only, along x; a 2D or 3D mesh is not one.");
      }
    catch (const std::exception &e)
      {
        throw InputError(where + " cannot be read as a Gmsh mesh: " + e.what());
      }
    if (mesh.n_active_cells() == 0)
      throw InputError(where + " has no line elements");

    std::vector<BeamMeshCell> cells;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        const auto a = cell->vertex(0), b = cell->vertex(1);
        for (const auto &p : {a, b})
          if (p[1] != 0. || p[2] != 0.)
            throw InputError(where + ": the node at (" + number(p[0]) + ", " + number(p[1]) + ", " + number(p[2]) +
                             ") m is off the x axis; a beam mesh has its nodes on the x axis (y = z = 0)");
        if (!(b[0] > a[0]))
          throw InputError(where + ": an element runs from x = " + number(a[0]) + " m to x = " + number(b[0]) +
                           " m; x must increase from an element's first node to its second (and an element must "
                           "have a length)");
        // GridIn reads a physical tag as unsigned: -1 arrives as 4294967295.
        const auto tag = static_cast<unsigned int>(cell->material_id());
        if (tag > static_cast<unsigned int>(std::numeric_limits<int>::max()))
          throw InputError(where + ": the element from x = " + number(a[0]) + " m to x = " + number(b[0]) +
                           " m has the physical tag " + std::to_string(static_cast<int>(tag)) +
                           "; a physical tag is a number >= 0");
        cells.push_back({a[0], b[0], tag});
      }
    std::sort(cells.begin(), cells.end(), [](const auto &l, const auto &r) { return l.x_begin < r.x_begin; });

    if (cells.front().x_begin != 0.)
      throw InputError(where + ": the beam starts at x = " + number(cells.front().x_begin) +
                       " m; it must start at x = 0 (the left support)");
    for (std::size_t i = 1; i < cells.size(); ++i)
      {
        const double end = cells[i - 1].x_end, begin = cells[i].x_begin;
        if (begin > end)
          throw InputError(where + ": a gap between elements from x = " + number(end) + " m to x = " + number(begin) +
                           " m; the elements must join end to end");
        if (begin < end)
          throw InputError(where + ": elements overlap from x = " + number(begin) + " m to x = " + number(end) +
                           " m; the elements must join end to end");
      }
    return cells;
  }
} // namespace beamslider
