// Verification section "Linear frequencies": see report.h.
#include "numerics/elapsed.h"
#include "io/csv_writer.h"
#include "fem/fe_beam.h"
#include "fem/fe_modes.h"
#include "reduced/beam_backbone.h"
#include "verification/report/charts.h"
#include "verification/report/report.h"
#include "verification/studies/analytic_beam.h"
#include "io/console.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>

namespace beamslider
{
  namespace
  {
    constexpr unsigned int n_modes = 7;

    // A mesh study's frequencies, their errors and observed orders. Not
    // deal.II's ConvergenceTable: that class gives no read access to its
    // values or rates (only text and TeX output), while the mesh choice
    // (1.3) and the CSV need the numbers, and the Markdown puts modes in
    // rows and meshes in columns, the transpose of its layout.
    struct FrequencyConvergence
    {
      std::vector<unsigned int> meshes;
      std::vector<double> reference_hz;           // per mode
      std::vector<std::vector<double>> fe_hz;     // [mesh][mode]
      double error(unsigned int m, unsigned int k) const { return std::abs(fe_hz[m][k] - reference_hz[k]) / reference_hz[k]; }
      // Observed order between mesh m-1 and m (meshes double each time).
      double order(unsigned int m, unsigned int k) const { return std::log2(error(m - 1, k) / error(m, k)); }
    };

    FrequencyConvergence convergence_study(const Scene &scene, const std::vector<unsigned int> &meshes)
    {
      FrequencyConvergence t;
      t.meshes = meshes;
      const double EI = scene.beam.bending_stiffness(), rhoA = scene.beam.mass_per_length(), L = scene.beam.length;
      // Both ends pinned is the spring equation with k_r = 0 (βL = nπ).
      const SupportData &sup = scene.supports;
      const double k_r       = sup.type() == "pinned"   ? 0.
                               : sup.ideal_clamp ? std::numeric_limits<double>::infinity()
                                                 : sup.rotational_stiffness;
      for (const double bL : analytic::spring_supported_beta_L(n_modes, EI, L, k_r))
        t.reference_hz.push_back(analytic::frequency_from_beta_L(bL, EI, rhoA, L) / (2 * M_PI));
      for (const unsigned int n : meshes)
        {
          const FEModes modes = compute_bending_modes(FEBeam(scene, n), n_modes);
          t.fe_hz.emplace_back();
          for (const double w : modes.omega)
            t.fe_hz.back().push_back(w / (2 * M_PI));
        }
      return t;
    }

    // The FE frequencies on `meshes` (the mesh's elements split 1, 2, 4, ...
    // times) against the Richardson extrapolation of the two finest with order 4.
    FrequencyConvergence refinement_study(const Scene &scene, const std::vector<unsigned int> &meshes)
    {
      FrequencyConvergence t;
      t.meshes = meshes;
      for (const unsigned int n : meshes)
        {
          const FEModes modes = compute_bending_modes(FEBeam(scene, n), n_modes);
          t.fe_hz.emplace_back();
          for (const double w : modes.omega)
            t.fe_hz.back().push_back(w / (2 * M_PI));
        }
      const auto &fine = t.fe_hz.back(), &coarse = t.fe_hz[t.fe_hz.size() - 2];
      for (unsigned int k = 0; k < n_modes; ++k)
        t.reference_hz.push_back(fine[k] + (fine[k] - coarse[k]) / 15.);
      return t;
    }

    void write_convergence(Report &report, CsvWriter &csv, const std::string &label, const FrequencyConvergence &t)
    {
      auto &md = report.text;
      md << "| mode | reference [Hz] |";
      for (const unsigned int n : t.meshes)
        md << " n=" << n << " |";
      md << "\n|---|---|";
      for (std::size_t m = 0; m < t.meshes.size(); ++m)
        md << "---|";
      md << "\n";
      for (unsigned int k = 0; k < n_modes; ++k)
        {
          md << "| " << k + 1 << " | " << fixed(t.reference_hz[k], 4) << " |";
          for (std::size_t m = 0; m < t.meshes.size(); ++m)
            {
              md << " " << sci(t.error(m, k), 1);
              if (m > 0)
                md << " (" << fixed(t.order(m, k), 2) << ")";
              md << " |";
              csv.row({label, CsvWriter::cell(t.meshes[m]), CsvWriter::cell(k + 1), CsvWriter::cell(t.fe_hz[m][k], 12),
                       CsvWriter::cell(t.reference_hz[k], 12), CsvWriter::cell(t.error(m, k), 4),
                       m > 0 ? CsvWriter::cell(t.order(m, k), 4) : ""});
            }
          md << "\n";
        }
      md << "\nEntries: relative error of the FE frequency (observed order against the previous mesh). "
            "Once the error reaches ~1e-12 (the eigensolver tolerance and round-off) the order is meaningless.\n\n";
    }

