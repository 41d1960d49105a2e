// `beamslider statics` on a scene with a solid: the load path of the SVK
// strip under the uniform line load Q (the pressure Q/b on its top face,
// downward) or the modal load M φ_n f of its n-th bending mode, on every
// rank of an mpirun launch (rank 0 writes and prints). statics.csv has the
// beam's columns; w_mid_m is u_z averaged over the cross-section x = L/2,
// q_m_sqrt_kg (modal load) the coordinate φ_nᵀ M u. statics.pvtu holds the
// deformed strip at every step.
#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/output_file.h"
#include "fem/solid_coefficients.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "output/solid_output.h"
#include "fem/solid_statics.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "numerics/elapsed.h"
#include "verification/cli/commands.h"
#include "verification/cli/solid_command.h"
#include "io/console.h"

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cmath>
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
      const std::optional<double> &Q = options.line_load_n_per_m, &f = options.modal_load;
      // A modal load takes the first n bending modes as its basis Φ.
      const unsigned int n = f ? options.mode : 0;
      std::optional<SolidModes> modes;
      std::optional<SolidModalCoefficients<dim>> basis;
      if (f)
        {
          modes.emplace(compute_solid_modes(model, n));
          basis.emplace(model, *modes, n);
        }
      dealii::PETScWrappers::MPI::Vector F;
      if (Q)
        F = statics.line_load(-*Q); // downward = −z
      else
        F = basis->modal_load(*f * Eigen::VectorXd::Unit(n, n - 1));
      const double load = Q ? *Q : *f;
      std::optional<CsvWriter> csv;
      CsvOptions in_place; // each load step's row as it converges
      in_place.in_place = true;
      // Rank 0 writes; a failure there is every rank's, so that none waits in
      // the next solve for a rank that left.
      fail_together(comm, [&] {
        if (root)
          csv.emplace(dir + "/statics.csv", statics_csv_columns(options), in_place);
      });
      // The rows so far stay; a last line says where the path stopped (as the
      // beam's statics.csv, command_statics.cc).
      const auto mark_stopped = [&](const std::string &where) {
        fail_together(comm, [&] {
          if (!root)
            return;
          csv->close();
          OutputFile tail(dir + "/statics.csv", FileMode::append);
          tail.stream() << "# stopped: " << one_line(where) << '\n';
          tail.close();
        });
      };
      std::vector<dealii::PETScWrappers::MPI::Vector> states;
      double w_mid = 0, q_n = 0;
      try
        {
          statics.load_path(F, options.n_steps, [&](unsigned int, const double lambda,
                                                    const dealii::PETScWrappers::MPI::Vector &u,
                                                    const unsigned int iterations) {
            states.push_back(u);
            w_mid = statics.mid_span_deflection(u);
            if (f)
              q_n = basis->modal_coordinates(u)[n - 1]; // collective
            fail_together(comm, [&] {
              if (!root)
                return;
              std::vector<std::string> row{CsvWriter::cell(lambda * load)};
              if (f)
                row.push_back(CsvWriter::cell(q_n));
              row.push_back(CsvWriter::cell(w_mid));
              row.push_back(CsvWriter::cell(iterations));
              csv->row(row);
            });
          });
        }
      catch (const SolidStaticSolveError &e)
        {
          mark_stopped(e.what());
          throw SolidStaticSolveError(std::string(e.what()) + "; " + dir + "/statics.csv holds the " +
                                      std::to_string(states.size()) +
                                      " converged steps before it; statics.pvtu not written");
        }
      catch (const Interrupted &e)
        {
          mark_stopped("load step " + std::to_string(states.size() + 1) + " of " + std::to_string(options.n_steps) +
                       ": " + e.what());
          throw;
        }
      fail_together(comm, [&] {
        if (root)
          csv->close();
      });
      std::vector<SolidField> fields;
      for (unsigned int k = 0; k < states.size(); ++k)
        fields.push_back({"step_" + std::to_string(k + 1), &states[k], 1.});
      const std::string record = write_solid_fields(model, fields, dir, "statics");
      const double seconds     = elapsed_seconds(start);
      if (root)
        {
          console() << "Statics of the " << scene.solid.continuum << " solid of scene '" << scene.name << "' ("
                    << model.n_dofs() << " DoFs): ";
          if (Q)
            console() << "line load " << *Q << " N/m downward";
          else
            console() << "modal load " << *f << " N kg^-1/2 on bending mode " << n << " ("
                      << modes->all[modes->bending[n - 1]].omega / (2 * M_PI) << " Hz)";
          console() << " in " << options.n_steps << " steps, " << statics.n_linear_solves() << " Newton iterations, "
                    << seconds << " s\n";
          if (f)
            console() << "  modal coordinate q_" << n << " = " << q_n << " m kg^1/2 (linear: f / omega^2 = "
                      << *f / std::pow(modes->all[modes->bending[n - 1]].omega, 2) << ")\n";
          console() << "  mid-span deflection " << w_mid << " m = " << w_mid / scene.beam.thickness << " h\n"
                    << "Wrote " << dir << "/statics.csv and " << record << "\n";
        }
      return 0;
    }
  } // namespace

  int run_solid_statics(const CommonOptions &common, const Scene &scene, const StaticsOptions &options)
  {
    return run_on_solid(scene, [&](auto dim) { return solid_statics<decltype(dim)::value>(common, scene, options); });
  }
} // namespace beamslider
