// `beamslider modes`: the lowest bending modes of the bare beam, or of the
// beam with the slider bonded at x_C (compared with seed Eq. 5).
#include "numerics/elapsed.h"
#include "io/csv_writer.h"
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "output/vtk_beam_output.h"
#include "scene/scene.h"
#include "reduced/beam_backbone.h"
#include "verification/cli/commands.h"
#include "runtime/mpi_cells.h"
#include "io/console.h"

#include <chrono>
#include <cmath>
#include <iostream>

namespace beamslider
{
  int run_modes(const CommonOptions &common, const ModesOptions &options)
  {
    const Scene scene = read_scene(resolve_scene_path(common.scene_file), common.overrides);
    if (scene.solid.enabled())
      {
        if (options.slider_at || options.n_elements)
          throw InputError(std::string(options.slider_at ? "--slider-at" : "--elements") +
                           " is for beam scenes; this scene's Solid/Continuum is '" + scene.solid.continuum +
                           "' (the solid's mesh is set in its subsection Solid)");
        return run_solid_modes(common, scene, options.n_modes);
      }
    require_one_process("modes");
    if (options.slider_at)
      {
        // A bonded body is a point mass and inertia: any x_C on the beam is admissible.
        const double s = *options.slider_at;
        if (!(s >= 0 && s <= 1))
          throw InputError("--slider-at = " + std::to_string(s) + " is not allowed: x_C/L must lie in [0, 1]");
      }
    const std::string dir = prepare_output_dir(common, scene, "modes");

    const auto start = std::chrono::steady_clock::now();
    require_mesh_for_modes(options.n_elements ? options.n_elements : scene.discretisation.n_elements, options.n_modes,
                           "--modes");
    const FEBeam beam(scene, options.n_elements);
    const FEModes bare = compute_bending_modes(beam, options.n_modes);
    std::optional<FEModes> bonded;
    double x_C = 0;
    if (options.slider_at)
      {
        x_C    = *options.slider_at * scene.beam.length;
        bonded = compute_bending_modes(beam, options.n_modes, BondedBody{x_C, scene.slider_mass(), scene.slider_inertia()});
      }
    const double elapsed_ms = 1e3 * elapsed_seconds(start);
    const FEModes &modes = bonded ? *bonded : bare;

    if (!bonded)
      {
        CsvWriter csv(dir + "/modes.csv", {"mode", "frequency_hz"});
        for (unsigned int k = 0; k < modes.omega.size(); ++k)
          csv.row({CsvWriter::cell(k + 1), CsvWriter::cell(modes.omega[k] / (2 * M_PI))});
      }
    else
      {
        // Seed Eq. 5 with the bare beam's first mode (a Rayleigh quotient):
        // ω̃₁² = ω₁² / (1 + m φ₁(x_C)² + J φ₁'(x_C)²).
        const double phi = beam.deflection(bare.shapes[0], x_C), dphi = beam.slope(bare.shapes[0], x_C);
        const double eq5 = single_mode_backbone_frequency_with_slider(bare.omega[0], 0, 0, scene.slider_mass(),
                                                                     scene.slider_inertia(), phi, dphi);
        CsvWriter csv(dir + "/modes.csv", {"mode", "frequency_hz", "bare_beam_frequency_hz", "eq5_frequency_hz",
                                           "eq5_relative_difference"});
        for (unsigned int k = 0; k < modes.omega.size(); ++k)
          {
            const double f = modes.omega[k] / (2 * M_PI);
            csv.row({CsvWriter::cell(k + 1), CsvWriter::cell(f), CsvWriter::cell(bare.omega[k] / (2 * M_PI)),
                     k == 0 ? CsvWriter::cell(eq5 / (2 * M_PI)) : "",
                     k == 0 ? CsvWriter::cell((eq5 - modes.omega[0]) / modes.omega[0], 4) : ""});
          }
      }

    // Mode shapes, each scaled to a peak deflection of 2 h (written in the file).
    std::vector<NamedShape> shapes;
    for (unsigned int k = 0; k < modes.omega.size(); ++k)
      {
        double peak = 0;
        for (unsigned int i = 0; i <= 200; ++i)
          peak = std::max(peak, std::abs(beam.deflection(modes.shapes[k], scene.beam.length * i / 200)));
        shapes.push_back({"mode_" + std::to_string(k + 1), modes.shapes[k], 2 * scene.beam.thickness / peak});
      }
    std::vector<std::pair<std::string, double>> field_data;
    for (unsigned int k = 0; k < modes.omega.size(); ++k)
      field_data.emplace_back("frequency_hz_mode_" + std::to_string(k + 1), modes.omega[k] / (2 * M_PI));
    if (bonded)
      field_data.emplace_back("slider_x_m", x_C);
    write_beam_shapes_vtu(beam, shapes, dir + "/modes.vtu", field_data);

    console() << "Modes of scene '" << scene.name << "' (" << beam.n_elements() << " elements, " << beam.n_dofs()
              << " DoFs" << (bonded ? ", slider bonded at x_C/L = " + std::to_string(*options.slider_at) : "")
              << "): " << elapsed_ms << " ms\n";
    for (unsigned int k = 0; k < modes.omega.size(); ++k)
      console() << "  mode " << k + 1 << ": " << modes.omega[k] / (2 * M_PI) << " Hz\n";
    console() << "Wrote " << dir << "/modes.csv and " << dir << "/modes.vtu (displacement arrays mode_k, peak 2h)\n";
    return 0;
  }
} // namespace beamslider
