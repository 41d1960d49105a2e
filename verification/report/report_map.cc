// Report section 6: the operating range. A map of the adaptation (the
// scene's ROM, one run per cell) over excitation frequency × acceleration
// around the first natural frequency with the slider bonded at its start,
// classified by the one trace analysis; the published cases run as their own
// cells and judged against the class their name says; the seed's statement
// that self-adaptation works "for a broad, yet limited, range of excitation
// frequencies around the system's first natural frequency" put in numbers.
// Only with --full (the map takes minutes); the quick report points to
// `beamslider map`.
//
// Files in <report>/map/: map.csv (as `beamslider map` writes it),
// published_cases.csv, map_*.png (scripts/plot_map.py).
#include "io/csv_writer.h"
#include "numerics/stop_request.h"
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "numerics/elapsed.h"
#include "verification/report/charts.h"
#include "verification/report/map_files.h"
#include "verification/report/report.h"
#include "io/console.h"
#include "verification/studies/map_fe_check.h"
#include "verification/studies/operating_map.h"
#include "verification/studies/simulation_cases.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <thread>

namespace beamslider
{
  namespace
  {
    std::vector<double> spaced(const double low, const double high, const unsigned int n, const double unit)
    {
      std::vector<double> v;
      for (unsigned int i = 0; i < n; ++i)
        v.push_back(std::round((low + (high - low) * i / (n - 1)) / unit) * unit);
      return v;
    }

    bool adapted(const AdaptationClass c)
    {
      return c == AdaptationClass::signature_move || c == AdaptationClass::trivial_adaption;
    }

    // Strong scaling of `beamslider map` on MPI. The same small map (24
    // ROM cells of 10 s) run as one process and under `mpirun -np 2` by
    // `time_map` (programs started by the command line); wall time around
    // the whole command, start-up included.
    std::string scaling_subsection(const std::string &dir, const std::string &scene_file,
                                   const std::vector<std::string> &overrides, const MapTimer &time_map)
    {
      std::vector<std::string> map = {"map", scene_file, "--frequency", "100:135:5", "--acceleration", "8:18:5",
                                      "--end-time", "10", "--quiet"};
      for (const std::string &o : overrides)
        map.insert(map.end(), {"--set", o});
      const std::string machine = machine_description();
      std::ostringstream md;
      CsvWriter csv(dir + "/scaling.csv", {"ranks", "cells", "wall_s", "cells_per_s", "machine"});
      const unsigned int n_cells = 8 * 3;
      std::vector<std::pair<unsigned int, double>> points;
      std::string failures;
      for (const unsigned int ranks : {1u, 2u})
        {
          const std::string out = dir + "/ranks_" + std::to_string(ranks);
          std::error_code ec;
          std::filesystem::remove_all(out, ec);
          console() << "    scaling: " << ranks << " rank(s)" << std::endl;
          const TimedMap timed = time_map(ranks, map, out);
          if (!timed.failure.empty())
            {
              failures += " " + std::to_string(ranks) + " rank(s): " + timed.failure + ".";
              continue;
            }
          points.emplace_back(ranks, timed.wall_seconds);
          csv.row({CsvWriter::cell(ranks), CsvWriter::cell(n_cells), CsvWriter::cell(timed.wall_seconds, 6),
                   CsvWriter::cell(n_cells / timed.wall_seconds, 6), machine});
        }
      csv.close();
      md << "### Strong scaling on MPI\n\nThe same map of " << n_cells
         << " ROM cells (100–135 Hz × 8–18 m/s², 10 s each) by `beamslider map` as one process and under `mpirun -np "
            "2` (" << machine << "); wall time of the whole command, start-up included.\n\n"
         << "| ranks | wall [s] | cells per second | efficiency |\n|---|---|---|---|\n";
      for (const auto &[ranks, wall] : points)
        md << "| " << ranks << " | " << fixed(wall, 1) << " | " << fixed(n_cells / wall, 2) << " | "
           << (points.front().first == 1 ? fixed(points.front().second / (ranks * wall) * 100, 0) + " %" : "–") << " |\n";
      if (!failures.empty())
        md << "\nNot measured:" << failures << "\n";
      if (points.size() > 1 && run_plot_script("plot_map_scaling.py", {dir + "/scaling.csv", dir + "/map_scaling.png"}))
        md << "\n![Strong scaling](map_scaling/map_scaling.png)\n";
      md << "\nFiles: map_scaling/scaling.csv, map_scaling/ranks_*/ (each run's own folder). On a cluster: "
            "scripts/map_hostfile.example and scripts/slurm_map.sh (README).\n\n";
      return md.str();
    }
  } // namespace

