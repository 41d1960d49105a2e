// Reading and checking scene files (meshes/*.prm) with deal.II's
// ParameterHandler. Every entry is declared once, in bind_scene(), with a
// typed pattern, a documentation string that gives its unit (so that
// `scene_template()` writes a self-documenting file) and the Scene field it
// is read into. Ranges that a pattern cannot express (strict
// inequalities, relations between parameters) are checked in validate_scene().
#include "scene.h"

#include "io/input_file.h"
#include "meshes/beam_mesh.h"
#include "meshes/deal_ii_message.h"
#include "meshes/printable.h"

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <tuple>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

namespace beamslider
{
  namespace
  {
    using dealii::ParameterHandler;
    using dealii::Patterns::Anything;
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Map;
    using dealii::Patterns::Selection;

    // The shortest text that reads back to the same double (so that a scene
    // written by scene_file_text reads back bit for bit).
    std::string num(const double x)
    {
      std::array<char, 32> buffer;
      const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
      return std::string(buffer.data(), result.ptr);
    }

    // A double as written in a scene: the pattern has matched already, so
    // the only failure left is a magnitude below the smallest normal double
    // (2.2e-308, e.g. 1e-320), which Patterns::Double accepts but which is
    // an input error like any other, not a failure of the program.
    double read_double(const std::string &path, const std::string &text)
    {
      errno             = 0;
      char *end         = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (end == text.c_str())
        throw InputError("Parameter '" + path + "' = '" + text + "' is not allowed: it cannot be read as a number");
      if (errno == ERANGE && std::abs(value) < 1.)
        throw InputError("Parameter '" + path + "' = '" + text + "' is not allowed: its magnitude is below the "
                         "smallest normal double (2.2e-308), where a double underflows; give 0 or a value of "
                         "normal size");
      return value;
    }

    // "a, b ,c" -> {"a", "b", "c"}; empty entries dropped.
    std::vector<std::string> split_list(const std::string &text)
    {
      std::vector<std::string> items;
      std::istringstream in(text);
      std::string item;
      while (std::getline(in, item, ','))
        {
          const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
          if (b != std::string::npos)
            items.push_back(item.substr(b, e - b + 1));
        }
      return items;
    }

    std::string join(const std::vector<std::string> &items)
    {
      std::string text;
      for (const std::string &item : items)
        text += (text.empty() ? "" : ", ") + item;
      return text;
    }

    // The tables of a scene, as read: the sections by tag and the point
    // bodies by position, assembled into the beam by build_beam().
    struct SceneTables
    {
      std::map<std::string, std::map<unsigned int, double>> sections; // "Width" -> tag -> value
      std::map<double, double> masses, inertias;                      // x -> m, x -> J
    };

    // A "key: value, ..." table (the Map pattern has matched already).
    template <typename Key>
    std::map<Key, double> read_table(const std::string &path, const std::string &text)
    {
      std::map<Key, double> table;
      std::istringstream entries(text);
      std::string entry;
      while (std::getline(entries, entry, ','))
        {
          if (entry.find_first_not_of(" \t") == std::string::npos)
            continue;
          const auto colon = entry.find(':');
          Key key{};
          double value = 0;
          std::istringstream k(entry.substr(0, colon)), v(colon == std::string::npos ? "" : entry.substr(colon + 1));
          if (!(k >> key) || !(v >> value) || !std::isfinite(value) || !std::isfinite(double(key)))
            throw InputError("Parameter '" + path + "' = '" + text + "' is not allowed: the entry '" + entry +
                             "' is not 'key: value' with two finite numbers");
          if (!table.emplace(key, value).second)
            throw InputError("Parameter '" + path + "' = '" + text + "' is not allowed: it gives a value for " +
                             entry.substr(0, colon) + " twice");
        }
      return table;
    }

    // Declares entries of a ParameterHandler bound to the variables that
    // hold them: each entry's default is the variable's value (written
    // exactly, so a written scene reads back bit for bit), and a value read
    // from a file or set by --set goes straight into the variable through
    // the entry's action (ParameterHandler::add_action). One list of entries
    // thus serves reading a scene, the template and a run's effective
    // parameters.
    //
    // (ParameterHandler::add_parameter does the same for plain types but
    // writes a double's default with six digits, which would not read back
    // to the same scene.)
    class SceneBinder
    {
    public:
      // `values`, if given, receives every entry's path and text.
      explicit SceneBinder(ParameterHandler &prm, std::map<std::string, std::string> *values = nullptr)
        : prm_(prm)
        , values_(values)
      {}

      void enter(const std::string &section)
      {
        prm_.enter_subsection(section);
        section_ = section;
      }
      void leave() { prm_.leave_subsection(); }

      void bind(const std::string &name, double &field, const Double &pattern, const std::string &doc)
      {
        const std::string path = section_ + "/" + name;
        declare(name, num(field), pattern, doc,
                [&field, path](const std::string &text) { field = read_double(path, text); });
      }
      void bind(const std::string &name, unsigned int &field, const Integer &pattern, const std::string &doc)
      {
        declare(name, std::to_string(field), pattern, doc,
                [&field](const std::string &text) { field = static_cast<unsigned int>(std::stoul(text)); });
      }
      void bind(const std::string &name, bool &field, const std::string &doc)
      {
        declare(name, field ? "true" : "false", Bool(), doc,
                [&field](const std::string &text) { field = text == "true" || text == "yes"; });
      }
      void bind(const std::string &name, std::string &field, const dealii::Patterns::PatternBase &pattern,
                const std::string &doc)
      {
        declare(name, field, pattern, doc, [&field](const std::string &text) { field = text; });
      }
      // An entry whose text is turned into the scene by `on_value` (a
      // selection that sets several fields, a table).
      void declare(const std::string &name, const std::string &default_text,
                   const dealii::Patterns::PatternBase &pattern, const std::string &doc,
                   const std::function<void(const std::string &)> &on_value)
      {
        prm_.declare_entry(name, default_text, pattern, doc);
        prm_.add_action(name, on_value); // runs once now, with the default
        if (values_)
          (*values_)[section_ + "/" + name] = default_text;
      }

    private:
      ParameterHandler &prm_;
      std::map<std::string, std::string> *values_;
      std::string section_;
    };

    // Beam: the uniform beam, or the mesh file of a beam of sections.
    void bind_beam(SceneBinder &e, Scene &s)
    {
      e.enter("Beam");
      e.bind("Length", s.beam.length, Double(1e-3, 10), "L, distance between the supports [m], in [1e-3, 10]");
      e.bind("Width", s.beam.width, Double(0), "b, beam width [m]");
      e.bind("Thickness", s.beam.thickness, Double(0), "h, beam thickness [m], > 0 and < L/20 (Euler-Bernoulli)");
      e.bind("Young's modulus", s.beam.youngs_modulus, Double(1e6, 1e13), "E [Pa], in [1e6, 1e13] (soft polymers to diamond)");
      e.bind("Density", s.beam.density, Double(1, 1e5), "rho [kg/m^3], in [1, 1e5]");
      e.bind("Mesh file", s.beam.mesh_file, Anything(),
             "a Gmsh line mesh (.msh, format 2 or 4) of the beam, a path relative to the scene file: "
             "line elements along x from 0 to L, each with a physical tag whose section the subsection "
             "Sections gives. Empty: a uniform beam of the section above, meshed with Number of elements. "
             "With a mesh, Length is the mesh's and Width, Thickness, Young's modulus and Density are the "
             "thickest section's (R/h and amplitudes in thicknesses refer to it): leave them unset");
      e.leave();
    }

