// What the compiled module's files share: bad input raised as ValueError
// with the command line's one line, and the functions that add each group
// of objects to the module (run_binding.cc, model_bindings.cc).
#pragma once

#include "scene/scene.h"
#include "reduced/rom_operator.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace beamslider
{
  struct StudyHandover;
}

namespace beamslider_python
{
  namespace py = pybind11;

  // Bad input as ValueError with the line the command line prints for it.
  template <typename F>
  auto as_value_error(F &&f)
  {
    try
      {
        return f();
      }
    catch (const beamslider::InputError &e)
      {
        const std::string what = e.what();
        throw py::value_error("error: " + what.substr(0, what.find('\n')));
      }
    catch (const std::invalid_argument &e)
      {
        const std::string what = e.what();
        throw py::value_error("error: " + what.substr(0, what.find('\n')));
      }
  }

  // Records as {column name: float array}, `values` giving each record's
  // row (indexable, one number per name) in the order of `names`.
  template <typename Record, typename Values>
  py::dict columns(const std::vector<Record> &records, const std::vector<std::string> &names, Values values)
  {
    const auto n = static_cast<py::ssize_t>(records.size());
    std::vector<py::array_t<double>> arrays;
    for (std::size_t c = 0; c < names.size(); ++c)
      arrays.emplace_back(n);
    for (py::ssize_t i = 0; i < n; ++i)
      {
        const auto row = values(records[static_cast<std::size_t>(i)]);
        for (std::size_t c = 0; c < names.size(); ++c)
          arrays[c].mutable_at(i) = row[c];
      }
    py::dict out;
    for (std::size_t c = 0; c < names.size(); ++c)
      out[py::str(names[c])] = arrays[c];
    return out;
  }

  // Refuses (ValueError) a statics load path the command statics would
  // refuse: a line load Q [N/m] that is zero or not finite, steps outside
  // [1, 10000].
  void require_statics_load(double line_load, unsigned int steps);

  // Sorted cubic terms as the tensor [n, j, k, l] (N⁴ entries): each term
  // spread evenly over the distinct permutations of (j, k, l), so that
  // f_n = Σ t[n,j,k,l] q_j q_k q_l (model_bindings.cc).
  py::array_t<double> cubic_tensor(const std::vector<beamslider::CubicTerm> &terms, unsigned int n_modes);

  // Runs `beamslider args...` in this process with the GIL released (one
  // command at a time; Ctrl-C stops it): (exit status, error text, signal
  // or 0). `handover` computes or writes a study (commands.h).
  std::tuple<int, std::string, int> run_command(const std::vector<std::string> &args, py::object progress,
                                                beamslider::StudyHandover *handover = nullptr);

  void bind_run(py::module_ &m);
  void bind_models(py::module_ &m);
  void bind_solid(py::module_ &m);
  void bind_studies(py::module_ &m);
  void bind_branches(py::module_ &m);
} // namespace beamslider_python
