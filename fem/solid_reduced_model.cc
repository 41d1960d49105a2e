#include "fem/solid_reduced_model.h"
#include "numerics/elapsed.h"

#include "fem/petsc_session.h"
#include "fem/solid_coefficients.h"
#include "fem/solid_modal_basis.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "reduced/cubic_fit.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>

namespace beamslider
{
  namespace
  {
    template <int dim>
    SolidReducedModel build(const Scene &scene, const unsigned int N, const std::string &method,
                            const std::function<void(const std::string &)> &progress)
    {
      const auto start = std::chrono::steady_clock::now();
      const SolidModel<dim> model(scene, MPI_COMM_SELF);
      if (progress)
        progress("reduced model from the " + scene.solid.continuum + " solid (" + std::to_string(model.n_dofs()) +
                 " DoFs): " + std::to_string(N) + " bending modes, " + method + " coefficients ...");
      const SolidModes modes = compute_solid_modes(model, N);

      SolidReducedModel rom;
      rom.basis = make_solid_modal_basis(model, modes, N, scene);
      if (method != "analytic")
        {
          SolidModalCoefficients<dim> coefficients(model, modes, N);
          // Cubic terms only: the reduced model has no quadratic ones, and
          // the straight strip (make_solid_modal_basis refuses an arch) has
          // none beyond round-off.
          rom.cubic = solid_cubic_fit(coefficients, method, scene.beam.thickness).cubic;
        }
      rom.build_seconds = elapsed_seconds(start);
      return rom;
    }

  } // namespace

  SolidReducedModel build_solid_reduced_model(const Scene &scene, const unsigned int n_modes,
                                              const std::string &coefficients,
                                              const std::function<void(const std::string &)> &progress)
  {
    if (!scene.solid.enabled())
      throw InputError("a reduced model from the solid needs a scene with a Solid (Solid/Continuum = 3d or "
                       "plane stress)");
    const auto &methods = solid_rom_coefficient_methods();
    if (std::find(methods.begin(), methods.end(), coefficients) == methods.end())
      throw InputError("coefficients '" + coefficients + "' are not available on a solid scene (Solid/Continuum = '" +
                       scene.solid.continuum + "'): use one of " + solid_rom_coefficient_method_list());
    if (n_modes == 0)
      throw InputError("a reduced model from the solid needs N >= 1 modes");
    require_petsc();
    return scene.solid.dimension() == 3 ? build<3>(scene, n_modes, coefficients, progress)
                                        : build<2>(scene, n_modes, coefficients, progress);
  }
} // namespace beamslider