    // Tables "tag: value, tag: value" of a mesh beam's sections.
    void bind_section_tables(SceneBinder &e, Scene &s, SceneTables &tables)
    {
      e.enter("Sections");
      const auto section_table = [&](const char *name, double BeamSection::*field, const char *doc) {
        std::string text;
        for (const auto &[tag, section] : s.beam.sections)
          text += (text.empty() ? "" : ", ") + std::to_string(tag) + ": " + num(section.*field);
        const std::string path = std::string("Sections/") + name;
        e.declare(name, text, Map(Integer(0), Double(0), 0, Map::max_int_value, ",", ":"), doc,
                  [&tables, name, path](const std::string &value) {
                    tables.sections[name] = read_table<unsigned int>(path, value);
                  });
      };
      section_table("Width", &BeamSection::width, "b per physical tag of the mesh, 'tag: value, ...' [m] (mesh beams only)");
      section_table("Thickness", &BeamSection::thickness, "h per physical tag [m], each > 0 and < L/20");
      section_table("Young's modulus", &BeamSection::youngs_modulus, "E per physical tag [Pa], in [1e6, 1e13]");
      section_table("Density", &BeamSection::density, "rho per physical tag [kg/m^3], in [1, 1e5]");
      e.leave();
    }

    // Rigid bodies fixed to the beam, "x: value, ..." with x in metres.
    void bind_point_masses(SceneBinder &e, Scene &s, SceneTables &tables)
    {
      e.enter("Point masses");
      {
        std::string masses, inertias;
        for (const PointMass &m : s.beam.point_masses)
          {
            masses += (masses.empty() ? "" : ", ") + num(m.position) + ": " + num(m.mass);
            inertias += (inertias.empty() ? "" : ", ") + num(m.position) + ": " + num(m.rotary_inertia);
          }
        e.declare("Masses", masses, Map(Double(0), Double(0), 0, Map::max_int_value, ",", ":"),
                  "point masses on the beam, 'x: m, ...': position x in [0, L] [m], mass [kg] (on w(x))",
                  [&tables](const std::string &value) { tables.masses = read_table<double>("Point masses/Masses", value); });
        e.declare("Rotary inertias", inertias, Map(Double(0), Double(0), 0, Map::max_int_value, ",", ":"),
                  "rotary inertias of the bodies, 'x: J, ...' [m: kg m^2] (on w'(x)); a position without "
                  "a mass is a body of rotary inertia only",
                  [&tables](const std::string &value) {
                    tables.inertias = read_table<double>("Point masses/Rotary inertias", value);
                  });
      }
      e.leave();
    }

    void bind_supports(SceneBinder &e, Scene &s)
    {
      e.enter("Supports");
      e.declare("Type", s.supports.type(), Selection("elastic|clamped|pinned|clamped-pinned"),
                "elastic: w = 0 with a rotational spring k_r at each end and the axial stiffness k_t of the clamping; "
                "clamped: the ideal clamp w = w' = u = 0; pinned: immovable hinges w = u = 0, w' free; "
                "clamped-pinned: clamped at x = 0, pinned at x = L (the springs below are used by elastic only)",
                [&supports = s.supports](const std::string &type) {
                  supports.ideal_clamp = type == "clamped" || type == "clamped-pinned";
                  supports.pinned_end  = {{type == "pinned", type == "pinned" || type == "clamped-pinned"}};
                });
      e.bind("Rotational stiffness", s.supports.rotational_stiffness, Double(0), "k_r, on w' at each end [N m/rad]");
      e.bind("Axial stiffness", s.supports.axial_stiffness, Double(0), "k_t, the clamping's TOTAL axial stiffness as published (Mueller, Beck & Krack 2023): in series with the beam, k_ax = (L/(EA) + 1/k_t)^-1; the FE model puts 2 k_t at each end [N/m]");
      e.leave();
    }

    void bind_slider(SceneBinder &e, Scene &s)
    {
      e.enter("Slider");
      e.bind("Mass", s.slider.mass, Double(0), "m [kg], > 0");
      e.bind("Rotary inertia", s.slider.inertia, Double(0), "J_C about the centre of mass [kg m^2], > 0; the radius of gyration sqrt(J_C/m) must be at least 3 % of the corners' distance sqrt(d^2 + B^2/4) from the centre of mass (a rigid frame around the window cannot have less)");
      e.bind("Window width", s.slider.window_width, Double(0), "B, horizontal distance of the contact corners [m], < L");
      e.bind("Window height ratio", s.slider.window_height_ratio, Double(0), "R/h, inner window height over beam thickness [-], > 1");
      e.bind("Centre of mass offset", s.slider.com_offset, Double(0), "d, centre of mass below the window centre [m]");
      e.bind("Mass factor", s.slider.mass_factor, Double(0), "ablation: multiplies mass and rotary inertia [-], > 0");
      e.leave();
    }

    void bind_contact(SceneBinder &e, Scene &s)
    {
      e.enter("Contact");
      e.bind("Friction coefficient", s.contact.friction_coefficient, Double(0), "mu, Coulomb [-]");
      e.bind("Restitution", s.contact.restitution, Double(0, 1), "e_N, Newton's normal restitution [-] in [0, 1]");
      e.bind("Gravity", s.contact.gravity, Double(0), "g, acting on the slider in -z [m/s^2]");
      e.bind("Solver", s.contact.solver, Selection("projected|exact-local"),
             "contact impulses per step: projected Gauss-Seidel (as the authors' code) or exact-local "
             "(each contact's 2x2 problem solved exactly, block Gauss-Seidel; same solution, fewer sweeps)");
      e.leave();
    }

    void bind_damping_excitation_and_initial_state(SceneBinder &e, Scene &s)
    {
      e.enter("Damping");
      e.bind("Modal damping ratio", s.damping_ratio, Double(0, 1), "D, the same for every mode [-] in [0, 1)");
      e.leave();

      e.enter("Excitation");
      e.bind("Frequency", s.excitation.frequency_hz, Double(0.1, 1e5),
             "f_ex [Hz], in [0.1, 1e5] (at lower frequencies the base displacement a/Omega^2 swamps the micrometre gaps in round-off)");
      e.bind("Acceleration amplitude", s.excitation.acceleration_amplitude, Double(0), "base acceleration amplitude [m/s^2]");
      e.leave();

      e.enter("Initial state");
      e.bind("Slider position", s.initial.slider_position_over_L, Double(0, 1), "x_C/L at t = 0 [-]; the window must lie inside the beam");
      e.leave();
    }

