// Reading and checking scene files (meshes/*.prm) with deal.II's
// ParameterHandler. Every entry is declared once, in bind_scene(), with a
// typed pattern, a documentation string that gives its unit (so that
// `scene_template()` writes a self-documenting file) and the Scene field it
// is read into. Ranges that a pattern cannot express (strict
// inequalities, relations between parameters) are checked in validate_scene().
//
// This file holds the declarations (bind_scene); reading a scene is in
// scene_parameters_read.cc and scene_file_reader.cc, the checks are in
// scene_validation.cc, the writing in scene_parameters_write.cc.
#include "scene.h"

#include "scene/scene_parameters_internal.h"

#include <deal.II/base/parameter_handler.h>

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace beamslider
{
  namespace internal
  {
    // The shortest text that reads back to the same double (so that a scene
    // written by scene_file_text reads back bit for bit).
    std::string num(const double x)
    {
      std::array<char, 32> buffer;
      const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
      return std::string(buffer.data(), result.ptr);
    }
  } // namespace internal

  namespace
  {
    using dealii::ParameterHandler;
    using dealii::Patterns::Anything;
    using dealii::Patterns::Bool;
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    using dealii::Patterns::Map;
    using dealii::Patterns::Selection;
    using internal::num;
    using internal::SceneTables;

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
      e.bind("Normal stiffness", s.contact.normal_stiffness, Double(0),
             "k_N per corner [N/m]: 0 is a rigid corner with Newton's impact law; > 0 a spring-dashpot "
             "contact whose impacts last about pi sqrt(m / (2 k_N)), its damping set so that the slider "
             "landing flat on a rigid surface leaves with e_N times its speed (doc/physics.md section 4)");
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
      e.bind("FE impulses", s.time_stepping.fe_impulses, Selection("step|mass|redistributed"),
             "what an impact's impulse moves in the FE step: step (Moreau-Jean, through the step's iteration matrix "
             "M + theta^2 Delta t^2 K: the beam mass under an impact shrinks like sqrt(Delta t)), mass (through the "
             "mass matrix: the semi-discrete system's velocity jump, the same at every Delta t) or redistributed "
             "(Moreau-Jean with the beam's mass taken away from the two contact points: M - W A W^T, about half "
             "an element's mass a point)");
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
  } // namespace

  namespace internal
  {
    // Every entry of a scene, with the values of `s` as defaults, bound to
    // the fields of `s` (and to `tables` for the Sections and Point masses
    // tables, which build_beam() assembles into the beam afterwards): Scene{}
    // (the default scene, mueller2023) for reading and the template, a run's
    // own scene for the effective parameters it writes (scene_file_text).
    void bind_scene(ParameterHandler &prm, Scene &s, SceneTables &tables,
                    std::map<std::string, std::string> *values)
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
  } // namespace internal
} // namespace beamslider
