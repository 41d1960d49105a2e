// Reading a scene: its file and the --set overrides through the bound
// entries into a Scene, the beam completed from its tables or mesh file.
#include "io/input_file.h"
#include "scene/beam_mesh.h"
#include "scene/deal_ii_message.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "scene/scene_parameters_internal.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace beamslider
{
  namespace
  {
    using dealii::ParameterHandler;
    using internal::bind_scene;
    using internal::check_entries_unique;
    using internal::num;
    using internal::read_scene_text;
    using internal::require_recordable;
    using internal::SceneTables;
    using internal::SceneText;

    std::string info(const dealii::ExceptionBase &e) { return " " + deal_ii_message(e); }

    // Applies one "Section/Sub/Name=value" override.
    void apply_override(ParameterHandler &prm, const std::string &assignment)
    {
      const auto eq = assignment.find('=');
      if (eq == std::string::npos)
        throw InputError("--set \"" + assignment + "\": expected Section/Name=value");
      const std::string path  = assignment.substr(0, eq);
      const std::string value = assignment.substr(eq + 1);

      std::vector<std::string> parts;
      std::string::size_type start = 0, slash;
      while ((slash = path.find('/', start)) != std::string::npos)
        {
          parts.push_back(path.substr(start, slash - start));
          start = slash + 1;
        }
      const std::string entry = path.substr(start);
      if (parts.empty())
        throw InputError("--set \"" + assignment + "\": the parameter must be given with its section, e.g. Beam/Thickness=1e-3");

      for (const auto &p : parts)
        prm.enter_subsection(p);
      try
        {
          prm.set(entry, value);
        }
      catch (const ParameterHandler::ExcEntryUndeclared &)
        {
          throw InputError("--set: unknown parameter '" + path + "' (see the scene template for the valid names)");
        }
      catch (const ParameterHandler::ExcValueDoesNotMatchPattern &e)
        {
          throw InputError("--set: parameter '" + path + "' = '" + value + "' is outside its allowed range:" + info(e));
        }
      for (std::size_t i = 0; i < parts.size(); ++i)
        prm.leave_subsection();
    }

    // "Section/Sub/Name" of an override, without the value.
    std::string override_path(const std::string &assignment)
    {
      return assignment.substr(0, assignment.find('='));
    }

    std::string tag_list(const std::set<unsigned int> &tags)
    {
      std::string text;
      for (const unsigned int t : tags)
        text += (text.empty() ? "" : ", ") + std::to_string(t);
      return text;
    }

    // Completes the beam from the tables: its point bodies and, with a mesh
    // file (taken relative to the scene file), its elements, its sections
    // and the length and reference section they imply. `set_keys` are the
    // parameters the file or an override sets: with a mesh, an entry of the
    // uniform section that says something else than the mesh is refused.
    void build_beam(Scene &s, const SceneTables &t, const std::string &scene_file, const std::set<std::string> &set_keys)
    {
      BeamData &b = s.beam;
      for (const auto &[x, m] : t.masses)
        b.point_masses.push_back({x, m, t.inertias.count(x) ? t.inertias.at(x) : 0.});
      for (const auto &[x, J] : t.inertias)
        if (!t.masses.count(x))
          b.point_masses.push_back({x, 0., J});
      std::sort(b.point_masses.begin(), b.point_masses.end(),
                [](const PointMass &l, const PointMass &r) { return l.position < r.position; });

      if (b.mesh_file.empty())
        {
          for (const auto &[name, table] : t.sections)
            if (!table.empty())
              throw InputError("Parameter 'Sections/" + name + "' is set, but 'Beam/Mesh file' is empty: sections "
                               "belong to a beam read from a mesh (set Beam/Mesh file, or remove the Sections entries)");
          return;
        }

      namespace fs = std::filesystem;
      fs::path mesh(b.mesh_file);
      if (mesh.is_relative())
        mesh = fs::absolute(fs::path(scene_file).parent_path() / mesh);
      b.mesh_file  = mesh.lexically_normal().string();
      b.mesh_cells = read_beam_mesh(b.mesh_file);

      std::set<unsigned int> tags;
      for (const BeamMeshCell &c : b.mesh_cells)
        tags.insert(c.tag);
      for (const std::string name : {"Width", "Thickness", "Young's modulus", "Density"}) // the file's order
        {
          const std::map<unsigned int, double> &table = t.sections.at(name);
          for (const unsigned int tag : tags)
            if (!table.count(tag))
              throw InputError("Parameter 'Sections/" + name + "' has no value for physical tag " + std::to_string(tag) +
                               " of the mesh '" + b.mesh_file + "' (its tags: " + tag_list(tags) +
                               "); give 'tag: value' for every tag");
          for (const auto &entry : table)
            if (!tags.count(entry.first))
              throw InputError("Parameter 'Sections/" + name + "' gives a value for tag " + std::to_string(entry.first) +
                               ", which no element of the mesh '" + b.mesh_file + "' carries (its tags: " +
                               tag_list(tags) + ")");
        }
      for (const unsigned int tag : tags)
        b.sections[tag] = {t.sections.at("Width").at(tag), t.sections.at("Thickness").at(tag),
                           t.sections.at("Young's modulus").at(tag), t.sections.at("Density").at(tag)};

      // The mesh decides Length and (unless set) Number of elements; both
      // must lie in their patterns, which parameters.prm is written with.
      const double mesh_length = b.mesh_cells.back().x_end;
      if (!(mesh_length >= 1e-3 && mesh_length <= 10))
        throw InputError("Mesh file '" + printable(b.mesh_file) + "': the beam is " + num(mesh_length) +
                         " m long; 'Beam/Length', the mesh's length, must be in [1e-3, 10] m");
      if (!set_keys.count("Discretisation/Number of elements") && b.mesh_cells.size() > 4096)
        throw InputError("Mesh file '" + printable(b.mesh_file) + "' has " + std::to_string(b.mesh_cells.size()) +
                         " elements; 'Discretisation/Number of elements', the mesh's unless set, must be in [1, 4096]");

      // Length and the reference (thickest) section follow from the mesh.
      BeamSection thickest = b.sections.begin()->second;
      for (const auto &[tag, section] : b.sections)
        if (section.thickness > thickest.thickness)
          thickest = section;
      const std::array<std::tuple<const char *, double *, double>, 5> derived{
        {{"Length", &b.length, b.mesh_cells.back().x_end},
         {"Width", &b.width, thickest.width},
         {"Thickness", &b.thickness, thickest.thickness},
         {"Young's modulus", &b.youngs_modulus, thickest.youngs_modulus},
         {"Density", &b.density, thickest.density}}};
      for (const auto &[name, field, value] : derived)
        {
          if (set_keys.count(std::string("Beam/") + name) && *field != value)
            throw InputError("Parameter 'Beam/" + std::string(name) + "' = " + num(*field) +
                             " is not allowed with 'Beam/Mesh file': a mesh beam's " + name + " is " +
                             (std::string(name) == "Length" ? "the mesh's length, " : "its thickest section's, ") +
                             num(value) + "; remove the entry");
          *field = value;
        }
      if (!set_keys.count("Discretisation/Number of elements"))
        s.discretisation.n_elements = b.mesh_cells.size();
    }

    // Solid/Mesh file, relative to the scene file, made absolute; a missing
    // or unreadable file is refused here, its content by fem/solid_mesh.
    void resolve_solid_mesh(Scene &s, const std::string &scene_file)
    {
      if (s.solid.mesh_file.empty())
        return;
      namespace fs = std::filesystem;
      fs::path mesh(s.solid.mesh_file);
      if (mesh.is_relative())
        mesh = fs::absolute(fs::path(scene_file).parent_path() / mesh);
      s.solid.mesh_file = mesh.lexically_normal().string();
      std::error_code ec;
      if (!fs::is_regular_file(mesh, ec))
        throw InputError("Parameter 'Solid/Mesh file': '" + s.solid.mesh_file + "'" +
                         (fs::exists(mesh, ec) ? " is not a regular file" : " does not exist") +
                         " (a path relative to the scene file)");
      if (!std::ifstream(mesh))
        throw InputError("Parameter 'Solid/Mesh file': '" + s.solid.mesh_file + "' cannot be opened (unreadable)");
    }
  } // namespace

  void check_overrides_unique(const std::vector<std::string> &overrides)
  {
    std::map<std::string, std::string> seen;
    for (const auto &o : overrides)
      {
        const auto [it, inserted] = seen.emplace(override_path(o), o);
        if (!inserted)
          throw InputError("--set \"" + o + "\": '" + it->first + "' is already set by --set \"" + it->second +
                           "\"; give each parameter once");
      }
  }

  std::string deal_ii_message(const dealii::ExceptionBase &e)
  {
    std::ostringstream s;
    e.print_info(s);
    // One line: deal.II indents and breaks its message.
    std::string line;
    for (const char c : s.str())
      if (!std::isspace(static_cast<unsigned char>(c)))
        line += c;
      else if (!line.empty() && line.back() != ' ')
        line += ' ';
    while (!line.empty() && line.back() == ' ')
      line.pop_back();
    // A reader's message may quote what it read (a binary file's bytes).
    return printable(line, 400);
  }

  Scene read_scene(const std::string &filename, const std::vector<std::string> &overrides)
  {
    const SceneText text = read_scene_text(filename);
    std::set<std::string> set_keys = check_entries_unique(filename, text);
    check_overrides_unique(overrides);
    for (const auto &o : overrides)
      set_keys.insert(override_path(o));

    ParameterHandler prm;
    Scene s;
    SceneTables tables;
    bind_scene(prm, s, tables);
    try
      {
        std::istringstream in(text.text);
        prm.parse_input(in, filename);
      }
    catch (const dealii::ExceptionBase &e)
      {
        // deal.II counts the lines of the expanded text: name the file and
        // the line they come from instead.
        // (Most of deal.II's messages close the file's name with '>', its
        // "no such subsection" does not.)
        const std::string message = deal_ii_message(e);
        std::smatch m;
        if (std::regex_search(message, m, std::regex("^Line <([0-9]+)> of file <")))
          {
            std::string rest = m.suffix();
            if (rest.compare(0, filename.size(), filename) == 0)
              rest.erase(0, filename.size());
            rest.erase(0, rest.find_first_not_of(">: "));
            throw InputError(text.where(std::stoul(m[1])) + ": " + printable(rest, 400));
          }
        throw InputError("Scene file '" + printable(filename) + "': " + printable(message, 400));
      }
    for (const auto &o : overrides)
      apply_override(prm, o);
    require_recordable(s); // as given, before a path is opened; validate_scene checks the resolved paths

    build_beam(s, tables, filename, set_keys);
    resolve_solid_mesh(s, filename);
    const auto slash = filename.find_last_of('/');
    s.name           = filename.substr(slash == std::string::npos ? 0 : slash + 1);
    if (const auto dot = s.name.rfind(".prm"); dot != std::string::npos)
      s.name.erase(dot);
    validate_scene(s);
    return s;
  }
} // namespace beamslider