    void bind_discretisation_and_time_stepping(SceneBinder &e, Scene &s)
    {
      e.enter("Discretisation");
      e.bind("Number of elements", s.discretisation.n_elements, Integer(1, 4096), "beam elements of the FE model, at least N + 1 (Number of modes)");
      e.bind("Axial degree", s.discretisation.axial_degree, Integer(1, 6), "polynomial degree of the axial displacement u");
      e.bind("Number of modes", s.discretisation.n_modes, Integer(1, 40),
             "N, bending modes of the reduced model (and modes the FE damps); the explicit ROM step needs Delta t <= 2/omega_N");
      e.bind("Static corrections", s.discretisation.n_static_corrections, Integer(0, 40),
             "m, static corrections the reduced model adds to its N modes: the residual flexibility of unit point loads at m "
             "positions evenly over the beam (beam scenes only; 0: the modes alone)");
      e.bind("Ritz blocks", s.discretisation.ritz_blocks, Integer(1, 8),
             "b, blocks of m vectors the static corrections grow to: 1 the static corrections alone; b > 1 adds b - 1 "
             "blocks of load-dependent Ritz vectors (Wilson), K^-1 M times the block before, each without its part "
             "along the N modes (needs Static corrections >= 1)");
      e.bind("Geometric nonlinearity", s.discretisation.geometric_nonlinearity, "von Karman bending-stretching coupling on/off (ablation)");
      e.leave();

      e.enter("Time stepping");
      e.bind("Time step", s.time_stepping.time_step, Double(0), "Delta t [s] of the reduced model, > 0, at most 1/20 of the excitation period and below the model's stability limit (explicit ROM: 2/omega_max)");
      e.bind("FE time step", s.time_stepping.fe_time_step, Double(0),
             "Delta t [s] of the FE model (every --model fe run and the error ladder's FE reference), > 0, at most "
             "1/20 of the excitation period; with FE theta = 0.5 the FE's end state converges only at a much "
             "smaller step than with theta slightly above 0.5 (doc/verification.md section 7)");
      e.bind("FE impulses", s.time_stepping.fe_impulses, Selection("step|mass"),
             "what an impact's impulse moves in the FE step: step (Moreau-Jean, through the step's iteration matrix "
             "M + theta^2 Delta t^2 K: the beam mass under an impact shrinks like sqrt(Delta t)) or mass (through the "
             "mass matrix: the semi-discrete system's velocity jump, the same at every Delta t)");
      e.bind("FE theta", s.time_stepping.fe_theta, Double(0.5, 1),
             "theta of the FE's Moreau-Jean scheme, in [0.5, 1]: 0.5 is the implicit midpoint rule (no numerical "
             "damping); above, the modes the FE time step cannot resolve are damped, and the resolved ones by a "
             "damping ratio (theta - 0.5) omega Delta t");
      e.bind("End time", s.time_stepping.end_time, Double(0), "[s], at most 1e11 time steps");
      e.bind("Output rate", s.time_stepping.output_rate, Double(0), "samples per second in trace.csv [1/s]");
      e.leave();
    }

    void bind_solvers(SceneBinder &e, Scene &s)
    {
      e.enter("Solvers");
      e.bind("Contact tolerance", s.solvers.contact_tolerance, Double(1e-16, 1e-2),
             "contact impulses of a step: converged when the relative change of G P + c per sweep is below "
             "this [-], in [1e-16, 1e-2]");
      e.bind("Contact sweeps", s.solvers.contact_sweeps, Integer(1, 10000000),
             "cap on the Gauss-Seidel sweeps of one contact solve; a solve that reaches it stops the run "
             "with a message");
      e.bind("Newton relative tolerance", s.solvers.newton_relative_tolerance, Double(1e-15, 1e-2),
             "FE time step: Newton's correction relative to the end velocity [-], in [1e-15, 1e-2]");
      e.bind("Newton absolute tolerance", s.solvers.newton_absolute_tolerance, Double(0, 1),
             "FE time step: or a correction below this [m/s], in [0, 1]");
      e.bind("Newton iterations", s.solvers.newton_iterations, Integer(1, 1000),
             "FE time step: cap on Newton iterations per step, refactorisations included; a step that "
             "reaches it stops the run with a message");
      e.leave();
    }

    void bind_solid(SceneBinder &e, Scene &s)
    {
      e.enter("Solid");
      e.bind("Continuum", s.solid.continuum, Selection("none|plane stress|3d"),
             "the strip of subsection Beam as a St. Venant-Kirchhoff continuum clamped at both end faces "
             "(modes, coefficients): none (the beam alone), plane stress (2D, x-z plane, the width b as "
             "out-of-plane thickness) or 3d");
      e.bind("Poisson's ratio", s.solid.poissons_ratio, Double(0, 0.5), "nu [-], in [0, 0.5); 0 is what beam theory assumes");
      e.bind("Degree", s.solid.degree, Integer(1, 4), "polynomial degree p of the displacement (FE_Q(p)), in [1, 4]");
      e.bind("Elements along length", s.solid.elements_along_length, Integer(1, 100000),
             "elements of the generated strip in x");
      e.bind("Elements across width", s.solid.elements_across_width, Integer(1, 10000),
             "elements of the generated strip in y (3d only)");
      e.bind("Elements through thickness", s.solid.elements_through_thickness, Integer(1, 1000),
             "elements of the generated strip in z");
      e.bind("Arch rise", s.solid.arch_rise, Double(0, 1),
             "a shallow arch: the generated strip's mid-surface at z0(x) = rise sin(pi x / L) [m], in [0, 1]; "
             "0 is the flat strip");
      e.bind("Mesh file", s.solid.mesh_file, Anything(),
             "a solid mesh instead of the generated strip, a path relative to the scene file: Gmsh .msh "
             "(format 2 or 4; hexahedra or tetrahedra in 3d, quadrilaterals or triangles in plane stress) or "
             "Abaqus .inp. Its physical groups name the clamped faces, the loaded face and the material regions "
             "(the entries below); the strip's axis runs along x from 0 to L, z is the beam's w direction");
      e.declare("Clamped boundaries", join(s.solid.clamped_boundaries), dealii::Patterns::List(Anything()),
                "with a Mesh file: the physical groups of the clamped faces (u = 0), by Gmsh name or tag, "
                "comma-separated",
                [&s](const std::string &text) { s.solid.clamped_boundaries = split_list(text); });
      e.bind("Loaded boundary", s.solid.loaded_boundary, Anything(),
             "with a Mesh file: the physical group (name or tag) of the top face that the statics line load "
             "presses on");
      e.bind("Materials", s.solid.materials, Anything(),
             "with a Mesh file: one 'group: E nu rho' entry per cell region (Gmsh name or tag; E [Pa], nu [-], "
             "rho [kg/m^3]), comma-separated; empty: every cell has Beam/Young's modulus, Beam/Density and "
             "the Poisson's ratio above");
      e.leave();
    }

