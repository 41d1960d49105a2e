// Verification section "Cubic coefficients": analytic (seed Eq. 3) against
// STEP, condensed STEP and ICE on the FE model; the membrane over-prediction
// of plain STEP explained by a number; cost; ICE against its load level.
#include "io/csv_writer.h"
#include "numerics/stop_request.h"
#include "fem/fe_beam.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/fe_statics.h"
#include "verification/report/charts.h"
#include "verification/report/report.h"
#include "verification/studies/coefficient_methods.h"
#include "io/console.h"

#include <cmath>
#include <iomanip>
#include <iostream>

namespace beamslider
{
  namespace
  {
    std::string label(const CubicTerm &t)
    {
      return "c^(" + std::to_string(t.n + 1) + ")_" + std::to_string(t.j + 1) + std::to_string(t.k + 1) + std::to_string(t.l + 1);
    }

    // What the subsections share: the scene's FE beam, its modes, the basis
    // of N = 3 and every method's coefficients on it (analytic first, in the
    // order of coefficient_methods()).
    struct CoefficientStudy
    {
      explicit CoefficientStudy(const Scene &scene)
        : beam(scene)
        , modes(compute_bending_modes(beam, 7))
        , basis3(make_modal_basis(beam, modes, 3))
      {
        for (const auto &m : coefficient_methods())
          results.push_back(compute_coefficients(beam, modes, basis3, m, m == "ice" ? 0.03 : 1.0));
        for (const auto &t : analytic())
          largest = std::max(largest, std::abs(t.value));
      }

      const std::vector<CubicTerm> &analytic() const { return results[0].fit.cubic; }
      // A method's b_111 over the analytic one (results[i]).
      double b111_ratio(const std::size_t i) const
      {
        return results[i].fit.cubic_coefficient(0, 0, 0, 0) / analytic()[0].value;
      }

      const FEBeam beam;
      const FEModes modes;
      const ModalBasis basis3;
      std::vector<CoefficientResult> results;
      double largest = 0; // the largest analytic |c|
    };

    // 2.1: N = 3, every method against the analytic coefficients; every term
    // in coefficients_n3.csv, the terms above 1e-3 of the largest in the text.
    void add_n3_comparison(Report &report, const CoefficientStudy &study, CsvWriter &csv)
    {
      auto &md                                      = report.text;
      const std::vector<CubicTerm> &analytic        = study.analytic();
      const std::vector<CoefficientResult> &results = study.results;
      md << "### 2.1 N = 3, the terms above 1e-3 of the largest\n\n"
         << "| term | analytic | step / analytic | step-condensed / analytic | ice / analytic |\n|---|---|---|---|---|\n";
      double worst_condensed = 0, worst_ice = 0;
      for (std::size_t i = 0; i < analytic.size(); ++i)
        {
          const CubicTerm &t = analytic[i];
          std::vector<double> v;
          for (const auto &r : results)
            v.push_back(r.fit.cubic_coefficient(t.n, t.j, t.k, t.l));
          csv.row({CsvWriter::cell(t.n + 1), CsvWriter::cell(t.j + 1), CsvWriter::cell(t.k + 1), CsvWriter::cell(t.l + 1),
                   CsvWriter::cell(v[0]), CsvWriter::cell(v[1]), CsvWriter::cell(v[2]), CsvWriter::cell(v[3])});
          if (std::abs(t.value) < 1e-3 * study.largest)
            continue;
          worst_condensed = std::max(worst_condensed, std::abs(v[2] / v[0] - 1));
          worst_ice       = std::max(worst_ice, std::abs(v[3] / v[0] - 1));
          md << "| " << label(t) << " | " << sci(v[0]) << " | " << fixed(v[1] / v[0], 4) << " | " << fixed(v[2] / v[0], 6)
             << " | " << fixed(v[3] / v[0], 6) << " |\n";
        }
      md << "\nCondensed STEP agrees with the analytic coefficients to " << sci(worst_condensed, 1) << " and ICE (load level: "
         << "linear displacement 0.03 h) to " << sci(worst_ice, 1)
         << " on these terms. The quadratic coefficients, zero for a flat beam, come out at most "
         << sci(results[2].fit.max_abs_quadratic() / (study.largest * results[2].fit.amplitudes[0]), 1) << " (condensed STEP) and "
         << sci(results[3].fit.max_abs_quadratic() / (study.largest * results[3].fit.amplitudes[0]), 1)
         << " (ICE) of the largest cubic one, both taken at the amplitude a_1 (|a| a_1² against |c| a_1³).\n\n";
    }