  namespace
  {
    // The map's classes against the scene's FE model on a sample of cells
    // (verification/studies/map_fe_check.h), written to map/fe_check.csv.
    std::string fe_spot_check_subsection(const Report &report, const MapGrid &grid,
                                         const std::vector<std::vector<MapMember>> &cells, const double end_time)
    {
      const auto start                     = std::chrono::steady_clock::now();
      const std::vector<std::size_t> sample = spot_check_cells(grid, cells, 4, 2);
      console() << "    map: the FE on " << sample.size() << " of its cells, at its step and half of it" << std::endl;
      const std::vector<MapSpotCheck> checks =
        run_map_spot_checks(report.scene_file, report.overrides, grid, cells, sample, end_time);
      CsvWriter csv(report.dir + "/map/fe_check.csv",
                    {"frequency_hz", "acceleration_m_s2", "boundary", "rom_outcome", "fe_outcome", "fe_half_step_outcome",
                     "fe_final_x_over_L", "fe_half_step_final_x_over_L", "fe_converged", "agrees"});
      std::ostringstream md;
      md << "**The map's classes checked by the FE.** The map is the ROM with N = 5; " << checks.size()
         << " of its cells (" << std::count_if(checks.begin(), checks.end(), [](const MapSpotCheck &c) { return c.boundary; })
         << " on class boundaries, where a model error shows first, and signature-move cells inside the region) run "
            "again with the scene's FE model at its step and at half of it, one member each over "
         << end_time << " s. The FE's class counts as converged where both steps give it.\n\n"
         << "| f [Hz] | a [m/s²] | boundary | map (ROM) | FE | FE at half the step | FE end x_C/L (half step) |\n"
            "|---|---|---|---|---|---|---|\n";
      unsigned int converged = 0, agree = 0;
      for (const MapSpotCheck &c : checks)
        {
          converged += c.fe_converged();
          agree += c.agrees();
          csv.row({fixed(c.values[0], 1), fixed(c.values[1], 1), c.boundary ? "1" : "0", to_string(c.rom),
                   to_string(c.fe), to_string(c.fe_half), CsvWriter::cell(c.fe_final_position),
                   CsvWriter::cell(c.fe_half_final_position), c.fe_converged() ? "1" : "0", c.agrees() ? "1" : "0"});
          md << "| " << fixed(c.values[0], 1) << " | " << fixed(c.values[1], 1) << " | " << (c.boundary ? "yes" : "no")
             << " | " << to_string(c.rom) << " | " << to_string(c.fe) << " | " << to_string(c.fe_half) << " | "
             << fixed(c.fe_final_position, 3) << " (" << fixed(c.fe_half_final_position, 3) << ") |\n";
        }
      csv.close();
      md << "\nThe FE's class is converged in Δt at " << converged << " of " << checks.size()
         << " cells; the map's class agrees with it at " << agree << " of those " << converged
         << ". One member per cell: on a boundary any model may fall either way (`beamslider map --model fe "
            "--members K` gives a cell an ensemble). File: map/fe_check.csv. "
         << seconds_since(start) << ".\n\n";
      return md.str();
    }

    // The map as it runs: its grid around f_s, the settings of every cell
    // and, once run, each cell's members (cell i·n_levels + j: frequency i, level j).
    struct OperatingMap
    {
      double f_s = 0; // [Hz] the first natural frequency with the slider bonded at its start
      MapGrid grid;
      MapSettings settings;
      std::vector<std::vector<MapMember>> cells;
    };

    // The scene's ROM, one member per cell over the scene's end time, on 17
    // frequencies from 0.875 to 1.25 f_s × 9 accelerations from 0.25 to 1.5
    // times the scene's.
    OperatingMap map_around_resonance(const Scene &scene)
    {
      // Around the first natural frequency with the slider bonded at its start.
      const FEBeam beam(scene);
      const double x_C     = scene.initial.slider_position_over_L * scene.beam.length;
      const FEModes bonded = compute_bending_modes(beam, 1, BondedBody{x_C, scene.slider_mass(), scene.slider_inertia()});
      OperatingMap map;
      map.f_s          = bonded.omega[0] / (2 * M_PI);
      const double f_s = map.f_s;
      const double a0  = scene.excitation.acceleration_amplitude;
      map.grid.axes.push_back({"Excitation/Frequency", "frequency_hz", spaced(0.875 * f_s, 1.25 * f_s, 17, 0.1)});
      map.grid.axes.push_back({"Excitation/Acceleration amplitude", "acceleration_m_s2", spaced(0.25 * a0, 1.5 * a0, 9, 0.1)});
      map.settings.model.family = "rom";
      map.settings.n_members    = 1;
      map.settings.end_time     = scene.time_stepping.end_time;
      return map;
    }