    // Every entry of a scene, with the values of `s` as defaults, bound to
    // the fields of `s` (and to `tables` for the Sections and Point masses
    // tables, which build_beam() assembles into the beam afterwards): Scene{}
    // (the default scene, mueller2023) for reading and the template, a run's
    // own scene for the effective parameters it writes (scene_file_text).
    void bind_scene(ParameterHandler &prm, Scene &s, SceneTables &tables,
                    std::map<std::string, std::string> *values = nullptr)
    {
      SceneBinder e(prm, values);
      bind_beam(e, s);
      bind_section_tables(e, s, tables);
      bind_point_masses(e, s, tables);
      bind_supports(e, s);
      bind_slider(e, s);
      bind_contact(e, s);
      bind_damping_excitation_and_initial_state(e, s);
      bind_discretisation_and_time_stepping(e, s);
      bind_solvers(e, s);
      bind_solid(e, s);
    }

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

    // A scene file, and each file it includes, is a regular file of at most
    // this size: a device (/dev/zero) would be read without end, a FIFO would
    // block. The scene with its includes expanded is bounded alike (a file
    // included many times over).
    constexpr std::size_t max_scene_bytes = InputLimits::scene;
    // Includes nest at most this deep (a chain of distinct files).
    constexpr unsigned int max_include_depth = 16;

    // The lines of a scene after its `include` lines are replaced by the
    // files they name, with where each line comes from, so that a message
    // names the file and the line the user wrote.
    struct SceneText
    {
      struct Origin
      {
        std::string file;
        unsigned int line;
      };
      std::string text;            // every line, '\n'-terminated
      std::vector<Origin> origins; // of line i + 1 of text

      // "Scene file 'F', line N" for line `line` (from 1) of text.
      std::string where(const unsigned int line) const
      {
        if (line == 0 || line > origins.size())
          return "Scene file";
        const Origin &o = origins[line - 1];
        return "Scene file '" + printable(o.file) + "', line " + std::to_string(o.line);
      }
    };

    std::string trim(const std::string &x)
    {
      const auto b = x.find_first_not_of(" \t\r");
      const auto e = x.find_last_not_of(" \t\r");
      return b == std::string::npos ? std::string() : x.substr(b, e - b + 1);
    }

    // The first word of a scene line in lower case if deal.II takes it for
    // a keyword, which it does in lower or upper case ("set", "SET"); ""
    // for any other word ("Set").
    std::string scene_keyword(const std::string &word)
    {
      std::string lower = word, upper = word;
      std::transform(word.begin(), word.end(), lower.begin(), [](const unsigned char c) { return std::tolower(c); });
      std::transform(word.begin(), word.end(), upper.begin(), [](const unsigned char c) { return std::toupper(c); });
      return word == lower || word == upper ? lower : std::string();
    }

    // The text of one file, after checking with stat() that it is a regular
    // file of bounded size, before it is opened (a FIFO is never opened).
    // `what` names it in messages: "Scene file 'x.prm'" or the include line.
    std::string read_bounded_file(const std::string &path, const std::string &what)
    {
      struct stat info;
      if (::stat(path.c_str(), &info) != 0)
        throw InputError(what + (errno == ENOENT || errno == ENOTDIR ? " does not exist"
                                                                    : " cannot be examined: " +
                                                                        std::string(std::strerror(errno))));
      if (S_ISDIR(info.st_mode))
        throw InputError(what + " is a folder, not a scene file (.prm)");
      if (!S_ISREG(info.st_mode))
        throw InputError(what + " is not a regular file (a FIFO, device or socket); give a .prm file");
      if (static_cast<std::uintmax_t>(info.st_size) > max_scene_bytes)
        throw InputError(what + " has " + std::to_string(info.st_size) +
                         " bytes; a scene file has at most 1 MB (1048576 bytes)");
      // The read itself is the guarded one (io/input_file.h): should the
      // file have been replaced by a FIFO or have grown since, it says so.
      std::string text;
      try
        {
          text = read_text_file(path, max_scene_bytes);
        }
      catch (const FileReadError &e)
        {
          throw InputError(what + " cannot be read: " + e.what() + "; give a .prm file of at most 1 MB");
        }
      return text;
    }

    // Appends the lines of `file` to `scene`, each `include` line replaced
    // by the lines of the file it names (a path relative to the including
    // file, as Beam/Mesh file is). deal.II's own `include` would open the
    // path as given without any check; here every line is checked to be a
    // scene line first, so that a message never quotes a line of a file
    // that is not a scene (an included /etc/passwd is refused by its file
    // name and line number only). `chain` holds the files being read, the
    // outermost first: a file that includes one of them is a cycle.
    // `what` names the file for a message about the file as a whole,
    // `included_by` (" (included by 'a.prm', line 3)", or "") follows the
    // place of a message about one of its lines.
    void append_scene_file(const std::string &file, const std::string &what, const std::string &included_by,
                           std::vector<std::string> &chain, SceneText &scene)
    {
      namespace fs = std::filesystem;
      const std::string text = read_bounded_file(file, what);
      std::error_code ec;
      chain.push_back(fs::weakly_canonical(fs::absolute(file), ec).string());

      std::istringstream in(text);
      std::string line;
      unsigned int line_number = 0, depth = 0;
      bool continued = false; // the previous line ends in '\': deal.II joins the two
      while (std::getline(in, line))
        {
          ++line_number;
          const std::string where =
            "Scene file '" + printable(file) + "', line " + std::to_string(line_number) + included_by;
          for (std::size_t i = 0; i < line.size(); ++i)
            {
              const auto byte = static_cast<unsigned char>(line[i]);
              if ((byte < 0x20 && byte != '\t' && byte != '\r') || byte == 0x7f)
                throw InputError(where + " holds a byte that is not text (" + printable(std::string(1, line[i])) +
                                 " at column " + std::to_string(i + 1) + "); a scene file is text");
            }
          const std::string content = trim(line.substr(0, line.find('#')));
          const bool starts = !continued;
          continued = !trim(line).empty() && trim(line).back() == '\\';
          if (!starts || content.empty())
            {
              scene.text += line + '\n';
              scene.origins.push_back({file, line_number});
              continue;
            }
          std::istringstream words(content);
          std::string word;
          words >> word;
          const std::string keyword = scene_keyword(word), rest = trim(content.substr(word.size()));
          if (keyword == "subsection" && !rest.empty())
            ++depth;
          else if (keyword == "end" && rest.empty())
            {
              if (depth == 0)
                throw InputError(where + ": 'end' without a 'subsection' before it in this file");
              --depth;
            }
          else if (keyword == "include" && !rest.empty() && !continued)
            {
              if (chain.size() > max_include_depth)
                throw InputError(where + ": includes nest deeper than " + std::to_string(max_include_depth) +
                                 " files");
              fs::path target(rest);
              if (target.is_relative())
                target = fs::path(file).parent_path() / target;
              const std::string canonical = fs::weakly_canonical(fs::absolute(target), ec).string();
              const auto cycle = std::find(chain.begin(), chain.end(), canonical);
              if (cycle != chain.end())
                {
                  std::string names;
                  for (auto f = cycle; f != chain.end(); ++f)
                    names += "'" + printable(*f) + "' includes ";
                  throw InputError(where + ": 'include " + printable(rest) + "' is a cycle: " + names + "'" +
                                   printable(canonical) + "'; a scene cannot include itself");
                }
              const std::string place = "'" + printable(file) + "', line " + std::to_string(line_number);
              append_scene_file(target.string(), where + ": the included file '" + printable(target.string()) + "'",
                                " (included by " + place + ")", chain, scene);
              continue;
            }
          else if (keyword != "set" || rest.empty())
            throw InputError(where + " is not a scene line: a scene has only 'set Name = value', 'subsection "
                                     "Name', 'end' and 'include FILE' lines (the line is not shown, as it may "
                                     "not be from a scene file)");
          scene.text += line + '\n';
          scene.origins.push_back({file, line_number});
          if (scene.text.size() > max_scene_bytes)
            throw InputError(where + ": the scene with its included files has more than 1 MB; a scene has at "
                                     "most 1 MB (1048576 bytes)");
        }
      if (continued)
        throw InputError("Scene file '" + printable(file) + "', line " + std::to_string(line_number) + included_by +
                         ": the last line ends in '\\', which would join it to a line of another file");
      if (depth != 0)
        throw InputError("Scene file '" + printable(file) + "'" + included_by + ": " + std::to_string(depth) +
                         " 'subsection' without its 'end' (each file closes the subsections it opens)");
      chain.pop_back();
    }

