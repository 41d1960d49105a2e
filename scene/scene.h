// A scene: every physical and numerical parameter of one beam–slider set-up.
//
// The values are read from a deal.II parameter file (meshes/*.prm, see
// scene_parameters.cc). This header holds plain data only, so that the reduced
// model, the contact code and the tests can use a scene without pulling in
// deal.II headers. All quantities are SI (m, kg, s, N, rad) unless a name says
// otherwise (e.g. `_hz`, `_over_L`).
//
// Physics: doc/physics.md §1 (beam on elastic supports, von Kármán kinematics,
// rigid slider with clearance, base excitation w0 = (a/Ω²) cos Ωt).
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace beamslider
{
  // An error the user can fix: bad input, a missing file, a parameter out of
  // range. The message names the parameter, its value and what is allowed.
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // The cross-section and material of (a part of) the beam.
  struct BeamSection
  {
    double width          = 0; // b [m]
    double thickness      = 0; // h [m]
    double youngs_modulus = 0; // E [Pa]
    double density        = 0; // rho [kg/m^3]

    double area() const { return width * thickness; }                                        // A [m^2]
    double second_moment() const { return width * thickness * thickness * thickness / 12.; } // I [m^4]
    double mass_per_length() const { return density * area(); }                              // rho A [kg/m]
    double bending_stiffness() const { return youngs_modulus * second_moment(); }            // EI [N m^2]
    double axial_stiffness() const { return youngs_modulus * area(); }                       // EA [N]
  };

  // One element of a beam read from a mesh file: it spans [x_begin, x_end]
  // [m] and has the section of its physical tag.
  struct BeamMeshCell
  {
    double x_begin   = 0;
    double x_end     = 0;
    unsigned int tag = 0;
  };

  // A rigid body fixed to the beam at x: mass on w(x), rotary inertia on w'(x).
  struct PointMass
  {
    double position       = 0; // x [m]
    double mass           = 0; // [kg]
    double rotary_inertia = 0; // about its own centre of mass [kg m^2]
  };

  // The thickness along the beam, constant on each element: what the slider's
  // corners touch (the surfaces are at ±h(x)/2).
  struct ThicknessProfile
  {
    std::vector<double> x_end;     // right end of each piece [m], increasing
    std::vector<double> thickness; // h on each piece [m]

    ThicknessProfile(double uniform_thickness = 0) // NOLINT: a uniform beam is a profile of one piece
      : x_end{std::numeric_limits<double>::infinity()}
      , thickness{uniform_thickness}
    {}
    // h at x [m]; at a step, the piece to the right.
    double at(const double x) const
    {
      if (thickness.size() == 1)
        return thickness[0];
      const auto it = std::upper_bound(x_end.begin(), x_end.end(), x);
      return thickness[std::min<std::size_t>(it - x_end.begin(), thickness.size() - 1)];
    }
    double largest() const { return *std::max_element(thickness.begin(), thickness.end()); }
  };

  // The beam. Without a mesh file it is uniform: the section (width,
  // thickness, E, rho) below along the whole length, and the FE mesh is
  // generated. With a mesh file (doc/scenes.md, "Beams from a mesh"), the
  // elements and their sections come from the mesh and the scene's Sections
  // table; `length` is the mesh's length and the uniform section fields hold
  // the thickest section, the reference to which R/h and amplitudes "in
  // thicknesses" refer.
  struct BeamData
  {
    double length        = 0.14;    // L [m]
    double width         = 14.04e-3; // b [m]
    double thickness     = 1.0e-3;  // h [m]
    double youngs_modulus = 210e9;  // E [Pa]
    double density       = 7683.;   // rho [kg/m^3]

    std::string mesh_file;                        // Gmsh file, absolute path; empty: uniform generated beam
    std::vector<BeamMeshCell> mesh_cells;         // the mesh's elements from x = 0 to L
    std::map<unsigned int, BeamSection> sections; // by physical tag
    std::vector<PointMass> point_masses;          // rigid bodies fixed to the beam

    bool from_mesh() const { return !mesh_cells.empty(); }
    BeamSection uniform_section() const { return {width, thickness, youngs_modulus, density}; }
    ThicknessProfile thickness_profile() const;
    // ∫₀ᴸ dx / EA(x) [m/N]: the beam's axial compliance (L/EA when uniform).
    double axial_compliance() const;

    // The uniform (or reference) section's properties.
    double area() const { return uniform_section().area(); }                           // A [m^2]
    double second_moment() const { return uniform_section().second_moment(); }         // I [m^4]
    double mass_per_length() const { return uniform_section().mass_per_length(); }     // rho A [kg/m]
    double bending_stiffness() const { return uniform_section().bending_stiffness(); } // EI [N m^2]
    double axial_stiffness() const { return uniform_section().axial_stiffness(); }     // EA [N]
  };

  inline ThicknessProfile BeamData::thickness_profile() const
  {
    if (!from_mesh())
      return ThicknessProfile(thickness);
    ThicknessProfile p;
    p.x_end.clear();
    p.thickness.clear();
    for (const BeamMeshCell &c : mesh_cells)
      {
        const double h = sections.at(c.tag).thickness;
        if (!p.thickness.empty() && p.thickness.back() == h)
          p.x_end.back() = c.x_end; // merge elements of equal thickness
        else
          {
            p.x_end.push_back(c.x_end);
            p.thickness.push_back(h);
          }
      }
    return p;
  }

  inline double BeamData::axial_compliance() const
  {
    if (!from_mesh())
      return length / axial_stiffness();
    double compliance = 0;
    for (const BeamMeshCell &c : mesh_cells)
      compliance += (c.x_end - c.x_begin) / sections.at(c.tag).axial_stiffness();
    return compliance;
  }

  // Both ends carry w = 0, a rotational spring on w' and an axial spring on u.
  // "clamped" is the limit of infinite springs and is imposed by constraints.
  //
  // k_t is the TOTAL axial stiffness of the clamping, as Müller, Beck & Krack
  // (2023) define it: the two supports together, in series with the beam.
  // The symmetric FE model realises it with a spring 2 k_t at each end (two
  // springs 2 k_t in series are k_t).
  //
  // Supports (Type in the scene): elastic (the springs), clamped (w = w' =
  // u = 0 at both ends), pinned (w = u = 0, w' free: immovable hinges) and
  // clamped-pinned (clamped at x = 0, pinned at x = L). An end is pinned if
  // pinned_end says so, else clamped if ideal_clamp, else elastic.
  struct SupportData
  {
    bool   ideal_clamp          = false;
    std::array<bool, 2> pinned_end{{false, false}}; // at x = 0, x = L
    double rotational_stiffness = 125.;   // k_r, at each end [N m/rad]
    double axial_stiffness      = 1.93e7; // k_t, both ends together [N/m]

    // The axial spring the FE model puts at each end: 2 k_t [N/m].
    double axial_spring_per_end() const { return 2. * axial_stiffness; }
    // Both ends on the springs k_r, k_t (neither clamped nor pinned).
    bool elastic() const { return !ideal_clamp && !pinned_end[0] && !pinned_end[1]; }
    // The scene's Type: elastic | clamped | pinned | clamped-pinned.
    std::string type() const
    {
      if (pinned_end[0] && pinned_end[1])
        return "pinned";
      if (pinned_end[1])
        return "clamped-pinned";
      return ideal_clamp ? "clamped" : "elastic";
    }

    // Stiffness of the membrane in series with the clamping: the axial force
    // of a beam stretched by Δ is N = k_ax Δ with
    //   k_ax = (∫₀ᴸ dx/EA(x) + 1/k_t)^-1   (elastic supports, k_t in total),
    //   k_ax = (∫₀ᴸ dx/EA(x))^-1           (ideal clamp, pinned: immovable ends),
    // ∫dx/EA = L/EA for a uniform beam. Without axial inertia N is uniform
    // along x even where EA varies (N' = 0), so the series rule is exact.
    double membrane_stiffness(const BeamData &beam) const
    {
      return 1. / (beam.axial_compliance() + (elastic() ? 1. / axial_stiffness : 0.));
    }
  };

  struct SliderData
  {
    double mass              = 46.2e-3; // m [kg]
    double inertia           = 3.15e-6; // J_C about the centre of mass [kg m^2]
    double window_width      = 10e-3;   // B, distance of the contact corners [m]
    double window_height_ratio = 1.05;  // R/h [-], must exceed 1 (clearance)
    double com_offset        = 4.1e-3;  // d, centre of mass below the window centre [m]
    double mass_factor       = 1.;      // ablation: scales mass and inertia together
  };

  struct ContactData
  {
    double friction_coefficient = 0.2;  // mu [-]
    double restitution          = 0.5;  // e_N [-]
    // k_N [N/m] per corner: 0 is the rigid corner with Newton's impact law;
    // > 0 a spring–dashpot whose damping gives e_N (doc/physics.md §4).
    double normal_stiffness     = 0.;
    double gravity              = 9.81; // g [m/s^2], acts on the slider in -z
    // Contact solver: "projected" (Gauss–Seidel projections, as the authors'
    // code) or "exact-local" (each contact's 2×2 problem solved exactly).
    std::string solver = "projected";
  };

  struct ExcitationData
  {
    double frequency_hz           = 124.;  // f_ex [Hz]
    double acceleration_amplitude = 14.;   // base acceleration amplitude a [m/s^2]
  };

  struct InitialStateData
  {
    double slider_position_over_L = 0.3; // x_C / L at t = 0 [-]
  };

  struct DiscretisationData
  {
    unsigned int n_elements   = 32; // beam elements of the FE model
    unsigned int axial_degree = 2;  // polynomial degree of the axial field u
    unsigned int n_modes      = 5;  // N, bending modes kept by the reduced model
    // Static corrections the reduced model adds to its N modes: the
    // residual flexibility of unit point loads at m positions evenly over
    // the beam (fem/static_corrections.h); 0: the modes alone.
    unsigned int n_static_corrections = 0;
    // Blocks of such vectors: 1, the static corrections alone; b > 1 adds
    // b − 1 blocks of load-dependent Ritz vectors (K⁻¹M times the block
    // before), m vectors each.
    unsigned int ritz_blocks = 1;
    bool geometric_nonlinearity = true; // von Kármán bending–stretching coupling
  };

  struct TimeSteppingData
  {
    double time_step   = 2e-5; // Delta t [s] of the reduced model (ROM)
    // Delta t [s] and Moreau–Jean θ ∈ [0.5, 1] (fem/fe_transient.h) of the
    // FE model, used by every `--model fe` command and by the error ladder's
    // FE reference. θ = 0.5 is the implicit midpoint rule, no numerical
    // damping; above 0.5 the modes the step cannot resolve (ωΔt ≳ 1) are
    // damped by the scheme, the resolved ones a little (damping ratio about
    // (θ − 0.5) ω Δt). The FE keeps the bending modes above the ROM's N
    // undamped, and they ring after every impact; with θ = 0.5 the end state
    // of an adaptation converges in Δt only at ≤ 1.25e-6 s, after a plateau
    // at 5e-6 … 2.5e-6 s (doc/findings.md: on mueller2023's 32
    // elements 0.493, 0.432, 0.371, 0.371, 0.409, 0.409 L at 2e-5 …
    // 6.25e-7 s). θ = 0.51 at 1e-5 s ends where the converged midpoint rule
    // ends (0.409 L) with an eighth of its steps: the defaults.
    double fe_time_step = 1e-5;
    double fe_theta     = 0.51;
    // What an impact's impulse moves in the FE step: "step" (Moreau–Jean:
    // the step's iteration matrix S = M + θΔt C + θ²Δt² K_t, so the beam mass
    // under the impact shrinks like √Δt until Δt resolves the mesh's
    // highest mode), "mass" (the mass matrix: the velocity jump of the
    // semi-discrete system, the same at every Δt) or "redistributed"
    // (Moreau–Jean with no beam mass at the two contact points: M − W A Wᵀ,
    // fem/fe_transient.h). doc/physics.md §7.
    std::string fe_impulses = "step";
    double end_time    = 60.;  // [s]
    double output_rate = 1000.; // samples per second written to trace.csv [1/s]
  };

  // The numerical settings of the solvers inside a time step (not physics:
  // they decide how exactly each step's equations are solved).
  struct SolverData
  {
    double contact_tolerance        = 1e-10; // contact impulses: relative change of ξ = G P + c per sweep [-]
    unsigned int contact_sweeps     = 5000;  // cap on the Gauss–Seidel sweeps of one contact solve
    double newton_relative_tolerance = 1e-8; // FE step: Newton's correction relative to the velocity [-]
    double newton_absolute_tolerance = 1e-13; // FE step: ... or below this [m/s]
    unsigned int newton_iterations  = 30;    // FE step: cap per step, refactorisations included
  };

  // A continuum model of the beam (subsection Solid, fem/solid_model.h): a
  // geometrically nonlinear St. Venant–Kirchhoff solid of the strip the
  // subsection Beam describes (L × b × h, E, ρ), clamped at both end faces.
  // "none" (every beam scene) leaves it out; "plane stress" is the 2D strip
  // x ∈ [0, L], z ∈ [-h/2, h/2] with the width b as out-of-plane thickness;
  // "3d" the strip x ∈ [0, L], y ∈ [-b/2, b/2], z ∈ [-h/2, h/2]. z, the last
  // coordinate, is the beam's w direction in both.
  struct SolidData
  {
    std::string continuum = "none";  // none | plane stress | 3d
    double poissons_ratio = 0.3;     // ν [-], in [0, 0.5)
    unsigned int degree   = 2;       // p of the vector FE_Q(p)
    unsigned int elements_along_length      = 70; // generated strip's elements in x
    unsigned int elements_across_width      = 4;  // ... in y (3d only)
    unsigned int elements_through_thickness = 1;  // ... in z
    // A shallow arch: the generated strip's mid-surface lifted to
    // z₀(x) = rise · sin(π x / L) (0: the flat strip) [m].
    double arch_rise = 0;

    // A solid mesh instead of the generated strip (fem/solid_mesh.h):
    // Gmsh .msh (format 2 or 4) or Abaqus .inp, absolute path; empty: generated.
    std::string mesh_file;
    // Physical groups of the mesh's boundary faces, by Gmsh name or tag:
    // the clamped ones (u = 0) and the one the line load presses on.
    std::vector<std::string> clamped_boundaries{"clamp_left", "clamp_right"};
    std::string loaded_boundary = "top";
    // Material per cell region: "group: E nu rho" entries (name or tag);
    // empty: every cell has the Beam's E and ρ and the ν above.
    std::string materials;

    bool enabled() const { return continuum != "none"; }
    bool from_mesh() const { return !mesh_file.empty(); }

    unsigned int dimension() const { return continuum == "3d" ? 3 : 2; }
  };

  struct Scene
  {
    std::string name; // file stem, e.g. "mueller2023"

    BeamData           beam;
    SupportData        supports;
    SliderData         slider;
    ContactData        contact;
    double             damping_ratio = 1e-3; // D, modal damping ratio of every mode [-]
    ExcitationData     excitation;
    InitialStateData   initial;
    DiscretisationData discretisation;
    TimeSteppingData   time_stepping;
    SolverData         solvers;
    SolidData          solid;

    double slider_mass() const { return slider.mass * slider.mass_factor; }
    double slider_inertia() const { return slider.inertia * slider.mass_factor; }
    double window_height() const { return slider.window_height_ratio * beam.thickness; } // R [m]
  };

  // The longest run a scene may ask for, in time steps (End time / Time step):
  // beyond it the step count would not be exact in a double, and a typing slip
  // (End time = 1e20) would run without bound.
  constexpr double max_time_steps = 1e11;

  // Reads a scene file, applies overrides of the form "Section/Name=value"
  // (nested sections separated by '/'), validates, and returns the scene.
  // Throws InputError for a missing file, a folder, FIFO or other non-regular
  // file, an empty file, a parameter set twice (in the file or by two
  // overrides), an unknown parameter, a value outside its pattern, or an
  // inconsistent combination (see validate_scene).
  Scene read_scene(const std::string &filename,
                   const std::vector<std::string> &overrides = {});

  // Refuses two overrides of the same parameter (InputError).
  void check_overrides_unique(const std::vector<std::string> &overrides);

  // Checks the conditions that a single-parameter pattern cannot express
  // (R > h, slider inside the beam, ...). Throws InputError.
  void validate_scene(const Scene &scene);

  // One 'group: E nu rho' entry of Solid/Materials.
  struct SolidMaterialEntry
  {
    std::string group;          // Gmsh physical name or tag
    double youngs_modulus = 0;  // E [Pa]
    double poissons_ratio = 0;  // ν [-]
    double density        = 0;  // ρ [kg/m^3]
    std::string text;           // the entry as written, for messages
  };
  // The entries of Solid/Materials, each checked: three numbers, E, ν and ρ
  // in the ranges of Beam/Young's modulus, Solid/Poisson's ratio and
  // Beam/Density, and no group given twice. Throws InputError.
  std::vector<SolidMaterialEntry> solid_material_entries(const std::string &materials);

  // Writes a complete, commented scene file with every parameter, its default,
  // unit and allowed range.
  std::string scene_template();

  // The same complete scene file with the values of `scene` (every number in
  // the shortest form that reads back exactly): the effective parameters a
  // run writes into its output folder, so that read_scene of this text gives
  // the same scene, bit for bit.
  std::string scene_file_text(const Scene &scene);

  // Every parameter of `scene` as {"Section/Name": text}, the text exactly as
  // scene_file_text writes it (the Python module's Scene.get/parameters).
  std::map<std::string, std::string> scene_parameter_values(const Scene &scene);

  // One setting of a command (an option of the command line with its
  // effective value, given or default).
  struct CommandSetting
  {
    std::string name;        // the option without dashes, e.g. "settle-time"
    std::string value;       // as given, or the default ("" if it has none)
    std::string description; // the option's help text (unit, range)
  };
  // The settings as a parameter file (deal.II ParameterHandler format) with
  // one subsection named after the command: the settings a command uses
  // besides the scene (harmonics, sweep times, ...), written next to
  // parameters.prm so that a run's folder says everything it was run with.
  std::string command_settings_text(const std::string &command, const std::vector<CommandSetting> &settings);
} // namespace beamslider
