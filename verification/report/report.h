// The verification report: a Markdown file assembled from sections, each
// written by one study (frequencies, coefficients, backbones, contact cases,
// ...) together with its CSV files and PNG charts in the same folder.
#pragma once

#include "scene/scene.h"
#include "verification/studies/number_text.h"
#include "verification/studies/pcs_sweep.h"
#include "verification/studies/simulation_cases.h"

#include <sstream>
#include <functional>
#include <string>
#include <vector>

namespace beamslider
{
  struct Report
  {
    std::string dir;          // output folder (report.md, CSV, PNG)
    std::ostringstream text;  // Markdown
    // Where the scene came from, for sections that re-read it with more
    // overrides (the contact cases).
    std::string scene_file;
    std::vector<std::string> overrides;
    // Section 5's error ladder with its diagnostic rungs (`--diagnostics`).
    bool ladder_diagnostics = false;
  };

  // "2 cores, <CPU model>": the machine a report's wall times were measured
  // on (report_map.cc).
  std::string machine_description();

  // Section 1: linear frequencies. FE against the clamped–clamped and the
  // spring-supported characteristic equations on refined meshes (error and
  // observed order per mode), the bonded slider against seed Eq. 5, and the
  // choice of the default mesh.
  void add_frequency_section(Report &report, const Scene &scene);

  // Section 2: cubic coefficients, analytic vs STEP (plain, condensed) vs ICE
  // vs FE-implied, with the load-level study (report_coefficients.cc).
  void add_coefficient_section(Report &report, const Scene &scene, bool full);

  // Section 3: backbone curves, ROM (N, H) against FE (report_backbones.cc).
  void add_backbone_section(Report &report, const Scene &scene, bool full);

  // Section 4: slider contact dynamics on the ROM: published cases and
  // ablations, PCS sweeps (report_contact.cc).
  // Each case runs through `run_case` (the command line's simulate).
  void add_contact_section(Report &report, const Scene &scene, bool full, const CaseRunner &run_case);

  // Section 5: FE against ROM adaptation traces, speed against accuracy,
  // failure chart (report_fe_rom.cc).
  void add_fe_rom_section(Report &report, const Scene &scene, bool full);
  // Section 6: the operating range, a map of the adaptation over frequency ×
  // level with the published cases (--full only; report_map.cc). Its
  // strong-scaling table times `beamslider map` as programs on 1 and 2
  // ranks: `time_map` (the command line's) runs the map of `arguments` on
  // `ranks` processes into `output` and returns its wall time [s] and, if it
  // failed, why.
  struct TimedMap
  {
    double wall_seconds = 0;
    std::string failure; // empty: it ran
  };
  using MapTimer = std::function<TimedMap(unsigned int ranks, const std::vector<std::string> &arguments,
                                          const std::string &output)>;
  void add_map_section(Report &report, const Scene &scene, bool full, const MapTimer &time_map);
  // Section 7: the seed's System 1 facts, each run once on the scene with
  // its verdict (system1 only; report_system1.cc).
  void add_system1_section(Report &report, const Scene &scene, bool full);
  // Section 8: where von Kármán stops being enough: the 1D FE beam against
  // the SVK solid strip with ν = 0 (plane stress) and ν = 0.3 (3D):
  // frequencies, static hardening at w = h, 2h, 4h, b_111 and the ICE
  // backbone; with --full the adaptation end state of both ROMs
  // (report_solid.cc).
  void add_solid_section(Report &report, const Scene &scene, bool full);
  // The scene overrides of section 8's 3D strip (ν = 0.3, 70 × 4 × 1 Q2
  // elements), also timed by the benchmark SolidAssembly.
  std::vector<std::string> solid_strip_3d_overrides();

  // The prescribed-position sweep (report_pcs.cc).
  // A few lines of Markdown: the jumps, the zero crossings (stable/unstable),
  // where the free slider went, and the costs.
  std::string describe(const PcsStudy &study, const Scene &scene);

  // Report subsection (part of section 4): 0.5 s settling and 0.2 s
  // averaging per position; quick mode Δx_C/L = 0.005 and a 20 s free run
  // (~15 s wall on the ROM), full mode the seed's 0.003 and the scene's whole
  // free run. (Settling 2 s instead of 0.5 s moved no jump by a step on
  // system1.)
  void add_pcs_sweep_subsection(Report &report, const Scene &scene, bool full);
  // The held slider's periodic orbits: attractor probes and the attached
  // model's branch (report_pcs.cc, verification/studies/slow_manifold.h).
  void add_slow_manifold_subsection(Report &report, const Scene &scene);
} // namespace beamslider