    // The text of a scene file with its includes, after checking that it is
    // one: a regular, non-empty text file of scene lines (a folder, a FIFO
    // or a device is refused before it is opened, so that reading cannot
    // hang).
    SceneText read_scene_text(const std::string &filename)
    {
      const std::string what = "Scene file '" + printable(filename) + "'";
      SceneText scene;
      std::vector<std::string> chain;
      append_scene_file(filename, what, "", chain, scene);
      if (trim(scene.text).empty())
        throw InputError(what + " is empty; a scene sets its parameters with 'set Name = value' "
                                "(see `beamslider scene-template`)");
      return scene;
    }

    // deal.II's reader lets a later `set` silently replace an earlier one; a
    // scene that sets a parameter twice is almost always an editing slip, so
    // it is refused. Also refuses a file without any `set`: it would run the
    // built-in defaults under the file's name.
    std::set<std::string> check_entries_unique(const std::string &filename, const SceneText &scene)
    {
      std::istringstream in(scene.text);
      std::vector<std::string> sections;
      std::map<std::string, unsigned int> first_line;
      std::string line;
      unsigned int line_number = 0, n_entries = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          line = trim(line.substr(0, line.find('#')));
          std::istringstream words(line);
          std::string word;
          words >> word;
          const std::string keyword = scene_keyword(word);
          if (keyword == "subsection")
            sections.push_back(trim(line.substr(keyword.size())));
          else if (keyword == "end" && !sections.empty())
            sections.pop_back();
          else if (keyword == "set")
            {
              const std::string rest = line.substr(keyword.size());
              std::string key;
              for (const auto &section : sections)
                key += section + "/";
              key += trim(rest.substr(0, rest.find('=')));
              ++n_entries;
              const auto [it, inserted] = first_line.emplace(key, line_number);
              if (!inserted)
                {
                  const SceneText::Origin &first = scene.origins[it->second - 1];
                  const bool same_file = first.file == scene.origins[line_number - 1].file;
                  throw InputError(scene.where(line_number) + ": '" + printable(key) + "' is set a second time (first " +
                                   (same_file ? "on line " + std::to_string(first.line)
                                              : "in '" + printable(first.file) + "', line " + std::to_string(first.line)) +
                                   "); a scene sets each parameter once");
                }
            }
        }
      if (n_entries == 0)
        throw InputError("Scene file '" + printable(filename) + "' sets no parameter (no 'set Name = value' line); "
                         "see `beamslider scene-template`");
      std::set<std::string> keys;
      for (const auto &[key, line] : first_line)
        keys.insert(key);
      return keys;
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

    void require(const bool condition, const std::string &parameter, const double value, const std::string &allowed)
    {
      if (!condition)
        throw InputError("Parameter '" + parameter + "' = " + num(value) + " is not allowed: " + allowed);
    }

    // parameters.prm records a text parameter as `set Name = value` on one
    // line, which deal.II reads back up to a '#' (a comment), trimmed, with
    // tabs as spaces, joined to the next line after a trailing '\'. It has
    // no escape for these, so a value that would not read back to itself is
    // refused: a run's folder must repeat the run.
    void require_recordable(const std::string &parameter, const std::string &value)
    {
      std::string why;
      if (value.find('#') != std::string::npos)
        why = "it holds a '#', which starts a comment in a parameter file";
      else if (std::any_of(value.begin(), value.end(),
                           [](const unsigned char c) { return c < 0x20 || c == 0x7f; }))
        why = "it holds a control character (a line break, a tab, ...), which a parameter file cannot hold";
      else if (!value.empty() && value.back() == '\\')
        why = "it ends in '\\', which joins a parameter file's line to the next";
      else if (value != trim(value))
        why = "it begins or ends with a space, which a parameter file drops";
      if (!why.empty())
        throw InputError("Parameter '" + parameter + "' = '" + printable(value) + "' is not allowed: " + why +
                         ", so the run's parameters.prm could not record it; use a name without it");
    }

    // Every text parameter of a scene, as parameters.prm would write it.
    void require_recordable(const Scene &s)
    {
      require_recordable("Beam/Mesh file", s.beam.mesh_file);
      require_recordable("Solid/Mesh file", s.solid.mesh_file);
      require_recordable("Solid/Loaded boundary", s.solid.loaded_boundary);
      require_recordable("Solid/Materials", s.solid.materials);
      for (const std::string &group : s.solid.clamped_boundaries)
        require_recordable("Solid/Clamped boundaries", group);
    }

    std::string gigabytes(const double bytes)
    {
      std::ostringstream s;
      s.precision(3);
      s << bytes / 1e9 << " GB";
      return s.str();
    }

    // The memory this program may use [bytes] and what sets it: the
    // machine's memory, or less if the address space (ulimit -v) or the
    // cgroup (memory.max) is limited.
    std::pair<double, std::string> memory_limit()
    {
      const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
      std::pair<double, std::string> limit{pages > 0 && page_size > 0 ? double(pages) * double(page_size)
                                                                       : std::numeric_limits<double>::infinity(),
                                           "this machine's memory"};
      rlimit address_space{};
      if (::getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY &&
          double(address_space.rlim_cur) < limit.first)
        limit = {double(address_space.rlim_cur), "the address-space limit (ulimit -v)"};
      double cgroup = 0;
      if (std::ifstream("/sys/fs/cgroup/memory.max") >> cgroup && cgroup > 0 && cgroup < limit.first)
        limit = {cgroup, "the cgroup's memory limit (memory.max)"};
      return limit;
    }

