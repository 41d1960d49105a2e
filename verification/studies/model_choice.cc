// The model choice of `simulate --model auto`, see model_choice.h.
#include "verification/studies/model_choice.h"


#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>

namespace beamslider
{
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
      << ' ' << s.discretisation.n_modes << ' ' << s.discretisation.n_static_corrections << ' ' << s.discretisation.ritz_blocks << ' '
      << s.discretisation.geometric_nonlinearity << ' '
      << s.time_stepping.time_step << ' ' << s.solvers.contact_tolerance << ' ' << s.solvers.contact_sweeps << ' '
      << s.solvers.newton_relative_tolerance << ' ' << s.solvers.newton_absolute_tolerance << ' '
      << s.solvers.newton_iterations << ' ' << choice_ladder_members << ' ' << choice_ladder_end_time
      << ' ' << s.time_stepping.fe_time_step << ' ' << s.time_stepping.fe_theta
      << " ladder-6"; // the ladder's rungs: version 6 has the front's N = 15 and 6+4sc, each rung its Δt check
    // The compliant normal law, written only where it is used so that the
    // keys of rigid-corner scenes stay what they were.
    if (s.contact.normal_stiffness > 0.)
      c << " k_N " << s.contact.normal_stiffness;
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

  std::vector<LadderChoiceRow> choice_rows(const LadderStudy &study)
  {
    std::vector<LadderChoiceRow> rows;
    for (std::size_t i = 0; i < study.rungs.size(); ++i)
      {
        const LadderRungResult &r     = study.rungs[i];
        const ConvergenceCheck *check = study.refinement_check(i);
        LadderChoiceRow row;
        row.rung           = r.rung.name;
        row.model          = r.rung.model;
        row.reference      = i == study.reference;
        row.cost_units     = r.cost_units;
        row.final_x_median = r.final_position.median;
        row.refined_alike  = !check || check->converged;
        const SampleComparison &to = !row.reference ? r.position_to_reference
                                     : check           ? check->reference().position_to_next
                                                       : SampleComparison();
        row.w1      = to.n_a > 0 ? to.wasserstein : 0.;
        row.w1_high = to.n_a > 0 ? to.interval_high : 0.;
        if (!row.reference && to.n_a == 0)
          row.w1 = row.w1_high = NAN; // no member ended: never within a tolerance
        rows.push_back(row);
      }
    return rows;
  }

  double default_choice_tolerance(const std::vector<LadderChoiceRow> &rows)
  {
    double tolerance = choice_tolerance_floor;
    for (const auto &r : rows)
      if (r.reference && std::isfinite(r.w1_high))
        tolerance = std::max(tolerance, r.w1_high);
    return tolerance;
  }

  bool lands_within(const LadderChoiceRow &row, const double tolerance)
  {
    return row.refined_alike && std::isfinite(row.w1_high) && row.w1_high <= tolerance;
  }

  const LadderChoiceRow &cheapest_within(const std::vector<LadderChoiceRow> &rows, const double tolerance)
  {
    const LadderChoiceRow *best = nullptr;
    for (const auto &r : rows)
      {
        const bool within = r.reference || lands_within(r, tolerance);
        if (within && (!best || r.cost_units < best->cost_units || (r.cost_units == best->cost_units && r.reference)))
          best = &r;
      }
    if (!best)
      throw std::logic_error("cheapest_within: the ladder has no reference rung");
    return *best;
  }

  ChoiceLadder run_choice_ladder(const Scene &scene, const std::vector<LadderRung> &rungs, const std::size_t reference,
                                 const std::function<void(const LadderRung &, std::size_t)> &before_rung)
  {
    const LadderStudy study =
      run_ladder(scene, rungs, reference, choice_ladder_end_time, choice_ladder_members, before_rung);
    ChoiceLadder ladder;
    ladder.rows = choice_rows(study);
    for (const ConvergenceCheck &c : study.checks)
      ladder.check_verdicts.push_back(c.verdict());
    return ladder;
  }

  ModelChoice choose_from_ladder(const Scene &scene, const std::vector<LadderChoiceRow> &rows, const double tolerance)
  {
    // W₁ in full precision, as the cache holds it.
    const auto exact = [](const double x) {
      std::ostringstream text;
      text << std::setprecision(17) << x;
      return text.str();
    };
    const LadderChoiceRow &chosen = cheapest_within(rows, tolerance);
    std::ostringstream log;
    log << "  tolerance " << tolerance << " on the end position: the upper end of the 90 % interval of W₁ (final x_C/L, "
        << choice_ladder_members << " members over " << choice_ladder_end_time
        << " s) to the FE reference, for a model that ends alike at half its step; cost by a stated model (units: "
           "steps of the published ROM), not by wall time\n";
    for (const auto &r : rows)
      log << "  " << r.rung << " (" << r.model.label() << "): final x_C/L median " << r.final_x_median
          << (r.reference ? ", the reference (W₁ to its refinement ≤ " + exact(r.w1_high) + ")"
                          : ", W₁ " + exact(r.w1) + " ≤ " + exact(r.w1_high))
          << (r.refined_alike ? "" : ", moves when refined") << ", cost " << r.cost_units
          << (&r == &chosen ? "  <- picked" : "") << "\n";
    log << "picked " << chosen.rung << ": "
        << (chosen.reference ? "no cheaper model met the tolerance, so the FE reference"
                             : "the cheapest model within the tolerance that ends alike refined")
        << "\n";
    ModelChoice choice{chosen.model, log.str()};
    if (choice.model.family == "fe" && choice.model.n_elements == 0)
      choice.model.n_elements = scene.discretisation.n_elements;
    return choice;
  }

  ModelChoice choose_from_ladder(const Scene &scene, const std::vector<LadderChoiceRow> &rows)
  {
    return choose_from_ladder(scene, rows, default_choice_tolerance(rows));
  }
} // namespace beamslider
