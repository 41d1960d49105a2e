// `beamslider coefficients` on a scene with a solid: the quadratic and cubic
// modal coefficients of its first N bending modes (fem/solid_coefficients.h),
// or of the modes `--mode-indices i,j,...` (their `mode` in modes.csv, any
// shape: torsion and lateral modes too), on every rank of an mpirun launch
// (rank 0 writes and prints).
//
//   --method exact  the reduced SVK polynomial, integrated from the cubic law
//   --method step   plain STEP: u = Φ q prescribed, every other DoF held
//   --method step-condensed  STEP with every other DoF relaxed (Φᵀ M v = 0,
//                   f(u) ∈ span MΦ; fitted at 0.03 h)
//   --method ice    ICE: modal loads M Φ f̂, full nonlinear statics, q = Φᵀ M u
//
//   coefficients.csv            n,j,k,l,value (the beam's columns and units)
//   quadratic_coefficients.csv  n,j,k,value
//   summary.md                  mesh, modes, method, b_111, solves, wall time
#include "io/output_file.h"
#include "fem/solid_coefficients.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "scene/scene.h"
#include "reduced/cubic_fit.h"
#include "numerics/elapsed.h"
#include "verification/cli/coefficient_files.h"
#include "verification/cli/commands.h"
#include "verification/cli/solid_command.h"
#include "io/console.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace beamslider
{
  namespace
  {
    template <int dim>
    int solid_coefficients(const CommonOptions &common, const Scene &scene, const std::string &method,
                           const unsigned int n_bending, const std::vector<unsigned int> &indices)
    {
      const MPI_Comm comm = MPI_COMM_WORLD;
      const bool root     = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string dir = solid_output_dir(common, scene, "coefficients");

      const auto start = std::chrono::steady_clock::now();
      const SolidModel<dim> model(scene, comm);
      // The first N bending modes, or the modes asked for by index.
      const unsigned int n_lowest = indices.empty() ? 0 : *std::max_element(indices.begin(), indices.end()) + 1;
      const SolidModes modes      = compute_solid_modes(model, indices.empty() ? n_bending : 0, n_lowest);
      std::vector<unsigned int> kept = indices;
      if (kept.empty())
        kept.assign(modes.bending.begin(), modes.bending.end());
      const unsigned int N = kept.size();
      const double modes_seconds = elapsed_seconds(start);
      SolidModalCoefficients<dim> coefficients(model, modes, kept);
      const Eigen::VectorXd omega  = coefficients.omega();
      const CubicFit fit = solid_cubic_fit(coefficients, method, scene.beam.thickness);
      const double seconds = elapsed_seconds(start);

      // Rank 0 writes and prints; a failure there is every rank's (exit 1 on all).
      fail_together(comm, [&] {
        if (!root)
          return;
        write_coefficients_csv(dir + "/coefficients.csv", fit.cubic);
        write_quadratic_coefficients_csv(dir + "/quadratic_coefficients.csv", fit.quadratic);
        std::ostringstream summary;
        summary << "# Modal coefficients of a solid: scene `" << scene.name << "`, method `" << method
                << "`, N = " << N << "\n\n"
                << "- solid: " << scene.solid.continuum << ", nu = " << scene.solid.poissons_ratio << ", "
                << model.element_name() << ", " << model.n_cells() << " cells, " << model.n_dofs() << " DoFs, "
                << dealii::Utilities::MPI::n_mpi_processes(comm) << " MPI rank(s)\n"
                << "- modes kept, n = 1 ... N of coefficients.csv (index in modes.csv, shape, Hz):";
        for (unsigned int k = 0; k < N; ++k)
          summary << (k ? "; " : " ") << kept[k] + 1 << " " << modes.all[kept[k]].shape << " "
                  << omega[k] / (2 * M_PI);
        summary << "\n- b_111 (= c^(1)_111) = " << fit.cubic.front().value << " 1/(s^2 m^2 kg)\n"
                << "- largest quadratic coefficient (0 for a flat strip): " << fit.max_abs_quadratic() << "\n"
                << "- nonlinear static solves: " << coefficients.n_static_solves()
                << " (modified Newton: " << coefficients.n_linear_solves() << " back-substitutions on "
                << coefficients.n_factorisations() << " MUMPS factorisations)\n";
        if (method == "ice")
          summary << "- relative fit residual: " << fit.relative_fit_residual << "\n";
        summary << "- wall time: " << seconds << " s (modes " << modes_seconds << " s)\n";
        write_text_file(dir + "/summary.md", summary.str());
        console() << "Coefficients of the " << scene.solid.continuum << " solid of scene '" << scene.name
                  << "' by " << method << " (N = " << N << ", " << model.n_dofs() << " DoFs): b_111 = "
                  << fit.cubic.front().value << ", " << seconds << " s\n"
                  << "Wrote " << dir << "/coefficients.csv, quadratic_coefficients.csv and summary.md\n";
      });
      return 0;
    }
  } // namespace

  int run_solid_coefficients(const CommonOptions &common, const Scene &scene, const std::string &method,
                             const unsigned int n_modes, const std::vector<unsigned int> &mode_indices)
  {
    // step-condensed means on a solid what it means on a beam: STEP with the
    // DoFs outside the kept modes relaxed.
    const std::string solid_method = method == "step-condensed" ? "step-relaxed" : method;
    if (solid_method != "exact" && solid_method != "step" && solid_method != "step-relaxed" && solid_method != "ice")
      throw InputError("--method " + method + " is not for a solid scene (Solid/Continuum = '" +
                       scene.solid.continuum + "'): use exact, step, step-condensed or ice");
    std::vector<unsigned int> indices; // 0-based into SolidModes::all
    for (const unsigned int i : mode_indices)
      {
        if (i == 0)
          throw InputError("--mode-indices: 0 is not a mode; the indices of modes.csv start at 1");
        if (std::find(indices.begin(), indices.end(), i - 1) != indices.end())
          throw InputError("--mode-indices: mode " + std::to_string(i) + " is given twice; give each mode once");
        indices.push_back(i - 1);
      }
    if (indices.size() > 10)
      throw InputError("--mode-indices: " + std::to_string(indices.size()) + " modes, at most 10");
    return run_on_solid(scene, [&](auto dim) {
      return solid_coefficients<decltype(dim)::value>(common, scene, solid_method, n_modes, indices);
    });
  }
} // namespace beamslider