    // A published case run as its own cell.
    struct CaseResult
    {
      std::string name, expected;
      double f = 0, a = 0, x0 = 0;
      MapMember member;
    };

    // The published cases of this scene that a frequency × level map can
    // show, each run as its own cell (its own start and end time); those that
    // start where the map's runs start go to published_cases.csv in `dir`, to
    // be marked on the map. std::nullopt when interrupted.
    std::optional<std::vector<CaseResult>> run_published_cases(const Report &report, const Scene &scene,
                                                               const MapSettings &settings, const std::string &dir)
    {
      std::vector<CaseResult> cases;
      CsvWriter cases_csv(dir + "/published_cases.csv",
                          {"name", "frequency_hz", "acceleration_m_s2", "start_x_over_L", "expected_outcome"});
      for (const PublishedMapCase &c : published_map_cases())
        {
          if (scene.name != "mueller2023")
            break; // the published cases are those of mueller2023
          MapGrid one;
          one.axes = {{"Excitation/Frequency", "frequency_hz", {c.frequency_hz}},
                      {"Excitation/Acceleration amplitude", "acceleration_m_s2", {c.acceleration}},
                      {"Initial state/Slider position", "start_x_over_L", {c.start_over_L}}};
          MapSettings s = settings;
          s.end_time    = c.end_time;
          const std::vector<MapMember> m = run_map_cell_members(report.scene_file, report.overrides, one, 0, s);
          if (m.empty())
            return std::nullopt; // interrupted
          cases.push_back({c.name, c.expected_outcome, c.frequency_hz, c.acceleration, c.start_over_L, m.front()});
          // Marked on the map only if it starts where the map's runs start.
          if (std::abs(c.start_over_L - scene.initial.slider_position_over_L) < 1e-9)
            cases_csv.row({c.name, fixed(c.frequency_hz, 1), fixed(c.acceleration, 1), fixed(c.start_over_L, 2),
                           c.expected_outcome});
        }
      cases_csv.close();
      return cases;
    }

    // What ran, how long it took and how many cells ended in each class.
    void describe_map_runs(std::ostream &md, const Scene &scene, const OperatingMap &map, const double wall)
    {
      const MapGrid &grid = map.grid;
      std::map<std::string, unsigned int> counts;
      for (const auto &cell : map.cells)
        for (const MapMember &m : cell)
          ++counts[to_string(m.analysis.outcome)];
      md << "The scene's ROM (N = " << scene.discretisation.n_modes << ", Δt = " << scene.time_stepping.time_step
         << " s) from x_C/L = " << scene.initial.slider_position_over_L << " for " << map.settings.end_time
         << " s on every cell of a grid of " << grid.axes[0].values.size() << " frequencies from "
         << fixed(grid.axes[0].values.front(), 1) << " to " << fixed(grid.axes[0].values.back(), 1)
         << " Hz (0.875 to 1.25 times f_s = " << fixed(map.f_s, 1)
         << " Hz, the first natural frequency with the slider bonded at its start) × " << grid.axes[1].values.size()
         << " base accelerations from " << fixed(grid.axes[1].values.front(), 1) << " to "
         << fixed(grid.axes[1].values.back(), 1) << " m/s²: " << grid.n_cells()
         << " runs, one member each (a cell near a class boundary may fall either way: `beamslider map --members K` "
            "gives each cell an ensemble), "
         << fixed(wall, 0) << " s wall on " << std::max(1u, std::thread::hardware_concurrency())
         << " threads. Classes by the one trace analysis of section 4.\n\n| outcome | cells |\n|---|---|\n";
      for (const auto &[name, n] : counts)
        md << "| " << name << " | " << n << " |\n";
    }

    // Per level, the band of frequencies where the slider adapts the system
    // to resonance, against the seed's statement of a limited range.
    void describe_adaptation_band(std::ostream &md, const OperatingMap &map)
    {
      const MapGrid &grid = map.grid;
      const double f_s    = map.f_s;
      md << "\nWhere the slider adapts the system to resonance (signature move or trivial adaption: the end on the upper "
            "branch), per level:\n\n| a [m/s²] | adapting frequencies [Hz] | as f/f_s | cells adapting |\n|---|---|---|---|\n";
      const std::size_t n_f = grid.axes[0].values.size();
      for (std::size_t j = 0; j < grid.axes[1].values.size(); ++j)
        {
          double low = 0, high = 0;
          unsigned int n_adapt = 0;
          for (std::size_t i = 0; i < n_f; ++i)
            {
              const std::vector<MapMember> &cell = map.cells[i * grid.axes[1].values.size() + j];
              if (!cell.empty() && adapted(cell.front().analysis.outcome))
                {
                  const double f = grid.axes[0].values[i];
                  if (n_adapt == 0)
                    low = f;
                  high = f;
                  ++n_adapt;
                }
            }
          md << "| " << fixed(grid.axes[1].values[j], 1) << " | "
             << (n_adapt ? fixed(low, 1) + " – " + fixed(high, 1) : std::string("none")) << " | "
             << (n_adapt ? fixed(low / f_s, 3) + " – " + fixed(high / f_s, 3) : std::string("–")) << " | " << n_adapt
             << " of " << n_f << " |\n";
        }
      md << "\nThe seed states that self-adaptation works \"for a broad, yet limited, range of excitation frequencies "
            "around the system's first natural frequency\": the table gives that range at each level (where it is not "
            "one interval, the cells between low and high include others; see the map).\n\n";
    }