    // The generated strip against the memory there is: a strip of 1e9
    // cells would run until std::bad_alloc. The estimate is a floor: the
    // mesh (about 1 kB a cell) and the stiffness and mass matrices (12 bytes
    // a nonzero each; a cell of FE_Q(p) adds d p^d rows of d (2p + 1)^d
    // nonzeros); the eigensolver's factorisation needs more.
    void require_strip_fits_in_memory(const Scene &s)
    {
      const SolidData &solid = s.solid;
      const unsigned int dim = solid.dimension();
      double cells = double(solid.elements_along_length) * solid.elements_through_thickness;
      if (dim == 3)
        cells *= solid.elements_across_width;
      const double p = solid.degree;
      const double rows_per_cell = dim * std::pow(p, dim), nonzeros_per_row = dim * std::pow(2 * p + 1, dim);
      const double bytes = cells * (1024. + rows_per_cell * nonzeros_per_row * 24.);
      const auto [limit, what] = memory_limit();
      if (bytes > limit)
        throw InputError("Parameters 'Solid/Elements along length' = " + std::to_string(solid.elements_along_length) +
                         (dim == 3 ? ", 'Solid/Elements across width' = " + std::to_string(solid.elements_across_width)
                                   : std::string()) +
                         " and 'Solid/Elements through thickness' = " +
                         std::to_string(solid.elements_through_thickness) + " are not allowed: the strip's " +
                         num(cells) + " cells of degree " + std::to_string(solid.degree) + " need at least " +
                         gigabytes(bytes) + " of memory (the mesh and two matrices alone), more than " + what +
                         " of " + gigabytes(limit) + "; use fewer elements");
    }
  } // namespace

  namespace
  {
    // The conditions on a beam read from a mesh: every section a physical
    // one, and the elements a whole multiple of the mesh's.
    void validate_mesh_beam(const Scene &s)
    {
      const BeamData &b = s.beam;
      for (const auto &[tag, section] : b.sections)
        {
          const std::string t = " of tag " + std::to_string(tag);
          require(section.width > 0, "Sections/Width" + t, section.width, "must be > 0 m");
          require(section.thickness > 0 && section.thickness < b.length / 20., "Sections/Thickness" + t,
                  section.thickness, "must be in (0, L/20 = " + num(b.length / 20.) + ") m for Euler-Bernoulli theory");
          require(section.youngs_modulus >= 1e6 && section.youngs_modulus <= 1e13, "Sections/Young's modulus" + t,
                  section.youngs_modulus, "must be in [1e6, 1e13] Pa");
          require(section.density >= 1 && section.density <= 1e5, "Sections/Density" + t, section.density,
                  "must be in [1, 1e5] kg/m^3");
          for (const double value : {section.bending_stiffness(), section.axial_stiffness(), section.mass_per_length()})
            require(std::isnormal(value), "Sections/Width" + t, section.width,
                    "with its thickness it gives a stiffness or mass per length outside the doubles of normal size");
        }
      const auto n_cells = static_cast<unsigned int>(b.mesh_cells.size());
      require(s.discretisation.n_elements % n_cells == 0, "Discretisation/Number of elements", s.discretisation.n_elements,
              "with a mesh file it must be a multiple of the mesh's " + std::to_string(n_cells) +
                " elements (each is split into equal parts); leave it unset to take the mesh as it is");
    }

    // The slider's mass and rotary inertia: positive, and J_C not negligible.
    void validate_slider_mass(const Scene &s)
    {
      require(std::isfinite(s.slider.mass) && s.slider.mass > 0, "Slider/Mass", s.slider.mass, "must be > 0 kg");
      require(std::isfinite(s.slider.inertia) && s.slider.inertia > 0, "Slider/Rotary inertia", s.slider.inertia,
              "must be > 0 kg m^2");
      {
        // The Delassus matrix carries 1/m and lever²/J_C; a J_C negligible
        // against m × lever² makes it singular in effect (the slider would
        // spin through the beam within one step).
        const double lever2 = s.slider.com_offset * s.slider.com_offset + 0.25 * s.slider.window_width * s.slider.window_width;
        const double minimum = 0.03 * 0.03 * s.slider.mass * lever2;
        require(s.slider.inertia >= minimum, "Slider/Rotary inertia", s.slider.inertia,
                "must be >= " + num(minimum) + " kg m^2: the radius of gyration sqrt(J_C/m) must be at least 3 % of "
                "the corners' distance sqrt(d^2 + B^2/4) = " + num(std::sqrt(lever2)) + " m from the centre of mass");
      }
    }

    // The solid continuum: its material, supports and shape, or its mesh file.
    void validate_solid(const Scene &s)
    {
      if (s.solid.enabled())
        {
          require(s.solid.poissons_ratio >= 0 && s.solid.poissons_ratio < 0.5, "Solid/Poisson's ratio",
                  s.solid.poissons_ratio, "must be in [0, 0.5)");
          if (s.beam.from_mesh())
            throw InputError("Parameter 'Solid/Continuum' = '" + s.solid.continuum +
                             "' is not allowed with 'Beam/Mesh file': the solid is generated from a uniform strip");
          if (s.supports.type() != "clamped" && s.supports.type() != "elastic")
            throw InputError("Parameter 'Solid/Continuum' = '" + s.solid.continuum + "' is not allowed with "
                             "'Supports/Type' = " + s.supports.type() + ": a solid is clamped (its clamped faces, or "
                             "both end faces of the generated strip) or on the elastic supports (rigid end plates "
                             "on springs); set 'Supports/Type' = clamped or elastic");
          require(std::isfinite(s.solid.arch_rise) && s.solid.arch_rise >= 0 && s.solid.arch_rise <= s.beam.length / 10,
                  "Solid/Arch rise", s.solid.arch_rise,
                  "must be in [0, L/10 = " + num(s.beam.length / 10) + "] m (a shallow arch)");
          if (s.solid.from_mesh())
            {
              if (s.solid.arch_rise != 0)
                throw InputError("Parameter 'Solid/Arch rise' = " + num(s.solid.arch_rise) + " is not allowed with "
                                 "'Solid/Mesh file': the rise shapes the generated strip; a mesh carries its own shape");
              if (s.solid.clamped_boundaries.empty())
                throw InputError("Parameter 'Solid/Clamped boundaries' is empty: a solid mesh needs at least one "
                                 "clamped physical group (or it floats)");
              const std::string ext = std::filesystem::path(s.solid.mesh_file).extension().string();
              if (ext != ".msh" && ext != ".inp")
                throw InputError("Parameter 'Solid/Mesh file' = '" + printable(s.solid.mesh_file) + "' is not allowed: the "
                                 "extension must be .msh (Gmsh) or .inp (Abaqus)");
              solid_material_entries(s.solid.materials);
            }
          else
            require_strip_fits_in_memory(s);
        }
      else if (s.solid.from_mesh())
        throw InputError("Parameter 'Solid/Mesh file' = '" + s.solid.mesh_file + "' is set, but 'Solid/Continuum' is "
                         "none: set Continuum to 3d or plane stress to use the mesh");
    }