    // Section 1.1 for a beam from a mesh, which has no closed form here:
    // the mesh's elements refined and extrapolated. Returns that study.
    FrequencyConvergence add_mesh_beam_study(Report &report, CsvWriter &csv, const Scene &scene)
    {
      const auto cells           = static_cast<unsigned int>(scene.beam.mesh_cells.size());
      const FrequencyConvergence own = refinement_study(scene, {cells, 2 * cells, 4 * cells, 8 * cells, 16 * cells});
      report.text << "### 1.1 The mesh beam under refinement\n\n"
                  << "Beam of scene `" << scene.name << "` from its mesh (" << cells << " elements, "
                  << scene.beam.sections.size() << " section(s)), each element split into 1, 2, 4, 8, 16. No closed form "
                  << "exists for it, so the reference is the Richardson extrapolation of the two finest meshes with the "
                     "Hermite cubics' order 4, f_ref = f₁₆ + (f₁₆ − f₈)/15; the observed orders show whether that order "
                     "holds (the test suite checks the stepped gallery beam against an exact transfer-matrix solution).\n\n";
      write_convergence(report, csv, "mesh", own);
      return own;
    }

    // The scene's beam with the ideal clamp at both ends.
    Scene clamped_variant(const Scene &scene)
    {
      Scene clamped                = scene;
      clamped.supports.ideal_clamp = true;
      clamped.supports.pinned_end  = {{false, false}};
      return clamped;
    }

    // The scene's beam on rotational springs: its own, or for a scene with
    // ideal supports the mueller2023 springs.
    Scene elastic_variant(const Scene &scene)
    {
      Scene elastic = scene;
      if (!elastic.supports.elastic())
        {
          elastic.supports.ideal_clamp          = false;
          elastic.supports.pinned_end           = {{false, false}};
          elastic.supports.rotational_stiffness = SupportData().rotational_stiffness;
        }
      return elastic;
    }

    // Sections 1.1 and 1.2 for a beam with a closed form: the clamped and the
    // spring-supported beam against their characteristic equations. Returns
    // the study of the scene's own supports, for the mesh choice.
    FrequencyConvergence add_analytic_studies(Report &report, CsvWriter &csv, const Scene &scene)
    {
      auto &md = report.text;
      const std::vector<unsigned int> meshes{8, 16, 32, 64, 128, 256};
      const Scene elastic       = elastic_variant(scene);
      const FrequencyConvergence cc = convergence_study(clamped_variant(scene), meshes);
      const FrequencyConvergence el = convergence_study(elastic, meshes);

      md << "### 1.1 Clamped–clamped beam against cos βL cosh βL = 1\n\n"
         << "Beam of scene `" << scene.name << "` with the ideal clamp (w = w' = u = 0 by constraints). "
         << "Hermite cubic elements: the theory predicts order 4 for the frequencies.\n\n";
      write_convergence(report, csv, "clamped", cc);
      md << "### 1.2 Spring-supported beam against its characteristic equation\n\n"
         << "Rotational springs k_r = " << elastic.supports.rotational_stiffness
         << " N m/rad at both ends (k_r L/EI = " << fixed(elastic.supports.rotational_stiffness * elastic.beam.length / elastic.beam.bending_stiffness(), 3)
         << "). Reference: the symmetric and antisymmetric conditions 2EIβ² cos a + k_r β (cos a tanh a + sin a) = 0 and "
            "2EIβ² sin a tanh a + k_r β (sin a − tanh a cos a) = 0 (a = βL/2), solved by bisection independently of the FE code. "
            "The axial spring k_t does not enter the linear bending problem.\n\n";
      write_convergence(report, csv, "elastic", el);

      // The scene's own supports (clamped-pinned has no closed form here:
      // the clamped table stands in for it, which is what the mesh choice needs).
      const std::string type = scene.supports.type();
      return type == "pinned" ? convergence_study(scene, meshes) : scene.supports.elastic() ? el : cc;
    }

