// `beamslider statics`: the full-order nonlinear static solution of the
// scene's FE beam under a uniform dead line load, load-stepped (Newton from
// each step's equilibrium to the next). It is the independent check of every
// reduced model's static response: a ROM that is right reproduces statics.csv.
//
// On a scene with a solid the same load path is the solid's
// (command_statics_solid.cc).
//
// Sign: --line-load Q is positive downward (against +w, the direction of
// gravity in every scene); w_mid_m is the mid-span deflection in +w, so a
// downward load gives w_mid_m < 0.
#include "contact/csv_writer.h"
#include "fem/fe_beam.h"
#include "fem/fe_statics.h"
#include "fem/vtk_beam_output.h"
#include "meshes/scene.h"
#include "verification/cli/commands.h"
#include "verification/studies/console.h"

#include <chrono>
#include <cmath>

namespace beamslider
{
  int run_statics(const CommonOptions &common, const StaticsOptions &options)
  {
    const Scene scene = read_scene(resolve_scene_path(common.scene_file), common.overrides);
    if (!std::isfinite(options.line_load_n_per_m) || options.line_load_n_per_m == 0)
      throw InputError("--line-load = " + std::to_string(options.line_load_n_per_m) +
                       " is not allowed: the line load must be a finite, non-zero force per length [N/m]");
    if (scene.solid.enabled())
      return run_solid_statics(common, scene, options);
    const std::string dir = prepare_output_dir(common, scene, "statics");

    const auto start = std::chrono::steady_clock::now();
    const FEBeam beam(scene);
    dealii::Vector<double> F;
    beam.assemble_line_load(-options.line_load_n_per_m, F); // downward = -w
    FEStatics statics(beam);
    const std::vector<FEStatics::LoadStep> path = statics.load_path(F, options.n_steps);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const double x_mid = 0.5 * scene.beam.length;
    CsvWriter csv(dir + "/statics.csv", {"line_load_n_per_m", "w_mid_m", "newton_iterations"});
    std::vector<NamedShape> shapes;
    for (unsigned int k = 0; k < path.size(); ++k)
      {
        csv.row({CsvWriter::cell(path[k].load_factor * options.line_load_n_per_m),
                 CsvWriter::cell(beam.deflection(path[k].x, x_mid)), CsvWriter::cell(path[k].newton_iterations)});
        shapes.push_back({"step_" + std::to_string(k + 1), path[k].x, 1.});
      }
    csv.close();
    write_beam_shapes_vtu(beam, shapes, dir + "/statics.vtu", {{"line_load_n_per_m", options.line_load_n_per_m}});

    const double w_end = beam.deflection(path.back().x, x_mid);
    console() << "Statics of scene '" << scene.name << "' (" << beam.n_elements() << " elements, " << beam.n_dofs()
              << " DoFs): line load " << options.line_load_n_per_m << " N/m downward in " << options.n_steps
              << " steps, " << statics.n_linear_solves() << " Newton iterations, " << seconds << " s\n"
              << "  mid-span deflection " << w_end << " m = " << w_end / beam.thickness_at(x_mid) << " h (h at mid-span)\n"
              << "Wrote " << dir << "/statics.csv and " << dir << "/statics.vtu (displacement arrays step_k)\n";
    return 0;
  }
} // namespace beamslider