    // Each published case: the class found against the class its name says.
    void describe_published_cases(std::ostream &md, const std::vector<CaseResult> &cases)
    {
      if (cases.empty())
        return;
      md << "The published cases, each run as its own cell (its start and end time):\n\n"
            "| case | f [Hz] | a [m/s²] | start x_C/L | class found | the name says | end x_C/L | end ŵ/h |\n"
            "|---|---|---|---|---|---|---|---|\n";
      unsigned int agree = 0;
      for (const CaseResult &c : cases)
        {
          const std::string found = to_string(c.member.analysis.outcome);
          agree += found == c.expected;
          md << "| " << c.name << " | " << fixed(c.f, 1) << " | " << fixed(c.a, 1) << " | " << fixed(c.x0, 2) << " | "
             << found << " | " << c.expected << (found == c.expected ? "" : " (**differs**)") << " | "
             << fixed(c.member.analysis.final_position, 3) << " | " << fixed(c.member.analysis.final_amplitude, 2)
             << " |\n";
        }
      md << "\n" << agree << " of " << cases.size()
         << " published cases fall in the class their name says. The maps mark those that start where the map's runs "
            "start.\n\n";
    }
  } // namespace

  std::string machine_description()
  {
    std::string model = "unknown CPU";
    std::ifstream cpuinfo("/proc/cpuinfo");
    for (std::string line; std::getline(cpuinfo, line);)
      if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos)
        {
          model = line.substr(line.find(':') + 2);
          break;
        }
    return std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " cores, " + model;
  }

  void add_map_section(Report &report, const Scene &scene, const bool full, const MapTimer &time_map)
  {
    std::ostringstream &md = report.text;
    md << "## 6. Operating range\n\n";
    if (!full)
      {
        md << "The map of the adaptation over excitation frequency and level runs with `verify --full` (a few "
              "minutes on two cores) or on its own, on any number of MPI ranks, with `beamslider map` (README).\n\n";
        return;
      }
    const auto start = std::chrono::steady_clock::now();
    console() << "  section 6: operating-range map" << std::endl;
    OperatingMap map = map_around_resonance(scene);

    const std::string dir = report.dir + "/map";
    std::filesystem::create_directories(dir);
    map.cells = run_map_cells(report.scene_file, report.overrides, map.grid, map.settings,
                              [](const std::size_t done, const std::size_t n) {
                                if (done % 10 == 0 || done == n)
                                  console() << "    map: " << done << "/" << n << " cells" << std::endl;
                              });
    if (interruption_requested())
      {
        md << "(interrupted before the map was complete)\n\n";
        return;
      }
    write_map_csv(dir + "/map.csv", map.grid, map.cells);
    const std::optional<std::vector<CaseResult>> cases = run_published_cases(report, scene, map.settings, dir);
    if (!cases)
      return; // interrupted
    const double wall = elapsed_seconds(start);

    describe_map_runs(md, scene, map, wall);
    describe_adaptation_band(md, map);
    describe_published_cases(md, *cases);
    if (run_plot_script("plot_map.py", {dir, "operating range of " + scene.name + " (ROM)"}))
      md << "![Outcome class over frequency and level](map/map_outcome_frequency_hz_acceleration_m_s2.png)\n\n"
         << "![Final slider position](map/map_final_position_frequency_hz_acceleration_m_s2.png)\n\n"
         << "![Late amplitude](map/map_late_amplitude_frequency_hz_acceleration_m_s2.png)\n\n";
    md << "Files: map/map.csv (the columns of `beamslider map`), map/published_cases.csv, map/map_*.png.\n\n";
    md << fe_spot_check_subsection(report, map.grid, map.cells, map.settings.end_time);

    const std::string scaling_dir = report.dir + "/map_scaling";
    std::filesystem::create_directories(scaling_dir);
    md << scaling_subsection(scaling_dir, report.scene_file, report.overrides, time_map);
  }
} // namespace beamslider