    // Section 1.3: the coarsest mesh of the sequence whose frequency error on
    // the reduced model's N modes is below a tenth of the error the time
    // stepping itself makes on mode N (the midpoint rule lengthens the period
    // of an oscillation ω by the relative amount (ωΔt)²/24), against the
    // scene's mesh: `default_beam`, whose modes took `ms` to solve.
    void add_default_mesh_choice(Report &report, const Scene &scene, const FrequencyConvergence &own,
                                 const FEBeam &default_beam, const FEModes &default_modes, const double ms)
    {
      auto &md = report.text;
      const unsigned int N        = scene.discretisation.n_modes;
      const double omega_N        = 2 * M_PI * own.reference_hz[N - 1];
      const double dt_error       = std::pow(omega_N * scene.time_stepping.time_step, 2) / 24;
      const double threshold      = std::min(1e-3, 0.1 * dt_error);
      unsigned int sufficient     = 0;
      for (std::size_t m = 0; m < own.meshes.size() && sufficient == 0; ++m)
        {
          double worst = 0;
          for (unsigned int k = 0; k < N; ++k)
            worst = std::max(worst, own.error(m, k));
          if (worst < threshold)
            sufficient = own.meshes[m];
        }
      double worst_default = 0;
      for (unsigned int k = 0; k < N; ++k)
        worst_default = std::max(worst_default, std::abs(default_modes.omega[k] / (2 * M_PI) - own.reference_hz[k]) / own.reference_hz[k]);

      md << "### 1.3 Default mesh\n\n"
         << "The midpoint time stepping at Δt = " << scene.time_stepping.time_step << " s changes the frequency of mode " << N
         << " (the highest the reduced model keeps) by (ω_N Δt)²/24 = " << sci(dt_error, 1)
         << ". A mesh needs no better accuracy than a tenth of that (and 1e-3 at most): threshold " << sci(threshold, 1)
         << ". The coarsest mesh of the sequence that meets it on modes 1–" << N << " has "
         << (sufficient ? std::to_string(sufficient) : std::string("more than ") + std::to_string(own.meshes.back())) << " elements. The scene uses "
         << scene.discretisation.n_elements << " elements (" << default_beam.n_dofs() << " DoFs with axial degree "
         << scene.discretisation.axial_degree << "); its largest error on these modes is " << sci(worst_default, 2)
         << (worst_default < threshold ? " — sufficient" : " — NOT sufficient: refine the scene's mesh") << ". Solving for the "
         << n_modes << " lowest modes on the default mesh took " << fixed(ms, 1) << " ms (assembly and SLEPc; the first SLEPc call of a process adds PETSc's start-up).\n\n";
    }

