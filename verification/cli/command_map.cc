// `[mpirun -np P] beamslider map [SCENE] --frequency A:B:STEP --acceleration
// A:B:STEP [--start A:B:STEP] [--axis "Section/Name=A:B:STEP"]... [--members K]
// [--model rom|fe] [--end-time S]`: the adaptation on every cell of a grid
// (verification/studies/operating_map.h), spread over MPI ranks
// (verification/studies/mpi_cells.h).
//
// Writes into the output folder:
//   map.csv               one row per cell and member, the grid values first;
//                         each finished cell is appended and flushed at once
//   map_settings.txt      what the map is (scene content, model, members,
//                         end time, axes): a restart must match it
//   timing.csv            cell,rank,wall_s (appended; not part of the result)
//   published_cases.csv   the published cases of the scene, to mark on the maps
//   summary.md            outcome classes, cells per second, ranks
//   map_*.png             heat maps (scripts/plot_map.py)
//
// Restart: the same command on the same folder keeps the complete cells of
// map.csv (a cell cut short by a kill is dropped and computed again) and
// computes the others; the file then holds the same rows as an uninterrupted
// run, in another order.
#include "contact/csv_writer.h"
#include "contact/interruption.h"
#include "contact/output_file.h"
#include "meshes/scene.h"
#include "verification/cli/commands.h"
#include "verification/studies/mpi_cells.h"
#include "verification/studies/console.h"
#include "verification/studies/model_choice.h"
#include "verification/studies/operating_map.h"
#include "verification/studies/simulation_cases.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

namespace beamslider
{
  namespace
  {
    void write_published_cases(const std::string &path)
    {
      CsvWriter csv(path, {"name", "frequency_hz", "acceleration_m_s2", "start_x_over_L", "expected_outcome"});
      for (const PublishedMapCase &c : published_map_cases())
        csv.row({c.name, CsvWriter::cell(c.frequency_hz, 6), CsvWriter::cell(c.acceleration, 6),
                 CsvWriter::cell(c.start_over_L, 6), c.expected_outcome});
      csv.close();
    }

    std::string duration_text(const double seconds)
    {
      std::ostringstream s;
      if (seconds < 120)
        s << std::fixed << std::setprecision(0) << seconds << " s";
      else if (seconds < 7200)
        s << std::fixed << std::setprecision(1) << seconds / 60 << " min";
      else
        s << std::fixed << std::setprecision(1) << seconds / 3600 << " h";
      return s.str();
    }
  } // namespace

