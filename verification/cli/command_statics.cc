// `beamslider statics`: the full-order nonlinear static solution of the
// scene's FE beam under a dead load, load-stepped (Newton from each step's
// equilibrium to the next). It is the independent check of every reduced
// model's static response: a ROM that is right reproduces statics.csv.
//
// The load is one of
//   --line-load Q    a uniform line load Q [N/m], positive downward;
//   --modal-load f   the modal load M φ_n f [N] of bending mode n (--mode,
//                    mass-normalised φ_n, f in N kg^-1/2), along +φ_n: ICE's
//                    load (fem/fe_statics.h), whose linear response is the
//                    modal coordinate q_n = f / ω_n².
//
// On a scene with a solid the same load path is the solid's
// (command_statics_solid.cc).
//
// Sign: --line-load Q is positive downward (against +w, the direction of
// gravity in every scene); w_mid_m is the mid-span deflection in +w, so a
// downward load gives w_mid_m < 0.
#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/output_file.h"
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "fem/fe_statics.h"
#include "output/vtk_beam_output.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "numerics/elapsed.h"
#include "verification/cli/commands.h"
#include "runtime/mpi_cells.h"
#include "io/console.h"

#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

namespace beamslider
{
  int run_statics(const CommonOptions &common, const StaticsOptions &options)
  {
    const Scene scene = read_scene(resolve_scene_path(common.scene_file), common.overrides);
    const std::optional<double> &Q = options.line_load_n_per_m, &f = options.modal_load;
    if (Q.has_value() == f.has_value())
      throw InputError("statics needs exactly one load: --line-load Q [N/m] or --modal-load f [N kg^-1/2]");
    for (const auto &[name, value] : {std::pair{"--line-load", Q}, std::pair{"--modal-load", f}})
      if (value && (!std::isfinite(*value) || *value == 0))
        throw InputError(std::string(name) + " = " + std::to_string(*value) + " is not allowed: the load must be "
                         "finite and non-zero");
    if (scene.solid.enabled())
      return run_solid_statics(common, scene, options);
    require_one_process("statics");
    const std::string dir = prepare_output_dir(common, scene, "statics");

    const auto start = std::chrono::steady_clock::now();
    const FEBeam beam(scene);
    // The modal load's mode; FEStatics' basis Φ is then modes 1 … n.
    const unsigned int n = f ? options.mode : 0;
    const FEModes modes = n > 0 ? compute_bending_modes(beam, n) : FEModes{};
    FEStatics statics = n > 0 ? FEStatics(beam, modes, n) : FEStatics(beam);
    dealii::Vector<double> F;
    if (Q)
      beam.assemble_line_load(-*Q, F); // downward = -w
    else
      F = statics.modal_load(*f * Eigen::VectorXd::Unit(n, n - 1));
    // Each step's row as it converges (in place, like the solid's), so that
    // a failed step leaves the rows before it and a last line "# stopped: …"
    // that says where it stopped; a normal run's file is as before.
    const double x_mid = 0.5 * scene.beam.length, load = Q ? *Q : *f;
    CsvOptions in_place;
    in_place.in_place = true;
    CsvWriter csv(dir + "/statics.csv", statics_csv_columns(options), in_place);
    std::vector<NamedShape> shapes;
    unsigned int n_converged = 0;
    const auto write_row = [&](const FEStatics::LoadStep &step) {
      std::vector<std::string> row{CsvWriter::cell(step.load_factor * load)};
      if (f)
        row.push_back(CsvWriter::cell(statics.modal_coordinates(step.x)[n - 1]));
      row.push_back(CsvWriter::cell(beam.deflection(step.x, x_mid)));
      row.push_back(CsvWriter::cell(step.newton_iterations));
      csv.row(row);
      ++n_converged;
    };
    // The rows so far stay; a last line says where the path stopped.
    const auto mark_stopped = [&](const std::string &where) {
      csv.close();
      OutputFile tail(dir + "/statics.csv", FileMode::append);
      tail.stream() << "# stopped: " << one_line(where) << '\n';
      tail.close();
    };
    std::vector<FEStatics::LoadStep> path;
    try
      {
        path = statics.load_path(F, options.n_steps, write_row);
      }
    catch (const Interrupted &e)
      {
        mark_stopped("load step " + std::to_string(n_converged + 1) + " of " + std::to_string(options.n_steps) + ": " +
                     e.what());
        throw;
      }
    catch (const StaticSolveError &e)
      {
        mark_stopped(e.what());
        throw StaticSolveError(std::string(e.what()) + "; " + dir + "/statics.csv holds the " +
                               std::to_string(n_converged) + " converged steps before it; statics.vtu not written");
      }
    const double seconds = elapsed_seconds(start);
    for (unsigned int k = 0; k < path.size(); ++k)
      shapes.push_back({"step_" + std::to_string(k + 1), path[k].x, 1.});
    csv.close();
    write_beam_shapes_vtu(beam, shapes, dir + "/statics.vtu",
                          {{Q ? "line_load_n_per_m" : "modal_load_n_per_sqrt_kg", load}});

    const double w_end = beam.deflection(path.back().x, x_mid);
    console() << "Statics of scene '" << scene.name << "' (" << beam.n_elements() << " elements, " << beam.n_dofs()
              << " DoFs): ";
    if (Q)
      console() << "line load " << *Q << " N/m downward";
    else
      console() << "modal load " << *f << " N kg^-1/2 on bending mode " << n << " (" << modes.omega[n - 1] / (2 * M_PI)
                << " Hz)";
    console() << " in " << options.n_steps << " steps, " << statics.n_linear_solves() << " Newton iterations, "
              << seconds << " s\n";
    if (f)
      console() << "  modal coordinate q_" << n << " = " << statics.modal_coordinates(path.back().x)[n - 1]
                << " m kg^1/2 (linear: f / omega^2 = " << *f / std::pow(modes.omega[n - 1], 2) << ")\n";
    console() << "  mid-span deflection " << w_end << " m = " << w_end / beam.thickness_at(x_mid)
              << " h (h at mid-span)\n"
              << "Wrote " << dir << "/statics.csv and " << dir << "/statics.vtu (displacement arrays step_k)\n";
    return 0;
  }
} // namespace beamslider
