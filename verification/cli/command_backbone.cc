// `beamslider backbone SCENE --model rom|fe`: the mode-1 backbone curve (the
// undamped nonlinear normal mode) by harmonic balance and pseudo-arclength
// continuation (reduced/harmonic_balance.h), with restarts past internal-
// resonance tongues. Writes into the output folder
//
//   backbone.csv  amplitude_over_h, frequency_hz, segment, branch, peak_over_h, relative_residual
//                 amplitude_over_h: first-harmonic amplitude of w(L/2) (relative
//                 to the moving base) over the thickness h; segment: 0, then +1
//                 after each jump over a tongue; branch: "backbone", or "tongue"
//                 for the points the continuation followed out along the tongue
//                 before it jumped;
//   eq4.csv       amplitude_over_h, frequency_hz of seed Eq. 4 (one mode, one harmonic);
//   summary.md    settings, timing, where and why the continuation stopped;
//   backbone.png  the curves (scripts/plot_backbones.py).
//
// ROM: the scene's basis on the FE modes of its mesh (N modes, and its
// static corrections and Ritz blocks when it has them), analytic cubic
// coefficients. FE: the full FE model (axial DoFs with their inertia) on the
// scene's mesh; harmonics 0…H with w odd and u even (see
// FEConservativeSystem::even_harmonic_dofs). A coarser FE mesh:
// --set "Discretisation/Number of elements=16".
#include "io/csv_writer.h"
#include "io/output_file.h"
#include "fem/fe_beam.h"
#include "fem/fe_conservative_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/static_corrections.h"
#include "scene/scene.h"
#include "reduced/beam_backbone.h"
#include "reduced/rom_operator.h"
#include "numerics/elapsed.h"
#include "verification/cli/commands.h"
#include "io/console.h"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

