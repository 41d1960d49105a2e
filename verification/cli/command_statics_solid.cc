// `beamslider statics` on a scene with a solid: the load path of the SVK
// strip under the uniform line load Q (the pressure Q/b on its top face,
// downward), on every rank of an mpirun launch (rank 0 writes and prints).
// statics.csv has the beam's columns; w_mid_m is u_z averaged over the
// cross-section x = L/2. statics.pvtu holds the deformed strip at every step.
#include "contact/csv_writer.h"
#include "fem/solid_model.h"
#include "fem/solid_output.h"
#include "fem/solid_statics.h"
#include "meshes/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/solid_command.h"
#include "verification/studies/console.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <optional>

namespace beamslider
{
  namespace
  {
    template <int dim>
    int solid_statics(const CommonOptions &common, const Scene &scene, const StaticsOptions &options)
    {
      const MPI_Comm comm = MPI_COMM_WORLD;
      const bool root     = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string dir = solid_output_dir(common, scene, "statics");

      const auto start = std::chrono::steady_clock::now();
      const SolidModel<dim> model(scene, comm);
      SolidStatics<dim> statics(model);
      const auto F = statics.line_load(-options.line_load_n_per_m); // downward = −z
      dealii::PETScWrappers::MPI::Vector u, F_k, F_previous;
      model.reinit_vector(u);
      model.reinit_vector(F_previous);
      std::optional<CsvWriter> csv;
      if (root)
        csv.emplace(dir + "/statics.csv", std::vector<std::string>{"line_load_n_per_m", "w_mid_m", "newton_iterations"});
      std::vector<dealii::PETScWrappers::MPI::Vector> states(options.n_steps);
      double w_mid = 0;
      for (unsigned int k = 1; k <= options.n_steps; ++k)
        {
          const double lambda = double(k) / options.n_steps;
          F_k                 = F;
          F_k *= lambda;
          unsigned int iterations = 0;
          try
            {
              iterations = statics.solve(F_k, u, &F_previous);
            }
          catch (const SolidStaticSolveError &e)
            {
              throw SolidStaticSolveError("load step " + std::to_string(k) + " of " + std::to_string(options.n_steps) +
                                          ": " + e.what());
            }
          F_previous = F_k;
          model.reinit_ghosted_vector(states[k - 1]);
          states[k - 1] = u;
          w_mid         = statics.mid_span_deflection(states[k - 1]);
          if (root)
            csv->row({CsvWriter::cell(lambda * options.line_load_n_per_m), CsvWriter::cell(w_mid),
                      CsvWriter::cell(iterations)});
        }
      if (root)
        csv->close();
      std::vector<SolidField> fields;
      for (unsigned int k = 0; k < states.size(); ++k)
        fields.push_back({"step_" + std::to_string(k + 1), &states[k], 1.});
      const std::string record = write_solid_fields(model, fields, dir, "statics");
      const double seconds     = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (root)
        console() << "Statics of the " << scene.solid.continuum << " solid of scene '" << scene.name << "' ("
                  << model.n_dofs() << " DoFs): line load " << options.line_load_n_per_m << " N/m downward in "
                  << options.n_steps << " steps, " << statics.n_linear_solves() << " Newton iterations, " << seconds
                  << " s\n"
                  << "  mid-span deflection " << w_mid << " m = " << w_mid / scene.beam.thickness << " h\n"
                  << "Wrote " << dir << "/statics.csv and " << record << "\n";
      return 0;
    }
  } // namespace

  int run_solid_statics(const CommonOptions &common, const Scene &scene, const StaticsOptions &options)
  {
    return run_on_solid(scene, [&](auto dim) { return solid_statics<decltype(dim)::value>(common, scene, options); });
  }
} // namespace beamslider
