// The compiled part of beamslider.FEBeam and beamslider.ReducedModel: the
// FE beam's matrices, forces and modes, and the reduced model's frequencies,
// damping, cubic coefficients, force and mode shapes, from the library's own
// objects (fem/fe_beam.h, reduced/rom_operator.h as make_reduced_model
// builds it for the runs). Sparse matrices leave as CSR arrays (indptr,
// indices, data); __init__.py makes them scipy.sparse matrices.
#include "fem/fe_beam.h"
#include "fem/fe_statics.h"
#include "fem/fe_modes.h"
#include "python/bindings.h"
#include "reduced/beam_backbone.h"
#include "verification/studies/fe_rom_study.h"

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace beamslider_python
{
  namespace
  {
    using CsrArrays = std::tuple<py::array_t<py::ssize_t>, py::array_t<py::ssize_t>, py::array_t<double>>;

    // deal.II's rows (diagonal first) as CSR arrays; the Python side sorts
    // the column indices.
    CsrArrays csr(const dealii::SparseMatrix<double> &A)
    {
      const auto n = static_cast<py::ssize_t>(A.m());
      py::array_t<py::ssize_t> indptr(n + 1), indices(static_cast<py::ssize_t>(A.n_nonzero_elements()));
      py::array_t<double> data(static_cast<py::ssize_t>(A.n_nonzero_elements()));
      auto p = indptr.mutable_unchecked<1>();
      auto c = indices.mutable_unchecked<1>();
      auto v = data.mutable_unchecked<1>();
      py::ssize_t k = 0;
      for (py::ssize_t row = 0; row < n; ++row)
        {
          p(row) = k;
          for (auto entry = A.begin(row); entry != A.end(row); ++entry, ++k)
            {
              c(k) = static_cast<py::ssize_t>(entry->column());
              v(k) = entry->value();
            }
        }
      p(n) = k;
      return {indptr, indices, data};
    }

    Eigen::VectorXd to_eigen(const dealii::Vector<double> &x)
    {
      return Eigen::Map<const Eigen::VectorXd>(x.begin(), static_cast<Eigen::Index>(x.size()));
    }

    // The FE beam of a scene, matrices without constraints (every DoF kept;
    // free_dofs names the ones the modes leave free).
    class PyFEBeam
    {
    public:
      PyFEBeam(const std::string &path, const std::vector<std::string> &overrides, const unsigned int n_elements)
      {
        as_value_error([&] {
          beam_.emplace(beamslider::read_scene(path, overrides), n_elements);
          return 0;
        });
        none_.close();
      }

      unsigned int n_dofs() const { return beam_->n_dofs(); }

      CsrArrays mass() const
      {
        dealii::SparseMatrix<double> M(beam_->sparsity_pattern());
        beam_->assemble_mass_matrix(M, none_);
        return csr(M);
      }

      CsrArrays tangent(const Eigen::VectorXd &q) const
      {
        dealii::SparseMatrix<double> K(beam_->sparsity_pattern());
        beam_->assemble_internal_force(from(q), nullptr, &K, none_);
        return csr(K);
      }

      Eigen::VectorXd internal_force(const Eigen::VectorXd &q) const
      {
        dealii::Vector<double> f(beam_->n_dofs());
        beam_->assemble_internal_force(from(q), &f, nullptr, none_);
        return to_eigen(f);
      }

      // The DoFs the bending modes leave free (u = 0 and the supports'
      // constraints taken out), ascending.
      std::vector<unsigned int> free_dofs() const
      {
        std::vector<unsigned int> free;
        for (unsigned int i = 0; i < beam_->n_dofs(); ++i)
          if (!beam_->bending_constraints().is_constrained(i))
            free.push_back(i);
        return free;
      }

      std::vector<bool> axial_dofs() const { return beam_->axial_dofs(); }
      std::vector<bool> deflection_dofs() const { return beam_->deflection_dofs(); }
      std::vector<bool> slope_dofs() const { return beam_->slope_dofs(); }

      // The element ends x [m], from 0 to L.
      std::vector<double> nodes() const
      {
        std::vector<double> x;
        for (const auto &cell : beam_->cells_in_order())
          x.push_back(cell->vertex(0)[0]);
        x.push_back(beam_->cells_in_order().back()->vertex(1)[0]);
        return x;
      }

      // ω [rad/s] of the lowest n bending modes and their mass-normalised
      // shapes as columns (n_dofs × n).
      std::pair<Eigen::VectorXd, Eigen::MatrixXd> modes(const unsigned int n) const
      {
        const beamslider::FEModes modes = as_value_error([&] { return beamslider::compute_bending_modes(*beam_, n); });
        Eigen::MatrixXd shapes(beam_->n_dofs(), modes.shapes.size());
        for (std::size_t k = 0; k < modes.shapes.size(); ++k)
          shapes.col(static_cast<Eigen::Index>(k)) = to_eigen(modes.shapes[k]);
        return {Eigen::Map<const Eigen::VectorXd>(modes.omega.data(), static_cast<Eigen::Index>(modes.omega.size())),
                shapes};
      }

      // The load path of the uniform dead line load Q [N/m], downward, in
      // `steps` equal steps (the command `statics`): each step's load,
      // mid-span deflection [m] (+w up), Newton iterations and displacement.
      py::dict statics(const double Q, const unsigned int steps) const
      {
        require_statics_load(Q, steps);
        std::vector<beamslider::FEStatics::LoadStep> path;
        {
          py::gil_scoped_release no_gil;
          beamslider::FEStatics statics(*beam_);
          dealii::Vector<double> F;
          beam_->assemble_line_load(-Q, F); // downward = -w
          try
            {
              path = statics.load_path(F, steps);
            }
          catch (const beamslider::StaticSolveError &e)
            {
              throw std::runtime_error(std::string("statics of the FE beam: ") + e.what());
            }
        }
        std::vector<double> load, w_mid, iterations;
        Eigen::MatrixXd x(beam_->n_dofs(), path.size());
        for (std::size_t k = 0; k < path.size(); ++k)
          {
            load.push_back(path[k].load_factor * Q);
            w_mid.push_back(beam_->deflection(path[k].x, 0.5 * beam_->length()));
            iterations.push_back(path[k].newton_iterations);
            x.col(static_cast<Eigen::Index>(k)) = to_eigen(path[k].x);
          }
        py::dict d;
        d["line_load_n_per_m"] = py::array(py::cast(load));
        d["w_mid_m"]           = py::array(py::cast(w_mid));
        d["newton_iterations"] = py::array(py::cast(iterations));
        d["displacement"]      = x;
        return d;
      }

    private:
      dealii::Vector<double> from(const Eigen::VectorXd &q) const
      {
        if (q.size() != static_cast<Eigen::Index>(beam_->n_dofs()))
          throw py::value_error("error: q has " + std::to_string(q.size()) + " entries, the beam has " +
                                std::to_string(beam_->n_dofs()) + " DoFs");
        dealii::Vector<double> x(q.size());
        for (Eigen::Index i = 0; i < q.size(); ++i)
          x[static_cast<unsigned int>(i)] = q[i];
        return x;
      }

      std::optional<beamslider::FEBeam> beam_;
      dealii::AffineConstraints<double> none_;
    };

    // The reduced model of a scene as the runs build it.
    class PyReducedModel
    {
    public:
      PyReducedModel(const std::string &path, const std::vector<std::string> &overrides, const unsigned int n_modes,
                     const std::string &coefficients)
      {
        as_value_error([&] {
          const beamslider::Scene scene = beamslider::read_scene(path, overrides);
          beamslider::ModelSetting setting = beamslider::scene_model(scene, "rom");
          if (n_modes > 0)
            setting.n_modes = n_modes;
          if (!coefficients.empty())
            setting.coefficients = coefficients;
          rom_.emplace(beamslider::make_reduced_model(scene, setting));
          thickness_ = scene.beam.thickness;
          return 0;
        });
      }

      Eigen::VectorXd omega() const { return rom_->basis().omega; }
      Eigen::VectorXd damping() const { return rom_->damping_coefficients(); }
      double length() const { return rom_->basis().length; }

      // The tensor [n, j, k, l] of f_n = Σ t[n,j,k,l] q_j q_k q_l.
      py::array_t<double> coefficients() const { return cubic_tensor(rom_->cubic_terms(), rom_->n_modes()); }

      Eigen::VectorXd force(const Eigen::VectorXd &q) const
      {
        check(q);
        return rom_->nonlinear_force(q);
      }

      Eigen::MatrixXd tangent(const Eigen::VectorXd &q) const
      {
        check(q);
        return rom_->nonlinear_tangent(q);
      }

      // φ_n(x) and φ_n'(x) at each x, as len(x) × N matrices.
      std::pair<Eigen::MatrixXd, Eigen::MatrixXd> shapes(const std::vector<double> &x) const
      {
        const unsigned int N = rom_->n_modes();
        Eigen::MatrixXd phi(x.size(), N), dphi(x.size(), N);
        Eigen::VectorXd p(N), d(N);
        for (std::size_t i = 0; i < x.size(); ++i)
          {
            if (!(x[i] >= 0 && x[i] <= length()))
              throw py::value_error("error: x = " + std::to_string(x[i]) + " is outside the beam [0, " +
                                    std::to_string(length()) + "] m");
            rom_->basis().evaluate(x[i], p, d);
            phi.row(static_cast<Eigen::Index>(i))  = p;
            dphi.row(static_cast<Eigen::Index>(i)) = d;
          }
        return {phi, dphi};
      }

      // The mode-1 backbone by harmonic balance (odd harmonics 1…H,
      // pseudo-arclength, restarts past internal-resonance tongues) of the
      // deflection at x_out (default L/2), as the command `backbone` computes
      // it: {amplitude_over_h, frequency_hz, peak_over_h, segment, tongue}.
      py::dict backbone(const unsigned int n_harmonics, const double max_amplitude_over_h, const double x_out) const
      {
        beamslider::BeamBackboneSettings settings;
        settings.n_harmonics = n_harmonics;
        settings.thickness   = thickness_;
        settings.end_over_h  = max_amplitude_over_h;
        const double x = x_out >= 0 ? x_out : 0.5 * length();
        const beamslider::Backbone b = as_value_error([&] {
          py::gil_scoped_release no_gil;
          return beamslider::compute_rom_backbone(*rom_, x, settings);
        });
        std::vector<double> a, f, peak, segment, tongue;
        for (const auto &p : b.points)
          {
            a.push_back(std::abs(p.amplitude) / thickness_);
            f.push_back(p.omega / (2 * M_PI));
            peak.push_back(p.peak / thickness_);
            segment.push_back(p.segment);
            tongue.push_back(p.tongue);
          }
        py::dict d;
        d["amplitude_over_h"] = py::array(py::cast(a));
        d["frequency_hz"]     = py::array(py::cast(f));
        d["peak_over_h"]      = py::array(py::cast(peak));
        d["segment"]          = py::array(py::cast(segment));
        d["tongue"]           = py::array(py::cast(tongue)).attr("astype")("bool");
        d["completed"]        = b.completed;
        d["message"]          = b.message;
        return d;
      }

    private:
      void check(const Eigen::VectorXd &q) const
      {
        if (q.size() != static_cast<Eigen::Index>(rom_->n_modes()))
          throw py::value_error("error: q has " + std::to_string(q.size()) + " entries, the model has " +
                                std::to_string(rom_->n_modes()) + " modes");
      }

      std::optional<beamslider::ReducedOrderModel> rom_;
      double thickness_ = 0;
    };
  } // namespace

  void require_statics_load(const double line_load, const unsigned int steps)
  {
    as_value_error([&] {
      if (!std::isfinite(line_load) || line_load == 0)
        throw beamslider::InputError("line_load = " + std::to_string(line_load) +
                                     " is not allowed: a finite, non-zero load Q [N/m], positive downward");
      if (steps < 1 || steps > 10000)
        throw beamslider::InputError("steps = " + std::to_string(steps) + " is not in [1, 10000]");
      return 0;
    });
  }

  py::array_t<double> cubic_tensor(const std::vector<beamslider::CubicTerm> &terms, const unsigned int n_modes)
  {
    const auto N = static_cast<py::ssize_t>(n_modes);
    py::array_t<double> t({N, N, N, N});
    std::fill(t.mutable_data(), t.mutable_data() + t.size(), 0.);
    auto v = t.mutable_unchecked<4>();
    for (const beamslider::CubicTerm &term : terms)
      {
        std::vector<std::array<unsigned int, 3>> permutations;
        std::array<unsigned int, 3> p{{term.j, term.k, term.l}};
        std::sort(p.begin(), p.end());
        do
          permutations.push_back(p);
        while (std::next_permutation(p.begin(), p.end()));
        for (const auto &q : permutations)
          v(term.n, q[0], q[1], q[2]) = term.value / static_cast<double>(permutations.size());
      }
    return t;
  }

  void bind_models(py::module_ &m)
  {
    py::class_<PyFEBeam>(m, "FEBeam", "The FE beam of a scene (use beamslider.FEBeam)")
      .def(py::init<const std::string &, const std::vector<std::string> &, unsigned int>(), py::arg("path"),
           py::arg("overrides"), py::arg("elements"))
      .def_property_readonly("n_dofs", &PyFEBeam::n_dofs)
      .def("mass_csr", &PyFEBeam::mass)
      .def("tangent_csr", &PyFEBeam::tangent, py::arg("q"))
      .def("internal_force", &PyFEBeam::internal_force, py::arg("q"))
      .def("free_dofs", &PyFEBeam::free_dofs)
      .def("axial_dofs", &PyFEBeam::axial_dofs)
      .def("deflection_dofs", &PyFEBeam::deflection_dofs)
      .def("slope_dofs", &PyFEBeam::slope_dofs)
      .def("nodes", &PyFEBeam::nodes)
      .def("modes", &PyFEBeam::modes, py::arg("n"), py::call_guard<py::gil_scoped_release>())
      .def("statics", &PyFEBeam::statics, py::arg("line_load"), py::arg("steps"));
    py::class_<PyReducedModel>(m, "ReducedModel", "The reduced model of a scene (use beamslider.ReducedModel)")
      .def(py::init<const std::string &, const std::vector<std::string> &, unsigned int, const std::string &>(),
           py::arg("path"), py::arg("overrides"), py::arg("modes"), py::arg("coefficients"))
      .def_property_readonly("omega", &PyReducedModel::omega)
      .def_property_readonly("damping", &PyReducedModel::damping)
      .def_property_readonly("length", &PyReducedModel::length)
      .def_property_readonly("coefficients", &PyReducedModel::coefficients)
      .def("force", &PyReducedModel::force, py::arg("q"))
      .def("tangent", &PyReducedModel::tangent, py::arg("q"))
      .def("shapes", &PyReducedModel::shapes, py::arg("x"))
      .def("backbone", &PyReducedModel::backbone, py::arg("harmonics"), py::arg("max_amplitude_over_h"),
           py::arg("x_out"));
  }
} // namespace beamslider_python