  int run_map(const CommonOptions &common, const MapOptions &options)
  {
    using clock = std::chrono::steady_clock;
    const auto start_time = clock::now();
    // Under mpirun every rank runs this; only rank 0 reads back, writes and prints.
    MpiSession mpi(launched_by_mpi_launcher());
    const bool root = mpi.rank() == 0;

    const std::string scene_file = resolve_scene_path(common.scene_file);
    check_overrides_unique(common.overrides);
    const Scene base = read_scene(scene_file, common.overrides);

    MapGrid grid;
    if (!options.frequency.empty())
      grid.axes.push_back({"Excitation/Frequency", "frequency_hz", parse_grid_range(options.frequency, "--frequency")});
    if (!options.acceleration.empty())
      grid.axes.push_back({"Excitation/Acceleration amplitude", "acceleration_m_s2",
                           parse_grid_range(options.acceleration, "--acceleration")});
    if (!options.start.empty())
      grid.axes.push_back(
        {"Initial state/Slider position", "start_x_over_L", parse_grid_range(options.start, "--start")});
    for (const std::string &a : options.axes)
      grid.axes.push_back(parse_parameter_axis(a));
    if (grid.axes.empty())
      throw InputError("map: no axis given: use --frequency, --acceleration, --start or --axis");
    grid.check_distinct_parameters("map");

    MapSettings settings;
    settings.model.family = options.model;
    settings.n_members    = options.members;
    settings.perturbation = options.perturbation;
    settings.end_time     = options.end_time ? *options.end_time : base.time_stepping.end_time;

    // Every cell's scene is checked before any work: a cell outside the
    // allowed ranges is an input error on every rank alike, not a dead worker.
    const std::size_t n_cells = grid.n_cells();
    for (std::size_t c = 0; c < n_cells; ++c)
      {
        const Scene s = map_cell_scene(scene_file, common.overrides, grid, c, settings.end_time);
        const double x_last = s.initial.slider_position_over_L + (settings.n_members - 1) * settings.perturbation;
        if (!(x_last < 1.))
          throw InputError("--perturbation " + std::to_string(settings.perturbation) +
                           " moves the last member's start beyond the beam in cell " + map_cell_key(grid, c));
      }

    const std::vector<std::string> columns = map_csv_columns(grid);
    std::string dir, map_csv;
    std::optional<CsvWriter> map_rows, timing; // rank 0's map.csv and timing.csv
    std::vector<std::size_t> todo;
    std::size_t n_skipped = 0;
    if (root)
      {
        // What this map is; a restart into the same folder must be the same map.
        std::ostringstream what;
        what << "scene " << base.name << " content " << scene_content_key(base) << "\nmodel " << options.model
             << "\nmembers " << settings.n_members << "\nperturbation " << settings.perturbation << "\nend time "
             << settings.end_time << " s\n";
        for (const std::string &o : common.overrides)
          what << "set " << o << "\n";
        for (const MapAxis &a : grid.axes)
          {
            what << "axis " << a.parameter << " =";
            for (const double v : a.values)
              what << ' ' << v;
            what << "\n";
          }
        // Checked before anything in the folder is written: a folder of
        // another map is refused as it is (its parameters.prm and
        // command.prm still describe that map).
        const std::string planned = output_dir_path(common, base, "map");
        if (std::filesystem::is_directory(planned))
          lock_output_folder(planned);
        const std::string previous = read_text_file_if_present(planned + "/map_settings.txt");
        if (!previous.empty() && previous != what.str())
          throw InputError("the output folder '" + planned + "' holds a map with other settings (" + planned +
                           "/map_settings.txt); use another --output or remove that folder");
        dir     = prepare_output_dir(common, base, "map");
        map_csv = dir + "/map.csv";
        const std::string settings_path = dir + "/map_settings.txt";
        std::map<std::string, std::string> finished;
        if (!previous.empty())
          finished = read_finished_cells(map_csv, columns, settings.n_members);
        write_text_file(settings_path, what.str());
        // map.csv anew with the complete cells only (atomically: a kill now
        // leaves the old file or the new one).
        std::string kept = CsvWriter::line(columns) + "\n";
        for (const auto &[key, rows] : finished)
          kept += rows;
        write_file_atomically(map_csv, kept);
        // The cells computed now are appended, each row flushed as written.
        CsvOptions continued;
        continued.append = true;
        map_rows.emplace(map_csv, columns, continued);
        CsvOptions timing_options;
        timing_options.in_place = true; // rows as cells finish
        // A resumed map appends to the timing rows it has (its header is there).
        std::error_code no_file;
        timing_options.append = std::filesystem::file_size(dir + "/timing.csv", no_file) > 0 && !no_file;
        timing.emplace(dir + "/timing.csv", std::vector<std::string>{"cell", "rank", "wall_s"}, timing_options);
        for (std::size_t c = 0; c < n_cells; ++c)
          if (finished.count(map_cell_key(grid, c)))
            ++n_skipped;
          else
            todo.push_back(c);
        write_published_cases(dir + "/published_cases.csv");

        console() << "map " << base.name << ": " << n_cells << " cells";
        for (const MapAxis &a : grid.axes)
          console() << (&a == &grid.axes.front() ? " (" : " x ") << a.values.size() << " " << a.column;
        console() << ") x " << settings.n_members << " member(s) of " << options.model << ", " << settings.end_time
                  << " s each, on " << mpi.size() << " rank(s)";
        if (n_skipped)
          console() << "; " << n_skipped << " cells already in map.csv are kept";
        console() << "; into " << dir << std::endl;
      }

    std::size_t n_done = 0;
    std::map<std::string, unsigned int> class_counts;
    const auto work_start = clock::now();
    distribute_cells(
      mpi, todo,
      [&](const std::size_t cell) {
        const auto t0        = clock::now();
        std::string rows     = run_map_cell(scene_file, common.overrides, grid, cell, settings);
        const double seconds = std::chrono::duration<double>(clock::now() - t0).count();
        if (!rows.empty())
          rows += "#wall " + std::to_string(seconds) + "\n"; // carried to rank 0 for timing.csv, not written to map.csv
        return rows;
      },
      [&](const std::size_t cell, const std::string &result, const unsigned int rank) {
        const std::size_t cut = result.rfind("#wall ");
        const std::string rows = result.substr(0, cut);
        const double wall = cut == std::string::npos ? 0. : std::stod(result.substr(cut + 6));
        std::istringstream lines(rows);
        std::string line;
        while (std::getline(lines, line))
          {
            const std::vector<std::string> cells = CsvWriter::cells(line);
            map_rows->row(cells);
            ++class_counts[cells[grid.axes.size() + 3]]; // the outcome column
          }
        timing->row({"\"" + map_cell_key(grid, cell) + "\"", std::to_string(rank), std::to_string(wall)});
        ++n_done;
        const double elapsed = std::chrono::duration<double>(clock::now() - work_start).count();
        const double rate    = n_done / elapsed;
        console() << "  cells " << n_done + n_skipped << "/" << n_cells << " (" << map_cell_key(grid, cell)
                  << " on rank " << rank << ", " << std::fixed << std::setprecision(1) << wall << " s), "
                  << std::setprecision(3) << rate * 60 << " cells/min, about "
                  << duration_text((todo.size() - n_done) / rate) << " left" << std::defaultfloat << std::endl;
      },
      [] { return interruption_requested(); });

    if (!root)
      return 0;
    const double wall = std::chrono::duration<double>(clock::now() - start_time).count();
    const double work_wall = std::chrono::duration<double>(clock::now() - work_start).count();
    if (interruption_requested() || n_done < todo.size())
      {
        std::cerr << "map: stopped after " << n_done << " of " << todo.size()
                  << " cells; map.csv holds every finished cell: run the same command again to continue" << std::endl;
        return interruption_requested() ? 0 : 1; // main() turns an interruption into 130/143
      }

    std::ostringstream summary;
    summary << "# Map: scene `" << base.name << "`\n\n- Axes:";
    for (const MapAxis &a : grid.axes)
      summary << " " << a.parameter << " (" << a.values.size() << " values, " << a.values.front() << " … "
              << a.values.back() << ");";
    summary << "\n- " << n_cells << " cells × " << settings.n_members << " member(s), " << options.model << ", "
            << settings.end_time << " s simulated each; " << n_skipped << " cells kept from an earlier run.\n"
            << "- " << mpi.size() << " MPI rank(s); " << n_done << " cells computed in " << std::fixed
            << std::setprecision(1) << work_wall << " s (" << std::setprecision(3) << n_done / work_wall
            << " cells/s); whole command " << std::setprecision(1) << wall << " s.\n"
            << std::defaultfloat
            << "- Classes by the one trace analysis (contact/trace_analysis.h) of each member; the adaptation "
               "time is when the slider comes within 0.01 L of its end position for good.\n\n"
            << "| outcome | members (this run) |\n|---|---|\n";
    for (const auto &[name, count] : class_counts)
      summary << "| " << name << " | " << count << " |\n";
    summary << "\nFiles: map.csv (one row per cell and member), timing.csv, published_cases.csv, map_*.png.\n";
    write_text_file(dir + "/summary.md", summary.str());
    if (!run_plot_script("plot_map.py", {dir, "map of " + base.name + " (" + options.model + ")"}))
      note_output_failure("map_*.png (scripts/plot_map.py)");
    console() << "map: " << n_done << " cells in " << std::fixed << std::setprecision(1) << work_wall << " s on "
              << mpi.size() << " rank(s); " << dir << "/summary.md" << std::endl;
    return 0;
  }
} // namespace beamslider
