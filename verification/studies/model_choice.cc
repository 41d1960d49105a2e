// The model choice of `simulate --model auto`, see model_choice.h.
#include "verification/studies/model_choice.h"

#include "io/csv_writer.h"
#include "verification/studies/console.h"
#include "verification/studies/error_ladder.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace beamslider
{
  namespace
  {
    constexpr unsigned int ladder_members = 4;
    constexpr double ladder_end_time      = 25.; // [s]: the end state of the published cases is reached by ~25 s

    const std::vector<std::string> cache_columns = {"rung",        "family",       "n_modes",    "n_elements",
                                                    "integrator",  "time_step_s",  "damped_modes", "theta", "reference",
                                                    "cost_units",  "final_x_median", "w1",         "w1_high"};

    // The cache, or an empty vector if there is none or it is not ours.
    std::vector<LadderChoiceRow> read_cache(const std::string &path)
    {
      std::vector<LadderChoiceRow> rows;
      std::ifstream in(path);
      std::string line;
      if (!in || !std::getline(in, line) || line != CsvWriter::line(cache_columns))
        return rows;
      while (std::getline(in, line))
        {
          const auto c = CsvWriter::cells(line);
          if (c.size() != cache_columns.size())
            return {};
          LadderChoiceRow r;
          r.rung                = c[0];
          r.model.family        = c[1];
          r.model.n_modes       = std::stoul(c[2]);
          r.model.n_elements    = std::stoul(c[3]);
          r.model.integrator    = c[4];
          r.model.time_step     = std::stod(c[5]);
          r.model.damped_modes  = std::stoul(c[6]);
          r.model.theta         = std::stod(c[7]);
          r.reference           = c[8] == "1";
          r.cost_units          = std::stod(c[9]);
          r.final_x_median      = std::stod(c[10]);
          r.w1                  = std::stod(c[11]);
          r.w1_high             = std::stod(c[12]);
          rows.push_back(r);
        }
      return rows;
    }

    // 17 significant digits: a double read back from the cache is the one written.
    std::string number(const double x) { return CsvWriter::cell(x, 17); }
  } // namespace

  std::string scene_content_key(const Scene &s)
  {
    // Every field the ladder's outcome depends on, in full precision.
    std::ostringstream c;
    c << std::setprecision(17) << s.beam.length << ' ' << s.beam.width << ' ' << s.beam.thickness << ' '
      << s.beam.youngs_modulus << ' ' << s.beam.density << ' ' << s.supports.type() << ' '
      << s.supports.rotational_stiffness << ' ' << s.supports.axial_stiffness << ' ' << s.slider.mass << ' '
      << s.slider.inertia << ' ' << s.slider.window_width << ' ' << s.slider.window_height_ratio << ' '
      << s.slider.com_offset << ' ' << s.slider.mass_factor << ' ' << s.contact.friction_coefficient << ' '
      << s.contact.restitution << ' ' << s.contact.gravity << ' ' << s.contact.solver << ' ' << s.damping_ratio << ' '
      << s.excitation.frequency_hz << ' ' << s.excitation.acceleration_amplitude << ' '
      << s.initial.slider_position_over_L << ' ' << s.discretisation.n_elements << ' ' << s.discretisation.axial_degree
      << ' ' << s.discretisation.n_modes << ' ' << s.discretisation.geometric_nonlinearity << ' '
      << s.time_stepping.time_step << ' ' << s.solvers.contact_tolerance << ' ' << s.solvers.contact_sweeps << ' '
      << s.solvers.newton_relative_tolerance << ' ' << s.solvers.newton_absolute_tolerance << ' '
      << s.solvers.newton_iterations << ' ' << ladder_members << ' ' << ladder_end_time
      << ' ' << s.time_stepping.fe_time_step << ' ' << s.time_stepping.fe_theta
      << " ladder-4"; // the ladder's rungs: version 4's reference is the FE step its convergence check accepted
    // A mesh beam by its elements and sections (not its file name alone:
    // the file may change), and the point bodies.
    for (const BeamMeshCell &cell : s.beam.mesh_cells)
      c << ' ' << cell.x_begin << ' ' << cell.x_end << ' ' << cell.tag;
    for (const auto &[tag, section] : s.beam.sections)
      c << ' ' << tag << ' ' << section.width << ' ' << section.thickness << ' ' << section.youngs_modulus << ' '
        << section.density;
    for (const PointMass &body : s.beam.point_masses)
      c << ' ' << body.position << ' ' << body.mass << ' ' << body.rotary_inertia;
    std::uint64_t hash = 14695981039346656037ull; // FNV-1a, 64 bit
    for (const unsigned char byte : c.str())
      {
        hash ^= byte;
        hash *= 1099511628211ull;
      }
    std::ostringstream key;
    key << std::hex << std::setw(16) << std::setfill('0') << hash;
    return key.str();
  }

  const LadderChoiceRow &cheapest_within(const std::vector<LadderChoiceRow> &rows, const double tolerance)
  {
    const LadderChoiceRow *best = nullptr;
    for (const auto &r : rows)
      {
        const bool within = r.reference || (std::isfinite(r.w1_high) && r.w1_high <= tolerance);
        if (within && (!best || r.cost_units < best->cost_units || (r.cost_units == best->cost_units && r.reference)))
          best = &r;
      }
    if (!best)
      throw std::logic_error("cheapest_within: the ladder has no reference rung");
    return *best;
  }

  ModelSetting choose_model(const Scene &scene, const double tolerance, const std::string &cache_dir, std::string &why)
  {
    const std::string path = cache_dir + "/ladder-" + scene_content_key(scene) + ".csv";
    std::vector<LadderChoiceRow> rows = read_cache(path);
    std::ostringstream log;
    if (!rows.empty())
      log << "model choice from the cached error ladder " << path << ":\n";
    else
      {
        std::size_t reference = 0;
        const auto rungs      = default_ladder(scene, LadderScope::quick, reference);
        console() << "simulate --model auto: no cached error ladder for this scene; running it (" << rungs.size()
                  << " models × " << ladder_members << " members over " << ladder_end_time
                  << " s, a few minutes, the FE most of it) ..." << std::endl;
        const LadderStudy study = run_ladder(scene, rungs, reference, ladder_end_time, ladder_members,
                                             [](const LadderRung &rung, std::size_t) {
                                               console() << "  " << rung.name << " (" << rung.model.label() << ")"
                                                         << std::endl;
                                             });
        for (std::size_t i = 0; i < study.rungs.size(); ++i)
          {
            const LadderRungResult &r = study.rungs[i];
            LadderChoiceRow row;
            row.rung            = r.rung.name;
            row.model           = r.rung.model;
            row.reference       = i == reference;
            row.cost_units      = r.cost_units;
            row.final_x_median  = r.final_position.median;
            row.w1              = row.reference ? 0. : r.position_to_reference.wasserstein;
            row.w1_high         = row.reference ? 0. : r.position_to_reference.interval_high;
            rows.push_back(row);
          }
        std::filesystem::create_directories(cache_dir);
        CsvWriter cache(path, cache_columns);
        for (const auto &r : rows)
          cache.row({r.rung, r.model.family, CsvWriter::cell(r.model.n_modes), CsvWriter::cell(r.model.n_elements),
                     r.model.integrator, number(r.model.time_step), CsvWriter::cell(r.model.damped_modes),
                     number(r.model.theta), r.reference ? "1" : "0", number(r.cost_units), number(r.final_x_median), number(r.w1),
                     number(r.w1_high)});
        cache.close();
        log << "model choice from the error ladder just computed (cached in " << path << "):\n";
        for (const ConvergenceCheck &c : study.checks)
          log << "  " << c.verdict() << "\n";
      }

    const LadderChoiceRow &chosen = cheapest_within(rows, tolerance);
    log << "  tolerance " << tolerance << " on the end position: the upper end of the 90 % interval of W₁ (final x_C/L, "
        << ladder_members << " members over " << ladder_end_time
        << " s) to the FE reference; cost by a stated model (units: steps of the published ROM), not by wall time\n";
    for (const auto &r : rows)
      log << "  " << r.rung << " (" << r.model.label() << "): final x_C/L median " << r.final_x_median
          << (r.reference ? ", the reference" : ", W₁ " + number(r.w1) + " ≤ " + number(r.w1_high)) << ", cost "
          << r.cost_units << (&r == &chosen ? "  <- picked" : "") << "\n";
    log << "picked " << chosen.rung << ": "
        << (chosen.reference ? "no cheaper model met the tolerance, so the FE reference"
                             : "the cheapest model within the tolerance")
        << "\n";
    why = log.str();
    ModelSetting setting = chosen.model;
    if (setting.family == "fe" && setting.n_elements == 0)
      setting.n_elements = scene.discretisation.n_elements;
    return setting;
  }
} // namespace beamslider
