// What the compiled module's files share: bad input raised as ValueError
// with the command line's one line, and the functions that add each group
// of objects to the module (run_binding.cc, model_bindings.cc).
#pragma once

#include "meshes/scene.h"

#include <pybind11/pybind11.h>

#include <stdexcept>
#include <string>

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

  void bind_run(py::module_ &m);
  void bind_models(py::module_ &m);
} // namespace beamslider_python
