// beamslider.Solid's compiled part: the continuum model of a solid scene
// (fem/solid_model.h, 2D plane stress or 3D by Solid/Continuum) held in
// the Python process, its modes and its modal coefficients by the solid's
// methods, as the commands `modes` and `coefficients` compute them on a
// solid scene. MPI, PETSc and SLEPc start with the first Solid (one
// process, one rank). Calls keep the GIL: PETSc is not thread-safe.
#include "fem/petsc_session.h"
#include "fem/solid_coefficients.h"
#include "fem/solid_modes.h"
#include "fem/solid_statics.h"
#include "python/bindings.h"

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace beamslider_python
{
  namespace
  {
    // One dimension's model, its modes computed once for the most asked.
    template <int dim>
    struct SolidOfDim
    {
      explicit SolidOfDim(const beamslider::Scene &scene)
        : model(scene, MPI_COMM_WORLD)
      {}

      const beamslider::SolidModes &modes_for(const unsigned int n_bending)
      {
        if (!modes || modes->bending.size() < n_bending)
          modes = beamslider::compute_solid_modes(model, n_bending);
        return *modes;
      }

      beamslider::SolidModel<dim> model;
      std::optional<beamslider::SolidModes> modes;
    };

    class PySolid
    {
    public:
      PySolid(const std::string &path, const std::vector<std::string> &overrides)
      {
        as_value_error([&] {
          const beamslider::Scene scene = beamslider::read_scene(path, overrides);
          if (!scene.solid.enabled())
            throw beamslider::InputError("scene '" + scene.name +
                                         "' has no solid (Solid/Continuum = none): use FEBeam for the beam");
          thickness_ = scene.beam.thickness;
          beamslider::require_petsc();
          if (scene.solid.dimension() == 3)
            solid3_ = std::make_unique<SolidOfDim<3>>(scene);
          else
            solid2_ = std::make_unique<SolidOfDim<2>>(scene);
          return 0;
        });
      }

      unsigned int dimension() const { return solid3_ ? 3 : 2; }
      unsigned int n_dofs() const { return solid3_ ? solid3_->model.n_dofs() : solid2_->model.n_dofs(); }

      // The lowest modes until n_bending bending ones: every mode's
      // frequency [Hz] and shape name, and the bending ones' indices.
      py::dict modes(const unsigned int n_bending)
      {
        return solid3_ ? modes_of(*solid3_, n_bending) : modes_of(*solid2_, n_bending);
      }

      // The cubic tensor [n, j, k, l] of the first n bending modes by a
      // method (exact, step, step-relaxed, ice), as coefficients.csv.
      py::array_t<double> coefficients(const std::string &method, const unsigned int n)
      {
        return solid3_ ? coefficients_of(*solid3_, method, n) : coefficients_of(*solid2_, method, n);
      }

      // The load path of the uniform dead line load Q [N/m], downward, in
      // `steps` equal steps: each step's load, mid-span deflection [m] (+z
      // up) and Newton iterations, as the command `statics` writes them.
      py::dict statics(const double line_load, const unsigned int steps)
      {
        require_statics_load(line_load, steps);
        return solid3_ ? statics_of(*solid3_, line_load, steps) : statics_of(*solid2_, line_load, steps);
      }

    private:
      template <int dim>
      py::dict statics_of(SolidOfDim<dim> &solid, const double Q, const unsigned int steps)
      {
        std::vector<double> load, w_mid, iterations;
        beamslider::SolidStatics<dim> statics(solid.model);
        const auto F = as_value_error([&] { return statics.line_load(-Q); }); // downward = −z
        try
          {
            statics.load_path(F, steps, [&](unsigned int, const double lambda, const auto &u, const unsigned int n) {
              load.push_back(lambda * Q);
              w_mid.push_back(statics.mid_span_deflection(u));
              iterations.push_back(n);
            });
          }
        catch (const beamslider::SolidStaticSolveError &e)
          {
            throw std::runtime_error(std::string("statics of the solid: ") + e.what() + " (" +
                                     std::to_string(load.size()) + " converged steps before it)");
          }
        py::dict d;
        d["line_load_n_per_m"] = py::array(py::cast(load));
        d["w_mid_m"]           = py::array(py::cast(w_mid));
        d["newton_iterations"] = py::array(py::cast(iterations));
        return d;
      }

      template <int dim>
      py::dict modes_of(SolidOfDim<dim> &solid, const unsigned int n_bending)
      {
        const beamslider::SolidModes &m = as_value_error([&]() -> const beamslider::SolidModes & {
          return solid.modes_for(n_bending);
        });
        std::vector<double> hz;
        std::vector<std::string> shape;
        for (const beamslider::SolidMode &mode : m.all)
          {
            hz.push_back(mode.omega / (2 * M_PI));
            shape.push_back(mode.shape);
          }
        py::dict d;
        d["frequency_hz"] = py::array(py::cast(hz));
        d["shape"]        = shape;
        d["bending"]      = std::vector<unsigned int>(m.bending.begin(), m.bending.begin() + std::min<std::size_t>(n_bending, m.bending.size()));
        return d;
      }

      template <int dim>
      py::array_t<double> coefficients_of(SolidOfDim<dim> &solid, const std::string &method, const unsigned int n)
      {
        const beamslider::CubicFit fit = as_value_error([&] {
          const beamslider::SolidModes &m = solid.modes_for(n);
          beamslider::SolidModalCoefficients<dim> c(solid.model, m, n);
          return beamslider::solid_cubic_fit(c, method, thickness_);
        });
        return cubic_tensor(fit.cubic, n);
      }

      std::unique_ptr<SolidOfDim<2>> solid2_;
      std::unique_ptr<SolidOfDim<3>> solid3_;
      double thickness_ = 0;
    };
  } // namespace

  void bind_solid(py::module_ &m)
  {
    py::class_<PySolid>(m, "Solid", "The continuum model of a solid scene (use beamslider.Solid)")
      .def(py::init<const std::string &, const std::vector<std::string> &>(), py::arg("path"), py::arg("overrides"))
      .def_property_readonly("dimension", &PySolid::dimension)
      .def_property_readonly("n_dofs", &PySolid::n_dofs)
      .def("modes", &PySolid::modes, py::arg("n_bending"))
      .def("coefficients", &PySolid::coefficients, py::arg("method"), py::arg("n"))
      .def("statics", &PySolid::statics, py::arg("line_load"), py::arg("steps"));
  }
} // namespace beamslider_python
