// The reduced model of a solid scene: what `simulate`, `ensemble`, `map`
// and `animate` with `--model rom` run when the scene has a Solid (issue 26
// item 6). The slider's contact code asks a beam model for the deflection
// and slope of the beam line; the solid gives them from its bending modes
// (fem/solid_modal_basis.h: u_z on the mid-surface averaged over the
// width), and its own cubic coefficients:
//
//   ice       ICE on the solid (load level: linear response 0.03 h, as for
//             the beam): the default, what a user with a solid mesh gets
//   step      plain STEP on the solid (amplitudes of one thickness)
//   exact     the reduced SVK polynomial integrated from the cubic law
//   analytic  the membrane form (k_ax/2)(qᵀK'q)K'q of the solid's beam line:
//             the beam's assumption on the solid's modes
//
// Building it takes the solid's modes and, for ICE, a few hundred static
// solves (3D strip, N = 5: about a minute), far more than a whole ROM run:
// the model factory (verification/studies/fe_rom_study.cc) builds it once
// per process and scene, and an ensemble's members share it. The solid is
// solved on MPI_COMM_SELF: every rank of an mpirun launch that needs the
// model builds its own.
#pragma once

#include "scene/scene.h"
#include "reduced/modal_basis.h"
#include "reduced/rom_operator.h"

#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  struct SolidReducedModel
  {
    ModalBasis basis;              // the solid's beam line, N bending modes
    std::vector<CubicTerm> cubic;  // empty for "analytic"
    double build_seconds = 0;      // modes + coefficients, wall time
  };

  // The methods a solid scene's ROM accepts (the first is the default), and
  // the same as a list for messages.
  inline const std::vector<std::string> &solid_rom_coefficient_methods()
  {
    static const std::vector<std::string> methods{"ice", "step", "exact", "analytic"};
    return methods;
  }
  inline std::string solid_rom_coefficient_method_list()
  {
    std::string list;
    for (const std::string &m : solid_rom_coefficient_methods())
      list += (list.empty() ? "" : ", ") + m;
    return list;
  }

  // The reduced model of `scene`'s solid (scene.solid.enabled()) with
  // n_modes bending modes and cubic terms by `coefficients`; starts PETSc if
  // needed. Not thread-safe (PETSc is not): one build at a time. `progress`
  // (optional) gets a line when the build starts. Throws InputError for a
  // method the solid does not offer or a scene without a solid,
  // std::runtime_error if the solid's solves fail.
  SolidReducedModel build_solid_reduced_model(const Scene &scene, unsigned int n_modes,
                                              const std::string &coefficients,
                                              const std::function<void(const std::string &)> &progress = {});
} // namespace beamslider