    // 2.2: the over-prediction of plain STEP, predicted and measured.
    void add_step_overprediction(Report &report, const Scene &scene, const CoefficientStudy &study)
    {
      auto &md       = report.text;
      const double L = scene.beam.length, k_ax = study.basis3.membrane_stiffness;
      const double I2 = study.basis3.stretch(0, 0), EA_I4 = axial_weighted_slope_fourth_power(study.beam, study.modes.shapes[0]);
      const double predicted = EA_I4 / (k_ax * I2 * I2);
      const double measured  = study.b111_ratio(1);
      md << "### 2.2 Why plain STEP over-predicts\n\n"
         << "With the axial DoFs held at zero the membrane strain is ½w'² at every point and the supports do not give: "
            "b_111 becomes ½∫EA φ₁'⁴ dx instead of (k_ax/2)(∫φ₁'² dx)², with k_ax = (∫dx/EA + 1/k_t)⁻¹ (the membrane "
            "force of a beam without axial inertia is the same all along it, whatever EA(x) does). The ratio "
            "∫EAφ₁'⁴/(k_ax(∫φ₁'²)²) is predicted at "
         << fixed(predicted, 5) << " and measured at " << fixed(measured, 5) << ".";
      if (!scene.beam.from_mesh())
        md << " On a uniform beam it is the product of a shape factor L∫φ₁'⁴/(∫φ₁'²)² = "
           << fixed(L * EA_I4 / (scene.beam.axial_stiffness() * I2 * I2), 5)
           << " (the membrane cannot even out the strain along the beam) and a support factor EA/(L k_ax) = "
           << fixed(scene.beam.axial_stiffness() / (L * k_ax), 5) << " (the axial springs cannot give).";
      md << " Condensed STEP and ICE let the membrane relax and have neither error.\n\n";
    }

    // 2.2b: the coefficient the FE model implies through its own backbone.
    void add_fe_implied_coefficient(Report &report, const CoefficientStudy &study)
    {
      console() << "[verify] cubic coefficients: FE-implied b_111 ..." << std::endl;
      const FEImpliedCoefficient fe_implied = fe_implied_b111(study.beam, study.modes);
      report.text << "### 2.2b FE-implied b_111\n\n"
                  << "Harmonic balance on the full FE model (axial DoFs and their inertia kept, harmonics 0…" << fe_implied.n_harmonics
                  << ") along the mode-1 backbone at ŵ/h = 0.05…0.3 (" << fe_implied.n_points
                  << " points), fitted as (ω/ω₁)² − 1 = c a² + d a⁴, gives c = " << fixed(fe_implied.c, 5)
                  << " and, through Eq. 4, b_111 = " << sci(fe_implied.b_111, 5) << ": FE-implied / analytic = "
                  << fixed(fe_implied.b_111 / study.analytic()[0].value, 6) << ", step-condensed / analytic = "
                  << fixed(study.b111_ratio(2), 6) << ", ICE / analytic = "
                  << fixed(study.b111_ratio(3), 6) << " (" << sci(fe_implied.seconds, 2)
                  << " s). This route uses no modal fit of static solves at all, so it checks the other three independently; "
                     "what remains is the axial inertia that the modal model condenses out (of order (ω₁/ω_axial)²).\n\n";
    }

    // 2.3: every method's cost for N = 5 and 7 (rows in coefficient_cost.csv).
    void add_cost_table(Report &report, const CoefficientStudy &study, CsvWriter &cost)
    {
      auto &md = report.text;
      md << "### 2.3 Cost\n\n| method | N | modal force evaluations | FE static solves | sparse solves | wall time [s] |\n|---|---|---|---|---|---|\n";
      for (const unsigned int n : {5u, 7u})
        {
          const ModalBasis basis = make_modal_basis(study.beam, study.modes, n);
          for (const auto &m : coefficient_methods())
            {
              const CoefficientResult r = compute_coefficients(study.beam, study.modes, basis, m, m == "ice" ? 0.03 : 1.0);
              md << "| " << m << " | " << n << " | " << r.fit.n_evaluations << " | " << r.n_static_solves << " | "
                 << r.n_linear_solves << " | " << sci(r.seconds, 2) << " |\n";
              cost.row({m, CsvWriter::cell(n), CsvWriter::cell(r.fit.n_evaluations), CsvWriter::cell(r.n_static_solves),
                        CsvWriter::cell(r.n_linear_solves), CsvWriter::cell(r.seconds, 4)});
            }
        }
      md << "\nA STEP point costs one internal-force evaluation (plain) or one linear axial solve (condensed: for given w the "
            "axial equilibrium is linear in u); an ICE point is a full Newton solve with load stepping.\n\n";
    }

