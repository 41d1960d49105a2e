// The checks of a scene that its entries' patterns cannot express: strict
// ranges, relations between parameters, text that parameters.prm can record
// and a generated strip that fits in memory (validate_scene).
#include "scene/printable.h"
#include "numerics/spring_dashpot_restitution.h"
#include "scene/scene.h"
#include "scene/scene_parameters_internal.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

namespace beamslider
{
  namespace
  {
    using internal::num;
    using internal::require_recordable;
    using internal::trim;

    void require(const bool condition, const std::string &parameter, const double value, const std::string &allowed)
    {
      if (!condition)
        throw InputError("Parameter '" + parameter + "' = " + num(value) + " is not allowed: " + allowed);
    }
  } // namespace

  namespace internal
  {
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
  } // namespace internal

  namespace
  {
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
    require(s.contact.normal_stiffness >= 0. && std::isfinite(s.contact.normal_stiffness), "Contact/Normal stiffness",
            s.contact.normal_stiffness, "must be finite and >= 0 N/m (0 for rigid corners)");
    const double e_min = s.contact.normal_stiffness > 0. ? smallest_compliant_restitution() : 0.;
    require(s.contact.normal_stiffness == 0. || s.contact.restitution > e_min, "Contact/Restitution",
            s.contact.restitution,
            "must exceed " + std::to_string(e_min) +
              " with compliant corners (Contact/Normal stiffness > 0): a dashpot that only pushes returns at least "
              "that much of the approach speed up to critical damping");
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
} // namespace beamslider
