// `[mpirun -np P] beamslider map [SCENE] --frequency A:B:STEP --acceleration
// A:B:STEP [--start A:B:STEP] [--axis "Section/Name=A:B:STEP"]... [--members K]
// [--model rom|fe] [--end-time S]`: the adaptation on every cell of a grid
// (verification/studies/operating_map.h), spread over MPI ranks
// (runtime/mpi_cells.h); map.csv is written and read back by
// verification/report/map_files.h.
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
#include "io/csv_writer.h"
#include "io/interruption.h"
#include "io/input_file.h"
#include "io/output_file.h"
#include "scene/scene.h"
#include "verification/cli/commands.h"
#include "verification/cli/ladder_cache.h"
#include "verification/cli/study_results.h"
#include "verification/report/map_files.h"
#include "numerics/elapsed.h"
#include "runtime/mpi_cells.h"
#include "io/console.h"
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

    using clock = std::chrono::steady_clock;

    // The state of one map, shared by its stages: the grid and settings (on
    // every rank), and on rank 0 the folder, its open files, the cells to
    // compute and the tally of those computed.
    struct MapRun
    {
      MapRun(const CommonOptions &common, const MapOptions &options, const MpiSession &mpi)
        : common(common)
        , options(options)
        , mpi(mpi)
      {}
      const CommonOptions &common;
      const MapOptions &options;
      const MpiSession &mpi;
      std::string scene_file;
      Scene base;
      MapGrid grid;
      MapSettings settings;
      std::vector<std::string> columns; // of map.csv
      std::string dir;
      std::optional<CsvWriter> map_rows, timing; // rank 0's map.csv and timing.csv
      std::vector<std::size_t> todo;
      std::size_t n_skipped = 0, n_done = 0;
      std::map<std::string, unsigned int> class_counts;
      clock::time_point work_start;
      std::string model_choice; // --model auto: the numbers the model was picked on
      MapCells *kept = nullptr; // computing for a handover: the cells' rows go here, not to files
      bool replaying = false;   // writing a kept map: no progress per cell
    };

    MapGrid map_grid(const MapOptions &options)
    {
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
      return grid;
    }

    // --model auto: the model picked on the scene without the axes (its
    // error ladder, cached), the same in every cell. An axis over the
    // discretisation would change the model it picked, so it is refused.
    void choose_map_model(MapRun &m)
    {
      for (const MapAxis &a : m.grid.axes)
        if (a.parameter.rfind("Discretisation/", 0) == 0 || a.parameter.rfind("Time stepping/", 0) == 0)
          throw InputError("--model auto picks one model for every cell; the axis over '" + a.parameter +
                           "' would change it: use --model rom or fe");
      m.settings.model  = choose_model(m.base, m.options.tolerance, choice_cache_dir(m.base), m.model_choice, m.mpi.size());
      m.settings.chosen = true;
      if (m.mpi.rank() == 0)
        console() << m.model_choice << std::endl;
    }

    // The scene, grid and settings of the map. Every cell's scene is checked
    // before any work: a cell outside the allowed ranges is an input error
    // on every rank alike, not a dead worker.
    void read_map_setup(MapRun &m)
    {
      m.scene_file = resolve_scene_path(m.common.scene_file);
      check_overrides_unique(m.common.overrides);
      m.base = read_scene(m.scene_file, m.common.overrides);
      m.grid = map_grid(m.options);

      MapSettings &settings = m.settings;
      settings.model.family = m.options.model;
      if (m.options.model == "auto")
        choose_map_model(m);
      else if (m.options.tolerance)
        throw InputError("--tolerance applies to --model auto only");
      settings.n_members    = m.options.members;
      settings.perturbation = m.options.perturbation;
      settings.end_time     = m.options.end_time ? *m.options.end_time : m.base.time_stepping.end_time;

      for (std::size_t c = 0; c < m.grid.n_cells(); ++c)
        {
          const Scene s = map_cell_scene(m.scene_file, m.common.overrides, m.grid, c, settings.end_time);
          const double x_last = s.initial.slider_position_over_L + (settings.n_members - 1) * settings.perturbation;
          if (!(x_last < 1.))
            throw InputError("--perturbation " + std::to_string(settings.perturbation) +
                             " moves the last member's start beyond the beam in cell " + map_cell_key(m.grid, c));
        }
      m.columns = map_csv_columns(m.grid);
    }

    // What this map is (map_settings.txt); a restart into the same folder
    // must be the same map.
    std::string map_identity(const MapRun &m)
    {
      std::ostringstream what;
      what << "scene " << m.base.name << " content " << scene_content_key(m.base) << "\nmodel " << m.options.model
           << (m.settings.chosen ? " " + m.settings.model.label() : std::string())
           << "\nmembers " << m.settings.n_members << "\nperturbation " << m.settings.perturbation << "\nend time "
           << m.settings.end_time << " s\n";
      for (const std::string &o : m.common.overrides)
        what << "set " << o << "\n";
      for (const MapAxis &a : m.grid.axes)
        {
          what << "axis " << a.parameter << " =";
          for (const double v : a.values)
            what << ' ' << v;
          what << "\n";
        }
      return what.str();
    }

    // Takes the map's folder and returns the complete cells (by key) an
    // earlier run of this map left in its map.csv. Checked before anything
    // in the folder is written: a folder of another map is refused as it is
    // (its parameters.prm and command.prm still describe that map).
    std::map<std::string, std::string> take_map_folder(MapRun &m)
    {
      const std::string what    = map_identity(m);
      const std::string planned = output_dir_path(m.common, m.base, "map");
      if (std::filesystem::is_directory(planned))
        lock_output_folder(planned);
      const std::string previous = read_text_file_if_present(planned + "/map_settings.txt", InputLimits::text);
      if (!previous.empty() && previous != what)
        throw InputError("the output folder '" + planned + "' holds a map with other settings (" + planned +
                         "/map_settings.txt); use another --output or remove that folder");
      m.dir = prepare_output_dir(m.common, m.base, "map");
      std::map<std::string, std::string> finished;
      if (!previous.empty())
        finished = read_finished_cells(m.dir + "/map.csv", m.columns, m.settings.n_members);
      write_text_file(m.dir + "/map_settings.txt", what);
      return finished;
    }

    // map.csv anew with the `finished` cells, which are not computed again,
    // open for the others; timing.csv; the published cases.
    void open_map_files(MapRun &m, const std::map<std::string, std::string> &finished)
    {
      const std::string map_csv = m.dir + "/map.csv";
      // Atomically: a kill now leaves the old file or the new one.
      std::string kept = CsvWriter::line(m.columns) + "\n";
      for (const auto &[key, rows] : finished)
        kept += rows;
      write_file_atomically(map_csv, kept);
      // The cells computed now are appended, each row flushed as written.
      CsvOptions continued;
      continued.append = true;
      m.map_rows.emplace(map_csv, m.columns, continued);
      CsvOptions timing_options;
      timing_options.in_place = true; // rows as cells finish
      // A resumed map appends to the timing rows it has (its header is there).
      std::error_code no_file;
      timing_options.append = std::filesystem::file_size(m.dir + "/timing.csv", no_file) > 0 && !no_file;
      m.timing.emplace(m.dir + "/timing.csv", std::vector<std::string>{"cell", "rank", "wall_s"}, timing_options);
      for (std::size_t c = 0; c < m.grid.n_cells(); ++c)
        if (finished.count(map_cell_key(m.grid, c)))
          ++m.n_skipped;
        else
          m.todo.push_back(c);
      write_published_cases(m.dir + "/published_cases.csv");
    }

    void announce_map(const MapRun &m)
    {
      console() << "map " << m.base.name << ": " << m.grid.n_cells() << " cells";
      for (const MapAxis &a : m.grid.axes)
        console() << (&a == &m.grid.axes.front() ? " (" : " x ") << a.values.size() << " " << a.column;
      console() << ") x " << m.settings.n_members << " member(s) of " << m.options.model << ", " << m.settings.end_time
                << " s each, on " << m.mpi.size() << " rank(s)";
      if (m.n_skipped)
        console() << "; " << m.n_skipped << " cells already in map.csv are kept";
      console() << (m.dir.empty() ? std::string("; in memory") : "; into " + m.dir) << std::endl;
    }

    // A cell's rows of map.csv ("" when interrupted), and its wall time on a
    // last line for rank 0's timing.csv.
    std::string compute_map_cell(const MapRun &m, const std::size_t cell)
    {
      const auto t0 = clock::now();
      const std::vector<MapMember> members =
        run_map_cell_members(m.scene_file, m.common.overrides, m.grid, cell, m.settings);
      const double seconds = elapsed_seconds(t0);
      std::string rows     = members.empty() ? std::string() : format_map_rows(m.grid, cell, members);
      if (!rows.empty())
        rows += "#wall " + std::to_string(seconds) + "\n"; // carried to rank 0 for timing.csv, not written to map.csv
      return rows;
    }

    // Rank 0: a computed cell into map.csv, timing.csv and the tally, and
    // the progress on the console.
    void record_map_cell(MapRun &m, const std::size_t cell, const std::string &result, const unsigned int rank)
    {
      const std::size_t cut  = result.rfind("#wall ");
      const std::string rows = result.substr(0, cut);
      const double wall      = cut == std::string::npos ? 0. : std::stod(result.substr(cut + 6));
      std::istringstream lines(rows);
      std::string line;
      while (std::getline(lines, line))
        {
          const std::vector<std::string> cells = CsvWriter::cells(line);
          if (m.map_rows)
            m.map_rows->row(cells);
          ++m.class_counts[cells[m.grid.axes.size() + 3]]; // the outcome column
        }
      if (m.timing)
        m.timing->row({"\"" + map_cell_key(m.grid, cell) + "\"", std::to_string(rank), std::to_string(wall)});
      if (m.kept)
        {
          m.kept->rows[cell]         = rows;
          m.kept->wall_seconds[cell] = wall;
        }
      ++m.n_done;
      if (m.replaying)
        return;
      const double elapsed = elapsed_seconds(m.work_start);
      const double rate    = m.n_done / elapsed;
      console() << "  cells " << m.n_done + m.n_skipped << "/" << m.grid.n_cells() << " (" << map_cell_key(m.grid, cell)
                << " on rank " << rank << ", " << std::fixed << std::setprecision(1) << wall << " s), "
                << std::setprecision(3) << rate * 60 << " cells/min, about "
                << duration_text((m.todo.size() - m.n_done) / rate) << " left" << std::defaultfloat << std::endl;
    }

    // summary.md: the grid, the cost and the outcome classes of this run's members.
    std::string map_summary(const MapRun &m, const double wall, const double work_wall)
    {
      std::ostringstream summary;
      summary << "# Map: scene `" << m.base.name << "`\n\n- Axes:";
      for (const MapAxis &a : m.grid.axes)
        summary << " " << a.parameter << " (" << a.values.size() << " values, " << a.values.front() << " … "
                << a.values.back() << ");";
      summary << "\n- " << m.grid.n_cells() << " cells × " << m.settings.n_members << " member(s), " << m.options.model
              << ", " << m.settings.end_time << " s simulated each; " << m.n_skipped
              << " cells kept from an earlier run.\n"
              << "- " << m.mpi.size() << " MPI rank(s); " << m.n_done << " cells computed in " << std::fixed
              << std::setprecision(1) << work_wall << " s (" << std::setprecision(3) << m.n_done / work_wall
              << " cells/s); whole command " << std::setprecision(1) << wall << " s.\n"
              << std::defaultfloat
              << "- Classes by the one trace analysis (runs/trace_analysis.h) of each member; the adaptation "
                 "time is when the slider comes within 0.01 L of its end position for good.\n\n"
              << "| outcome | members (this run) |\n|---|---|\n";
      for (const auto &[name, count] : m.class_counts)
        summary << "| " << name << " | " << count << " |\n";
      if (m.settings.chosen)
        summary << "\nThe model in every cell, by `--model auto` on the scene without the axes: "
                << m.settings.model.label() << ".\n\n```\n" << m.model_choice << "```\n";
      summary << "\nFiles: map.csv (one row per cell and member), timing.csv, published_cases.csv, map_*.png.\n";
      return summary.str();
    }
  } // namespace

  int run_map(const CommonOptions &common, const MapOptions &options, StudyHandover *handover)
  {
    const auto start_time = clock::now();
    // Under mpirun every rank runs this; only rank 0 reads back, writes and prints.
    MpiSession mpi(launched_by_mpi_launcher());
    const bool root = mpi.rank() == 0;
    MapRun m(common, options, mpi);
    read_map_setup(m);
    // A map computed before from the same options (python/study_bindings.cc)
    // is written as its cells come, replayed instead of computed.
    const MapCells *replay = nullptr;
    MapCells computed;
    if (handover && handover->mode == StudyHandover::Mode::write)
      {
        replay = &std::any_cast<const MapCells &>(handover->result);
        require_same_scene(replay->base, m.base, "map");
      }
    else if (handover)
      {
        computed.base = m.base;
        computed.grid = m.grid;
        computed.rows.resize(m.grid.n_cells());
        computed.wall_seconds.resize(m.grid.n_cells());
        m.kept = &computed;
        for (std::size_t c = 0; c < m.grid.n_cells(); ++c)
          m.todo.push_back(c);
        announce_map(m);
      }
    if (root && !m.kept)
      {
        std::map<std::string, std::string> finished = take_map_folder(m);
        if (replay)
          finished.clear(); // every cell anew, from the kept map
        open_map_files(m, finished);
        if (!replay)
          announce_map(m);
      }

    m.work_start = clock::now();
    m.replaying = replay != nullptr;
    if (replay)
      {
        for (const std::size_t cell : m.todo)
          if (!replay->rows[cell].empty()) // a cell an interruption left out stays out: the map says it is partial
            record_map_cell(m, cell,
                            replay->rows[cell] + "#wall " + std::to_string(replay->wall_seconds[cell]) + "\n", 0);
      }
    else
      distribute_cells(
        mpi, m.todo, [&m](const std::size_t cell) { return compute_map_cell(m, cell); },
        [&m](const std::size_t cell, const std::string &result, const unsigned int rank) {
          record_map_cell(m, cell, result, rank);
        },
        [] { return interruption_requested(); });
    if (m.kept)
      {
        computed.work_seconds = elapsed_seconds(m.work_start);
        handover->result      = std::move(computed);
        return 0;
      }

    if (!root)
      return 0;
    const double wall      = elapsed_seconds(start_time);
    const double work_wall = replay ? replay->work_seconds : elapsed_seconds(m.work_start);
    if (replay && m.n_done < m.todo.size())
      {
        std::cerr << "map: the kept map holds " << m.n_done << " of " << m.todo.size()
                  << " cells (it was stopped): map.csv holds those, and run.txt says the folder is partial" << std::endl;
        return 1;
      }
    if (interruption_requested() || m.n_done < m.todo.size())
      {
        std::cerr << "map: stopped after " << m.n_done << " of " << m.todo.size()
                  << " cells; map.csv holds every finished cell: run the same command again to continue" << std::endl;
        return interruption_requested() ? 0 : 1; // main() turns an interruption into 130/143
      }
    write_text_file(m.dir + "/summary.md", map_summary(m, wall, work_wall));
    if (!run_plot_script("plot_map.py", {m.dir, "map of " + m.base.name + " (" + options.model + ")"}))
      note_output_failure("map_*.png (scripts/plot_map.py)");
    console() << "map: " << m.n_done << " cells in " << std::fixed << std::setprecision(1) << work_wall << " s on "
              << mpi.size() << " rank(s); " << m.dir << "/summary.md" << std::endl;
    return 0;
  }
} // namespace beamslider