    // The beam's section (or its mesh's sections) and its point masses.
    void validate_beam(const Scene &s)
    {
      require(s.beam.width > 0, "Beam/Width", s.beam.width, "must be > 0 m");
      require(s.beam.thickness > 0, "Beam/Thickness", s.beam.thickness, "must be > 0 m");
      require(s.beam.thickness < s.beam.length / 20., "Beam/Thickness", s.beam.thickness,
              "must be < L/20 = " + num(s.beam.length / 20.) + " m for Euler-Bernoulli theory to hold");
      require(s.beam.youngs_modulus > 0, "Beam/Young's modulus", s.beam.youngs_modulus, "must be > 0 Pa");
      require(s.beam.density > 0, "Beam/Density", s.beam.density, "must be > 0 kg/m^3");
      {
        // Width and thickness have no upper or lower bound of their own, but
        // the section's stiffnesses and mass per length must be doubles of
        // normal size: h^3 underflows to 0 for h below ~1e-103 m (the beam
        // would have no bending stiffness: a singular stiffness matrix, PETSc's
        // "zero pivot"), E b overflows for b near 1e308 m.
        const BeamData &b = s.beam;
        for (const auto &[name, value] : {std::pair<const char *, double>{"bending stiffness EI = E b h^3/12", b.bending_stiffness()},
                                          {"axial stiffness EA = E b h", b.axial_stiffness()},
                                          {"mass per length rho b h", b.mass_per_length()}})
          if (!std::isnormal(value))
            throw InputError("Parameters 'Beam/Width' = " + num(b.width) + " and 'Beam/Thickness' = " + num(b.thickness) +
                             " are not allowed: they give the " + name + " = " + num(value) +
                             ", outside the doubles of normal size [2.2e-308, 1.8e308]");
      }
      if (s.beam.from_mesh())
        validate_mesh_beam(s);
      for (const PointMass &m : s.beam.point_masses)
        {
          require(m.position >= 0 && m.position <= s.beam.length, "Point masses (position)", m.position,
                  "a body must sit on the beam, x in [0, L = " + num(s.beam.length) + "] m");
          require(std::isfinite(m.mass) && m.mass >= 0, "Point masses/Masses", m.mass, "must be >= 0 kg");
          require(std::isfinite(m.rotary_inertia) && m.rotary_inertia >= 0, "Point masses/Rotary inertias",
                  m.rotary_inertia, "must be >= 0 kg m^2");
        }
    }

    // The slider's window on the beam, its mass factor and its initial position.
    void validate_slider_window(const Scene &s)
    {
      require(s.slider.window_height_ratio > 1., "Slider/Window height ratio", s.slider.window_height_ratio,
              s.beam.from_mesh()
                ? "R/h must be > 1, h = " + num(s.beam.thickness) + " m being the beam's thickest section: the slider "
                  "travels along the whole beam, so its window must clear the largest thickness it can meet"
                : "R/h must be > 1: the slider's window must be taller than the beam is thick");
      require(s.slider.window_width > 0, "Slider/Window width", s.slider.window_width, "must be > 0 m");
      require(s.slider.window_width < s.beam.length, "Slider/Window width", s.slider.window_width,
              "the slider must be narrower than the beam length L = " + num(s.beam.length) + " m");
      {
        // The corners are the slider's only contacts: a window lower than it
        // is wide (R < B) lets the slider turn by less than 45 degrees before
        // they meet the beam; a taller one is a loose ring the model does not
        // describe (and R/h = 1e300 overflows the gaps to NaN).
        const double largest = s.slider.window_width / s.beam.thickness;
        require(s.slider.window_height_ratio < largest, "Slider/Window height ratio", s.slider.window_height_ratio,
                "R/h must be in (1, B/h = " + num(largest) + "): the window (R = " +
                  num(s.slider.window_height_ratio * s.beam.thickness) + " m) must be lower than it is wide (B = " +
                  num(s.slider.window_width) + " m), as the model's only contacts are its four corners");
      }
      require(s.slider.mass_factor > 0, "Slider/Mass factor", s.slider.mass_factor, "must be > 0");
      const double half_window_over_L = 0.5 * s.slider.window_width / s.beam.length;
      require(s.initial.slider_position_over_L >= half_window_over_L &&
                s.initial.slider_position_over_L <= 1. - half_window_over_L,
              "Initial state/Slider position", s.initial.slider_position_over_L,
              "x_C/L must lie in [" + num(half_window_over_L) + ", " + num(1 - half_window_over_L) +
                "] so that the slider's window is on the beam");
    }

    void validate_damping_and_excitation(const Scene &s)
    {
      require(s.damping_ratio >= 0 && s.damping_ratio < 1, "Damping/Modal damping ratio", s.damping_ratio, "must be in [0, 1)");
      require(s.excitation.frequency_hz > 0, "Excitation/Frequency", s.excitation.frequency_hz, "must be > 0 Hz");
      {
        // The slider's coordinates are absolute, the beam's relative to the
        // base (contact/base_excitation.h): the base displacement amplitude
        // a/Omega^2 enters every gap, from t = 0 on. A frequency so low that it
        // overflows (e.g. 1e-182 Hz at 14 m/s^2) gives an infinite initial state.
        const double omega = 2. * M_PI * s.excitation.frequency_hz;
        const double base_amplitude = s.excitation.acceleration_amplitude / (omega * omega);
        require(std::isfinite(base_amplitude), "Excitation/Frequency", s.excitation.frequency_hz,
                "the base displacement amplitude a/(2 pi f)^2 = " + num(base_amplitude) + " m (a = " +
                  num(s.excitation.acceleration_amplitude) + " m/s^2) must be finite");
      }
    }

