// Operating-range maps, see operating_map.h.
#include "verification/studies/operating_map.h"

#include "runs/adaptation_run.h"
#include "contact/beam_system.h"
#include "numerics/stop_request.h"
#include "runtime/parallel_for.h"
#include "verification/studies/simulation_cases.h"

#include <cctype>
#include <cmath>
#include <iomanip>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    double parse_number(const std::string &text, const std::string &option)
    {
      std::size_t used = 0;
      double x         = 0;
      try
        {
          x = std::stod(text, &used);
        }
      catch (const std::exception &)
        {
          used = 0;
        }
      if (used == 0 || used != text.size() || !std::isfinite(x))
        throw InputError(option + " '" + text + "': not a finite number");
      return x;
    }

    // Grid values are written with 12 significant digits, so that A + i·STEP
    // gives the same text (and the same scene) on every rank and every run.
    double rounded(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(12) << x;
      return std::stod(s.str());
    }

    std::vector<std::string> split(const std::string &line, const char separator)
    {
      std::vector<std::string> fields;
      std::stringstream in(line);
      std::string field;
      while (std::getline(in, field, separator))
        fields.push_back(field);
      if (!line.empty() && line.back() == separator)
        fields.emplace_back();
      return fields;
    }
  } // namespace

  std::string grid_value_text(const double x)
  {
    std::ostringstream s;
    s << std::setprecision(12) << x;
    return s.str();
  }

  std::vector<double> parse_grid_range(const std::string &text, const std::string &option)
  {
    const std::vector<std::string> parts = split(text, ':');
    if (parts.size() == 1)
      return {rounded(parse_number(parts[0], option))};
    if (parts.size() != 3)
      throw InputError(option + " '" + text + "': expected A:B:STEP (from A to B in steps of STEP) or one value");
    const double a = parse_number(parts[0], option), b = parse_number(parts[1], option),
                 step = parse_number(parts[2], option);
    if (!(step > 0.))
      throw InputError(option + " '" + text + "': STEP = " + parts[2] + " must be > 0");
    if (b < a)
      throw InputError(option + " '" + text + "': the end B = " + parts[1] + " lies below the start A = " + parts[0]);
    const double count = std::floor((b - a) / step + 1e-9) + 1;
    if (count > 10000)
      throw InputError(option + " '" + text + "': " + std::to_string(static_cast<long long>(count)) +
                       " values, more than the 10000 allowed per axis");
    std::vector<double> values;
    for (long long i = 0; i < static_cast<long long>(count); ++i)
      values.push_back(rounded(a + i * step));
    return values;
  }

  MapAxis parse_parameter_axis(const std::string &text)
  {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0 || text.find('/') > eq)
      throw InputError("--axis '" + text + "': expected \"Section/Name=A:B:STEP\"");
    MapAxis axis;
    axis.parameter = text.substr(0, eq);
    axis.values    = parse_grid_range(text.substr(eq + 1), "--axis " + axis.parameter);
    for (const char c : axis.parameter)
      axis.column += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
    return axis;
  }

  std::size_t MapGrid::n_cells() const
  {
    std::size_t n = axes.empty() ? 0 : 1;
    for (const MapAxis &a : axes)
      n *= a.values.size();
    return n;
  }

  void MapGrid::check_distinct_parameters(const std::string &command) const
  {
    for (std::size_t i = 0; i < axes.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (axes[i].parameter == axes[j].parameter)
          throw InputError(command + ": the parameter '" + axes[i].parameter + "' is given as two axes");
  }

  std::vector<double> MapGrid::cell_values(std::size_t c) const
  {
    std::vector<double> v(axes.size());
    for (std::size_t k = axes.size(); k-- > 0;)
      {
        v[k] = axes[k].values[c % axes[k].values.size()];
        c /= axes[k].values.size();
      }
    return v;
  }

  Scene map_cell_scene(const std::string &scene_file, const std::vector<std::string> &overrides,
                       const MapGrid &grid, const std::size_t cell, const double end_time)
  {
    // The axes and the map's end time replace a user's --set of the same
    // parameter (read_scene refuses a parameter set twice; a --set of the
    // end time has reached `end_time` already, unless --end-time overrode it).
    const std::string end_time_key = "Time stepping/End time";
    std::vector<std::string> all;
    for (const std::string &o : overrides)
      {
        bool replaced = o.rfind(end_time_key + "=", 0) == 0;
        for (const MapAxis &a : grid.axes)
          replaced = replaced || o.rfind(a.parameter + "=", 0) == 0;
        if (!replaced)
          all.push_back(o);
      }
    const std::vector<double> values = grid.cell_values(cell);
    for (std::size_t k = 0; k < grid.axes.size(); ++k)
      all.push_back(grid.axes[k].parameter + "=" + grid_value_text(values[k]));
    all.push_back(end_time_key + "=" + grid_value_text(end_time));
    return read_scene(scene_file, all);
  }

  std::vector<MapMember> run_map_cell_members(const std::string &scene_file, const std::vector<std::string> &overrides,
                                              const MapGrid &grid, const std::size_t cell, const MapSettings &settings)
  {
    const Scene scene = map_cell_scene(scene_file, overrides, grid, cell, settings.end_time);
    std::vector<MapMember> members;
    for (unsigned int m = 0; m < settings.n_members; ++m)
      {
        Scene member_scene = scene;
        member_scene.initial.slider_position_over_L += m * settings.perturbation;
        validate_scene(member_scene);
        std::vector<PeriodRecord> periods;
        RunResult result;
        try
          {
            ModelSetting model = settings.chosen ? settings.model : scene_model(member_scene, settings.model.family);
            if (!settings.chosen)
              model.integrator = settings.model.integrator;
            const std::unique_ptr<BeamSystem> beam = make_beam_model(member_scene, model);
            RunOptions options        = RunOptions::from_scene(member_scene, model.time_step); // the FE at its FE time step
            options.progress_interval = 1e300;
            AdaptationRun run(member_scene, *beam, options);
            run.on_period = [&periods](const PeriodRecord &p) { periods.push_back(p); };
            result        = run.run();
          }
        catch (const InputError &)
          {
            throw;
          }
        catch (const std::invalid_argument &)
          {
            throw;
          }
        catch (const Interrupted &)
          {
            result.status = RunStatus::interrupted;
          }
        catch (const std::exception &e)
          {
            result.status  = RunStatus::beam_solver_failure;
            result.message = e.what();
          }
        if (result.status == RunStatus::interrupted)
          return {};
        MapMember member;
        member.index        = m;
        member.perturbation = m * settings.perturbation;
        member.status       = result.status;
        member.analysis     = analyse_trace(periods, result.status, trace_thresholds(member_scene));
        members.push_back(std::move(member));
      }
    return members;
  }

  std::vector<std::vector<MapMember>> run_map_cells(const std::string &scene_file,
                                                    const std::vector<std::string> &overrides, const MapGrid &grid,
                                                    const MapSettings &settings,
                                                    const std::function<void(std::size_t, std::size_t)> &on_cell)
  {
    const std::size_t n = grid.n_cells();
    std::vector<std::vector<MapMember>> results(n);
    std::mutex report;
    std::size_t done = 0;
    parallel_for(n, 0, [&](const std::size_t c) {
      if (interruption_requested())
        return;
      results[c] = run_map_cell_members(scene_file, overrides, grid, c, settings);
      const std::lock_guard<std::mutex> lock(report);
      ++done;
      if (on_cell)
        on_cell(done, n);
    });
    return results;
  }

  std::vector<PublishedMapCase> published_map_cases()
  {
    std::vector<PublishedMapCase> cases;
    for (const SimulationCase &c : simulation_cases())
      {
        PublishedMapCase p;
        p.name     = c.name;
        p.end_time = c.end_time;
        bool plain = true;
        for (const std::string &o : c.overrides)
          {
            const std::size_t eq  = o.find('=');
            const std::string key = o.substr(0, eq);
            if (key == "Excitation/Frequency")
              p.frequency_hz = std::stod(o.substr(eq + 1));
            else if (key == "Excitation/Acceleration amplitude")
              p.acceleration = std::stod(o.substr(eq + 1));
            else if (key == "Initial state/Slider position")
              p.start_over_L = std::stod(o.substr(eq + 1));
            else
              plain = false;
          }
        const std::pair<const char *, AdaptationClass> names[] = {
          {"signature-move", AdaptationClass::signature_move},
          {"trivial-adaption", AdaptationClass::trivial_adaption},
          {"relaxation-oscillation", AdaptationClass::relaxation_oscillation},
          {"self-damping", AdaptationClass::self_damping}};
        for (const auto &[prefix, outcome] : names)
          if (c.name.rfind(prefix, 0) == 0)
            p.expected_outcome = to_string(outcome);
        if (plain && !p.expected_outcome.empty())
          cases.push_back(p);
      }
    return cases;
  }

} // namespace beamslider
