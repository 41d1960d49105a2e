// `beamslider modes` on a scene with a solid (Solid/Continuum = plane stress
// or 3d): the lowest modes of the SVK strip by SLEPc, on every MPI rank of an
// mpirun launch (rank 0 writes the CSV and prints), classified as bending,
// torsion, lateral, axial or plate (fem/solid_modes.h).
//
//   modes.csv    mode, frequency_hz, shape, bending_index (1 … N for the
//                bending modes the reduced model would keep, empty for the
//                others), energy_x/y/z (shares of the kinetic energy per
//                component), twist_correlation, width_order (fem/solid_modes.h),
//                vtu_scale
//   line_modes.csv  the bending modes along the beam line as a reduced model
//                takes them (fem/solid_modal_basis.h): x_m, phi_1 … phi_N
//                [kg^-1/2], dphi_1 … dphi_N [kg^-1/2 m^-1] at 201 points
//                (not on an arch)
//   modes.pvtu   every mode as a displacement field (scaled to a peak of 2 h,
//                the factor in vtu_scale), one .vtu piece per rank
#include "io/csv_writer.h"
#include "fem/solid_modal_basis.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "output/solid_output.h"
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
    int solid_modes(const CommonOptions &common, const Scene &scene, const unsigned int n_bending)
    {
      const MPI_Comm comm = MPI_COMM_WORLD;
      const bool root     = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
      const std::string dir = solid_output_dir(common, scene, "modes");

      const auto start = std::chrono::steady_clock::now();
      const SolidModel<dim> model(scene, comm);
      const SolidModes modes = compute_solid_modes(model, n_bending);
      const double seconds   = elapsed_seconds(start);

      std::vector<SolidField> fields;
      std::vector<double> scales;
      for (unsigned int k = 0; k < modes.all.size(); ++k)
        {
          const double peak = modes.all[k].vector.linfty_norm(); // the largest displacement component
          scales.push_back(2 * scene.beam.thickness / peak);
          fields.push_back({"mode_" + std::to_string(k + 1), &modes.all[k].vector, scales.back()});
        }
      const std::string record = write_solid_fields(model, fields, dir, "modes");
      // The bending modes along the beam line, as a reduced model takes them
      // (not on an arch, whose line is curved).
      std::optional<ModalBasis> line;
      if (scene.solid.arch_rise == 0)
        line = make_solid_modal_basis(model, modes, modes.bending.size(), scene);

      // Rank 0 writes and prints; a failure there is every rank's (exit 1 on all).
      fail_together(comm, [&] {
        if (!root)
          return;
        CsvWriter csv(dir + "/modes.csv", {"mode", "frequency_hz", "shape", "bending_index", "energy_x",
                                           "energy_y", "energy_z", "twist_correlation", "width_order",
                                           "vtu_scale"});
        for (unsigned int k = 0; k < modes.all.size(); ++k)
          {
            const SolidMode &m = modes.all[k];
            const auto b       = std::find(modes.bending.begin(), modes.bending.end(), k);
            csv.row({CsvWriter::cell(k + 1), CsvWriter::cell(m.omega / (2 * M_PI)), m.shape,
                     b == modes.bending.end() ? "" : CsvWriter::cell(unsigned(b - modes.bending.begin() + 1)),
                     CsvWriter::cell(m.energy_share[0]), CsvWriter::cell(m.energy_share[1]),
                     CsvWriter::cell(m.energy_share[2]), CsvWriter::cell(m.twist_correlation),
                     CsvWriter::cell(m.width_order),
                     CsvWriter::cell(scales[k])});
          }
        csv.close();
        if (line)
          {
            std::vector<std::string> columns{"x_m"};
            const unsigned int N = line->n_modes();
            for (unsigned int n = 1; n <= N; ++n)
              columns.push_back("phi_" + std::to_string(n));
            for (unsigned int n = 1; n <= N; ++n)
              columns.push_back("dphi_" + std::to_string(n));
            CsvWriter line_csv(dir + "/line_modes.csv", columns);
            Eigen::VectorXd phi, dphi;
            for (unsigned int i = 0; i <= 200; ++i)
              {
                const double x = line->length * i / 200;
                line->evaluate(x, phi, dphi);
                std::vector<double> row{x};
                row.insert(row.end(), phi.data(), phi.data() + N);
                row.insert(row.end(), dphi.data(), dphi.data() + N);
                line_csv.numbers(row, 10);
              }
            line_csv.close();
          }
        console() << "Modes of the " << scene.solid.continuum << " solid of scene '" << scene.name << "' ("
                  << model.n_cells() << " cells, " << model.element_name() << ", " << model.n_dofs()
                  << " DoFs, nu = " << scene.solid.poissons_ratio << ", "
                  << dealii::Utilities::MPI::n_mpi_processes(comm) << " rank(s)): " << seconds << " s\n";
        for (unsigned int k = 0; k < modes.all.size(); ++k)
          console() << "  mode " << k + 1 << ": " << modes.all[k].omega / (2 * M_PI) << " Hz, "
                    << modes.all[k].shape << "\n";
        console() << "Wrote " << dir << "/modes.csv, " << (line ? "line_modes.csv and " : "") << record << "\n";
      });
      return 0;
    }
  } // namespace

  int run_solid_modes(const CommonOptions &common, const Scene &scene, const unsigned int n_bending)
  {
    // Under mpirun every rank runs this; without, MPI starts as a singleton.
    return run_on_solid(scene, [&](auto dim) { return solid_modes<decltype(dim)::value>(common, scene, n_bending); });
  }
} // namespace beamslider