    // The two time steps against the excitation period, theta, the end time and the output rate.
    void validate_time_stepping(const Scene &s)
    {
      require(std::isfinite(s.time_stepping.time_step) && s.time_stepping.time_step > 0, "Time stepping/Time step",
              s.time_stepping.time_step, "must be > 0 s");
      {
        const double period = 1. / s.excitation.frequency_hz;
        require(s.time_stepping.time_step <= period / 20., "Time stepping/Time step", s.time_stepping.time_step,
                "must be <= " + num(period / 20.) + " s, a twentieth of the excitation period " + num(period) +
                  " s, to resolve the excitation");
      }
      require(std::isfinite(s.time_stepping.fe_time_step) && s.time_stepping.fe_time_step > 0,
              "Time stepping/FE time step", s.time_stepping.fe_time_step, "must be > 0 s");
      {
        const double period = 1. / s.excitation.frequency_hz;
        require(s.time_stepping.fe_time_step <= period / 20., "Time stepping/FE time step",
                s.time_stepping.fe_time_step,
                "must be <= " + num(period / 20.) + " s, a twentieth of the excitation period " + num(period) +
                  " s, to resolve the excitation");
      }
      require(s.time_stepping.fe_theta >= 0.5 && s.time_stepping.fe_theta <= 1., "Time stepping/FE theta",
              s.time_stepping.fe_theta, "must be in [0.5, 1] (0.5: the midpoint rule; 1: the implicit Euler step)");
      require(std::isfinite(s.time_stepping.end_time) && s.time_stepping.end_time >= 0, "Time stepping/End time",
              s.time_stepping.end_time, "must be >= 0 s");
      {
        // The smaller of the two steps sets the longest run.
        const double dt = std::min(s.time_stepping.time_step, s.time_stepping.fe_time_step);
        const std::string which =
          dt == s.time_stepping.time_step ? "Time stepping/Time step" : "Time stepping/FE time step";
        require(s.time_stepping.end_time / dt <= max_time_steps, "Time stepping/End time", s.time_stepping.end_time,
                "would need " + num(s.time_stepping.end_time / dt) + " time steps of " + num(dt) + " s (" + which +
                  "); at most " + num(max_time_steps) + " (End time <= " + num(max_time_steps * dt) +
                  " s) are allowed");
      }
      require(s.time_stepping.output_rate > 0, "Time stepping/Output rate", s.time_stepping.output_rate, "must be > 0 1/s");
    }

    void validate_supports(const Scene &s)
    {
      if (s.supports.elastic())
        {
          require(s.supports.rotational_stiffness > 0, "Supports/Rotational stiffness", s.supports.rotational_stiffness,
                  "must be > 0 N m/rad for elastic supports (use Type = clamped for the ideal clamp)");
          require(s.supports.axial_stiffness > 0, "Supports/Axial stiffness", s.supports.axial_stiffness,
                  "must be > 0 N/m for elastic supports");
        }
    }
  } // namespace

  void validate_scene(const Scene &s)
  {
    require_recordable(s);
    // NaN and infinity pass no check below silently: every comparison with
    // NaN is false, so each require() states the allowed set positively.
    validate_slider_mass(s);
    require(std::isfinite(s.contact.gravity), "Contact/Gravity", s.contact.gravity, "must be finite");
    require(std::isfinite(s.excitation.acceleration_amplitude), "Excitation/Acceleration amplitude",
            s.excitation.acceleration_amplitude, "must be finite");
    require(std::isfinite(s.contact.friction_coefficient), "Contact/Friction coefficient",
            s.contact.friction_coefficient, "must be finite");
    require(std::isfinite(s.slider.com_offset), "Slider/Centre of mass offset", s.slider.com_offset, "must be finite");
    require(s.discretisation.n_elements >= s.discretisation.n_modes + 1, "Discretisation/Number of elements",
            s.discretisation.n_elements,
            "must be at least Number of modes + 1 = " + std::to_string(s.discretisation.n_modes + 1) +
              " so that the mesh carries the reduced model's modes");
    require(s.beam.length > 0, "Beam/Length", s.beam.length, "must be > 0 m");
    require(s.discretisation.ritz_blocks == 1 || s.discretisation.n_static_corrections > 0, "Discretisation/Ritz blocks",
            s.discretisation.ritz_blocks,
            "must be 1 when Discretisation/Static corrections = 0: the Ritz blocks grow from the corrections' loads");
    validate_solid(s);
    validate_beam(s);
    validate_slider_window(s);
    validate_damping_and_excitation(s);
    validate_time_stepping(s);
    validate_supports(s);
  }

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

  std::vector<SolidMaterialEntry> solid_material_entries(const std::string &materials)
  {
    std::vector<SolidMaterialEntry> entries;
    std::istringstream in(materials);
    std::string entry;
    while (std::getline(in, entry, ','))
      {
        if (entry.find_first_not_of(" \t") == std::string::npos)
          continue;
        const std::string where = "Parameter 'Solid/Materials' entry '" + printable(trim(entry)) + "'";
        const auto colon = entry.find(':');
        SolidMaterialEntry m;
        m.text  = trim(entry);
        m.group = trim(entry.substr(0, colon));
        std::istringstream values(colon == std::string::npos ? "" : entry.substr(colon + 1));
        std::string rest;
        if (colon == std::string::npos || m.group.empty() ||
            !(values >> m.youngs_modulus >> m.poissons_ratio >> m.density) || (values >> rest))
          throw InputError(where + " is not 'group: E nu rho' (a group and three numbers)");
        // The ranges of Beam/Young's modulus, Solid/Poisson's ratio and
        // Beam/Density: E = 1e-300 Pa would reach the eigensolver as a
        // singular matrix.
        if (!(m.youngs_modulus >= 1e6 && m.youngs_modulus <= 1e13))
          throw InputError(where + ": E = " + num(m.youngs_modulus) + " Pa is not allowed: E must be in [1e6, 1e13] Pa");
        if (!(m.poissons_ratio >= 0 && m.poissons_ratio < 0.5))
          throw InputError(where + ": nu = " + num(m.poissons_ratio) + " is not allowed: nu must be in [0, 0.5)");
        if (!(m.density >= 1 && m.density <= 1e5))
          throw InputError(where + ": rho = " + num(m.density) +
                           " kg/m^3 is not allowed: rho must be in [1, 1e5] kg/m^3");
        for (const SolidMaterialEntry &other : entries)
          if (other.group == m.group)
            throw InputError("Parameter 'Solid/Materials' gives the region '" + printable(m.group) + "' twice ('" +
                             printable(other.text) + "' and '" + printable(m.text) + "'); give each region once");
        entries.push_back(m);
      }
    return entries;
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
        const std::string message = deal_ii_message(e);
        std::smatch m;
        if (std::regex_search(message, m, std::regex("^Line <([0-9]+)> of file <[^>]*>: *")))
          throw InputError(text.where(std::stoul(m[1])) + ": " + printable(m.suffix(), 400));
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

  std::string scene_template() { return scene_file_text(Scene()); }

  std::string scene_file_text(const Scene &scene)
  {
    ParameterHandler prm;
    Scene bound = scene; // bind_scene needs variables; this copy is only written
    SceneTables tables;
    bind_scene(prm, bound, tables);
    std::ostringstream out;
    prm.print_parameters(out, ParameterHandler::PRM);
    return out.str();
  }

  std::map<std::string, std::string> scene_parameter_values(const Scene &scene)
  {
    ParameterHandler prm;
    Scene bound = scene; // bind_scene needs variables; this copy is only written
    SceneTables tables;
    std::map<std::string, std::string> values;
    bind_scene(prm, bound, tables, &values);
    return values;
  }

  std::string command_settings_text(const std::string &command, const std::vector<CommandSetting> &settings)
  {
    ParameterHandler prm;
    prm.enter_subsection(command);
    for (const CommandSetting &c : settings)
      prm.declare_entry(c.name, c.value, Anything(), c.description);
    prm.leave_subsection();
    std::ostringstream out;
    prm.print_parameters(out, ParameterHandler::PRM);
    return out.str();
  }
} // namespace beamslider