namespace beamslider
{
  int run_backbone(const CommonOptions &common, const BackboneOptions &options)
  {
    const Scene scene     = read_scene(resolve_scene_path(common.scene_file), common.overrides);
    const unsigned int N  = options.n_modes ? options.n_modes : scene.discretisation.n_modes;
    require_mesh_for_modes(scene.discretisation.n_elements, N, "--modes");
    const std::string dir = prepare_output_dir(common, scene, "backbone");
    const double L = scene.beam.length, h = scene.beam.thickness, pi = std::acos(-1.);
    const auto t0 = std::chrono::steady_clock::now();

    const FEBeam beam(scene);
    // The scene's basis as every ROM builds it: N modes and, when the scene
    // asks for them, its static corrections and Ritz blocks after them.
    const unsigned int m = scene.discretisation.n_static_corrections, blocks = scene.discretisation.ritz_blocks;
    const FEModes modes  = reduced_basis_vectors(beam, std::max(N, 1u), m, blocks);

    BeamBackboneSettings settings;
    settings.n_harmonics = options.n_harmonics;
    settings.thickness   = h;
    settings.end_over_h  = options.max_amplitude_over_h;
    settings.keep_points_when_interrupted = true; // Ctrl-C: the converged points are written

    Backbone backbone;
    std::string model_text;
    if (options.model == "rom")
      {
        const ReducedOrderModel rom(make_modal_basis(beam, modes), 0.);
        backbone   = compute_rom_backbone(rom, 0.5 * L, settings);
        model_text = "ROM, N = " + std::to_string(N) + " modes" +
                     (m ? " and " + std::to_string(m) + " static corrections" : std::string()) +
                     (m && blocks > 1 ? " grown by " + std::to_string(m * (blocks - 1)) + " load-dependent Ritz vectors"
                                      : std::string()) +
                     " (FE modes of " + std::to_string(beam.n_elements()) +
                     " elements, analytic coefficients), odd harmonics 1…" + std::to_string(options.n_harmonics);
      }
    else
      {
        const FEConservativeSystem fe = make_fe_conservative_system(beam);
        backbone                      = compute_fe_backbone(fe, settings);
        model_text = "FE, " + std::to_string(beam.n_elements()) + " elements, " + std::to_string(fe.system.n_dofs()) +
                     " free DoFs (u, w, θ; axial inertia kept), harmonics 0…" + std::to_string(options.n_harmonics) +
                     " (w, θ odd, u even)";
      }
    const double seconds = elapsed_seconds(t0);

    CsvWriter csv(dir + "/backbone.csv", {"amplitude_over_h", "frequency_hz", "segment", "branch", "peak_over_h", "relative_residual"});
    double a_max = 0;
    for (const auto &p : backbone.points)
      {
        csv.row({CsvWriter::cell(std::abs(p.amplitude) / h), CsvWriter::cell(p.omega / (2 * pi)), CsvWriter::cell(p.segment),
                 p.tongue ? "tongue" : "backbone", CsvWriter::cell(p.peak / h), CsvWriter::cell(p.relative_residual, 3)});
        a_max = std::max(a_max, std::abs(p.amplitude) / h);
      }

    // Seed Eq. 4 with b_111 of the analytic one-mode ROM on the same modes.
    const ReducedOrderModel rom1(make_modal_basis(beam, modes, 1), 0.);
    const double omega_1 = modes.omega[0];
    const double c = single_mode_backbone_coefficient(omega_1, rom1.analytic_cubic_terms()[0].value,
                                                      beam.deflection(modes.shapes[0], 0.5 * L), h);
    CsvWriter eq4(dir + "/eq4.csv", {"amplitude_over_h", "frequency_hz"});
    for (unsigned int i = 0; i <= 200; ++i)
      {
        const double a = options.max_amplitude_over_h * i / 200.;
        eq4.row({CsvWriter::cell(a), CsvWriter::cell(omega_1 * single_mode_backbone_ratio(c, a) / (2 * pi))});
      }

    std::ostringstream summary;
    summary << "# Backbone: scene `" << scene.name << "`, model " << options.model << "\n\n"
            << "Amplitude: first-harmonic amplitude of w(L/2), the deflection at mid-span relative to the moving base, "
               "over the thickness h = "
            << h << " m (column amplitude_over_h of backbone.csv); peak_over_h is max_t |w(L/2, t)|/h.\n\n"
            << "- model: " << model_text << "\n"
            << "- linear frequency f₁ = " << omega_1 / (2 * pi) << " Hz; Eq. 4: (ω/ω₁)² = 1 + " << c << " (ŵ/h)²\n"
            << "- continuation: pseudo-arclength from ŵ/h = " << settings.start_over_h << " to " << settings.end_over_h
            << ", restarts past tongues\n"
            << "- " << backbone.points.size() << " points, " << backbone.n_newton_iterations
            << " Newton iterations, HB with " << backbone.n_time_samples << " time samples\n"
            << "- wall time: " << backbone.seconds << " s (continuation), " << seconds << " s (with FE set-up)\n"
            << "- largest ŵ/h reached: " << a_max << (backbone.completed ? " (completed)" : " (not completed)") << "\n"
            << "- stopped: " << backbone.message << (backbone.interrupted ? " (partial results)" : "") << "\n";
    for (const auto &g : backbone.gaps)
      summary << "- jumped over an internal-resonance tongue between ŵ/h = " << g.last_amplitude / h << " (f = "
              << g.last_omega / (2 * pi) << " Hz, ω/ω₁ = " << g.last_omega / omega_1 << ") and ŵ/h = "
              << g.restart_amplitude / h << " (f = " << g.restart_omega / (2 * pi)
              << " Hz; extrapolated backbone predicted " << g.restart_omega / g.predicted_omega - 1
              << " relative off)\n";
    write_text_file(dir + "/summary.md", summary.str());

    csv.close(); // whole files, renamed into place, before the chart reads them
    eq4.close();
    if (backbone.interrupted)
      {
        // The converged points are written; no chart of a partial curve.
        // main() turns the interruption into 130/143.
        console() << "Backbone of scene '" << scene.name << "' stopped: " << backbone.message << "; wrote the "
                  << backbone.points.size() << " converged points to " << dir << "/backbone.csv (partial)\n";
        return 0;
      }
    const bool plotted = run_plot_script("plot_backbones.py", {"command", dir});
    console() << "Backbone of scene '" << scene.name << "' (" << model_text << "): " << backbone.points.size()
              << " points up to ŵ/h = " << a_max << " in " << backbone.seconds << " s; " << backbone.message << "\n";
    for (const auto &g : backbone.gaps)
      console() << "  gap (tongue) between ŵ/h = " << g.last_amplitude / h << " and " << g.restart_amplitude / h << "\n";
    console() << "Wrote " << dir << "/backbone.csv, eq4.csv, summary.md" << (plotted ? ", backbone.png" : "") << std::endl;
    return 0;
  }
} // namespace beamslider