    // One cell of the load-level table: b_111's relative error by `method`
    // on `basis` at load level `s`, or "failed" (an interruption goes on).
    void add_load_level_cell(Report &report, const CoefficientStudy &study, CsvWriter &levels, const double s,
                             const std::string &method, const ModalBasis &basis)
    {
      auto &md = report.text;
      try
        {
          const CoefficientResult r = compute_coefficients(study.beam, study.modes, basis, method, s);
          const double err = r.fit.cubic_coefficient(0, 0, 0, 0) / study.analytic()[0].value - 1;
          md << " " << sci(err, 2) << " |";
          levels.row({CsvWriter::cell(s), method, CsvWriter::cell(basis.n_modes()), CsvWriter::cell(err, 6), "ok"});
        }
      catch (const Interrupted &)
        {
          throw;
        }
      catch (const std::exception &e)
        {
          md << " failed |";
          levels.row({CsvWriter::cell(s), method, CsvWriter::cell(basis.n_modes()), "", "failed"});
          console() << "  " << method << " at " << s << " h failed: " << e.what() << std::endl;
        }
    }

    // 2.4: b_111 against the STEP amplitude or ICE load level, for N = 1
    // and N = 3 (rows in coefficient_load_levels.csv); levels up to 5 h with --full.
    void add_load_level_study(Report &report, const Scene &scene, const CoefficientStudy &study, CsvWriter &levels,
                              const bool full)
    {
      auto &md = report.text;
      md << "### 2.4 Coefficient against the load level\n\n"
         << "Relative error of b_111 against the analytic value when the STEP amplitude or the ICE load level (given as the "
            "linear displacement it causes, in thicknesses) changes, for N = 1 and N = 3.\n\n"
         << "| level [h] | step-condensed N=1 | ice N=1 | ice N=3 |\n|---|---|---|---|\n";
      std::vector<double> scales{0.01, 0.03, 0.1, 0.3, 1.0, 2.0};
      if (full)
        scales.insert(scales.end(), {3.0, 5.0});
      const ModalBasis basis1 = make_modal_basis(study.beam, study.modes, 1);
      for (const double s : scales)
        {
          md << "| " << s << " |";
          for (const auto &[method, basis] : {std::pair<std::string, const ModalBasis *>{"step-condensed", &basis1},
                                              {"ice", &basis1}, {"ice", &study.basis3}})
            add_load_level_cell(report, study, levels, s, method, *basis);
          md << "\n";
        }
      md << "\nCondensed STEP does not depend on the amplitude: for given w the condensed FE force is a cubic polynomial. What "
            "remains of its difference is the discretisation of the axial field (the exact membrane force is uniform along the "
            "beam; the FE one, from u of degree "
         << scene.discretisation.axial_degree << " per element, is not quite). ICE's "
            "error grows with the square of the load: the static response also contains the modes outside the basis, whose "
            "effect enters the fit as quintic and higher terms aliased into the cubic ones, so the coefficient drifts with "
            "the load at which it is identified. The default ICE level (0.03 h) keeps it below 1e-3.\n\n"
         << "![Coefficient against load level](coefficient_load_levels.png)\n\n";
    }
  } // namespace

  void add_coefficient_section(Report &report, const Scene &scene, const bool full)
  {
    auto &md = report.text;
    console() << "[verify] cubic coefficients ..." << std::endl;
    md << "## 2. Cubic modal coefficients\n\n"
       << "Seed Eq. 3 with the membrane stiffness k_ax of the supports, against the three ways of extracting the cubic "
          "modal stiffness from the FE model (doc/physics.md §5). All on the scene's FE mesh and its mass-normalised modes. "
          "Coefficients c^(n)_jkl are stored once per sorted j ≤ k ≤ l (the sum over the permutations), "
          "f_n = Σ c^(n)_jkl q_j q_k q_l, in 1/(s² m² kg).\n\n";
    const CoefficientStudy study(scene);

    CsvWriter csv(report.dir + "/coefficients_n3.csv", {"n", "j", "k", "l", "analytic", "step", "step_condensed", "ice"});
    add_n3_comparison(report, study, csv);
    add_step_overprediction(report, scene, study);
    add_fe_implied_coefficient(report, study);
    CsvWriter cost(report.dir + "/coefficient_cost.csv",
                   {"method", "n_modes", "evaluations", "static_solves", "linear_solves", "seconds"});
    add_cost_table(report, study, cost);
    console() << "[verify] cubic coefficients: load-level study ..." << std::endl;
    CsvWriter levels(report.dir + "/coefficient_load_levels.csv",
                     {"level_over_h", "method", "n_modes", "b111_relative_error", "status"});
    add_load_level_study(report, scene, study, levels, full);
    // Whole files (renamed into place as they close) before the chart reads them.
    csv.close();
    cost.close();
    levels.close();
    run_plot_script("plot_coefficients.py", {report.dir});
  }
} // namespace beamslider