    // Section 1.4: the slider bonded to the beam at 21 positions, the FE
    // frequency against seed Eq. 5 (rows in bonded_slider.csv).
    void add_bonded_slider_comparison(Report &report, const Scene &scene, const FEBeam &default_beam,
                                      CsvWriter &bonded_csv)
    {
      auto &md = report.text;
      // 128 elements, or the mesh's elements split in four.
      const FEBeam fine_beam(scene, scene.beam.from_mesh() ? 4 * scene.beam.mesh_cells.size() : 128);
      const FEModes bare = compute_bending_modes(fine_beam, 1);
      md << "### 1.4 Slider bonded to the beam against seed Eq. 5\n\n"
         << "The slider (m = " << scene.slider_mass() * 1e3 << " g, J_C = " << scene.slider_inertia() * 1e6
         << " kg mm²) attached rigidly at x_C: mass on w(x_C), rotary inertia on w'(x_C). Eq. 5 at zero amplitude, "
            "ω̃₁² = ω₁²/(1 + m φ₁(x_C)² + J φ₁'(x_C)²), is the Rayleigh quotient of the bare first mode and therefore an upper bound; "
            "its error is the change of the mode shape that a heavy slider causes.\n\n"
         << "| x_C/L | FE " << scene.discretisation.n_elements << " el. [Hz] | FE 128 el. [Hz] | Eq. 5 [Hz] | (Eq. 5 − FE)/FE |\n|---|---|---|---|---|\n";
      double worst_eq5 = 0, worst_at = 0;
      for (unsigned int i = 0; i <= 20; ++i)
        {
          const double s = 0.025 * i, x = s * scene.beam.length;
          const BondedBody body{x, scene.slider_mass(), scene.slider_inertia()};
          const double f      = compute_bending_modes(default_beam, 1, body).omega[0] / (2 * M_PI);
          const double f_fine = compute_bending_modes(fine_beam, 1, body).omega[0] / (2 * M_PI);
          const double phi = fine_beam.deflection(bare.shapes[0], x), dphi = fine_beam.slope(bare.shapes[0], x);
          const double eq5 =
            single_mode_backbone_frequency_with_slider(bare.omega[0], 0, 0, body.mass, body.inertia, phi, dphi) / (2 * M_PI);
          const double rel = (eq5 - f_fine) / f_fine;
          if (rel > worst_eq5)
            worst_eq5 = rel, worst_at = s;
          bonded_csv.row({CsvWriter::cell(s, 4), CsvWriter::cell(f), CsvWriter::cell(f_fine), CsvWriter::cell(eq5), CsvWriter::cell(rel, 4)});
          if (i % 2 == 0)
            md << "| " << fixed(s, 3) << " | " << fixed(f, 2) << " | " << fixed(f_fine, 2) << " | " << fixed(eq5, 2)
               << " | " << sci(rel, 2) << " |\n";
        }
      md << "\nEq. 5 lies above the FE frequency everywhere, by at most " << fixed(100 * worst_eq5, 1) << " % (at x_C/L = " << worst_at
         << "): a one-mode Rayleigh quotient is accurate where the slider barely changes the mode shape (at the clamp and near the centre) "
            "and least accurate where a heavy slider sits on a steep part of the mode. The test suite checks that Rayleigh–Ritz with 1, 3, 7 bare "
            "modes decreases monotonically toward the FE value.\n\n";
    }
  } // namespace

  void add_frequency_section(Report &report, const Scene &scene)
  {
    auto &md = report.text;
    console() << "[verify] linear frequencies: convergence studies ..." << std::endl;
    CsvWriter csv(report.dir + "/frequency_convergence.csv",
                  {"supports", "n_elements", "mode", "fe_frequency_hz", "analytic_frequency_hz", "relative_error", "observed_order"});
    md << "## 1. Linear frequencies\n\n";
    // The scene's own supports, for the mesh choice below.
    const FrequencyConvergence own =
      scene.beam.from_mesh() ? add_mesh_beam_study(report, csv, scene) : add_analytic_studies(report, csv, scene);

    const auto start = std::chrono::steady_clock::now();
    const FEBeam default_beam(scene);
    const FEModes default_modes = compute_bending_modes(default_beam, n_modes);
    const double ms = 1e3 * elapsed_seconds(start);
    add_default_mesh_choice(report, scene, own, default_beam, default_modes, ms);

    console() << "[verify] linear frequencies: bonded slider against Eq. 5 ..." << std::endl;
    CsvWriter bonded_csv(report.dir + "/bonded_slider.csv",
                         {"x_over_L", "fe_frequency_hz", "fe_fine_frequency_hz", "eq5_frequency_hz", "eq5_relative_difference"});
    add_bonded_slider_comparison(report, scene, default_beam, bonded_csv);

    md << "![Frequency convergence](frequency_convergence.png)\n\n![Bonded slider](bonded_slider.png)\n\n";
    // Whole files (renamed into place as they close) before the chart reads them.
    csv.close();
    bonded_csv.close();
    run_plot_script("plot_frequencies.py", {report.dir});
  }
} // namespace beamslider
