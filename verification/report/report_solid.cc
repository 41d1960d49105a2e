// Verification section "Where von Kármán stops being enough": see report.h.
//
// The 1D FE beam (Euler–Bernoulli kinematics, von Kármán strain) beside the
// St. Venant–Kirchhoff continuum of the same strip on the same supports
// (fem/solid_model.h), twice:
//   ν = 0, plane stress (140 × 1 Q2 elements): what beam theory assumes, so
//          the two must agree up to shear and rotary inertia (Timoshenko);
//   ν = 0.3, 3D (70 × 4 × 1 Q2): the strip as built, a plate 14 h wide.
// Compared: frequencies of bending modes 1–5, the mid-span static deflection
// under the line loads that bend the beam to h, 2 h and 4 h, b_111 by ICE
// and the single-mode backbone ω/ω₁ it gives at ŵ = h and 2 h; with --full
// also the adaptation end state of the solid's ROM against the beam's (an
// ensemble each on the signature move, W₁ with its interval).
#include "io/csv_writer.h"
#include "fem/fe_beam.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/fe_statics.h"
#include "fem/petsc_session.h"
#include "fem/solid_coefficients.h"
#include "fem/solid_modal_basis.h"
#include "fem/solid_model.h"
#include "fem/solid_modes.h"
#include "fem/solid_statics.h"
#include "numerics/newton.h"
#include "reduced/beam_backbone.h"
#include "reduced/cubic_fit.h"
#include "numerics/elapsed.h"
#include "verification/report/report.h"
#include "verification/studies/coefficient_methods.h"
#include "io/console.h"
#include "verification/studies/ensemble.h"
#include "verification/studies/simulation_cases.h"

#include <array>
#include <chrono>
#include <cmath>

namespace beamslider
{
  namespace
  {
    constexpr unsigned int n_modes = 5;
    const std::array<double, 3> deflections_over_h = {{1., 2., 4.}};
    const std::array<double, 2> backbone_amplitudes_over_h = {{1., 2.}};

    // What one model says of the strip.
    struct StripFacts
    {
      std::string name;
      std::vector<double> f_hz;         // bending modes 1–5
      std::vector<double> w_mid_over_h; // at each of the loads
      double b111     = 0;              // ICE, N = 1 [1/(s² m² kg)]
      double omega1   = 0;              // [rad/s]
      double phi1_mid = 0;              // φ₁(L/2) of the beam line [kg^-1/2]
      unsigned int n_dofs = 0;
      double seconds      = 0;

      // ω/ω₁ of the single-mode ICE model at mid-span amplitude ŵ (seed
      // Eq. 4 at the modal amplitude A = ŵ/|φ₁(L/2)|).
      double backbone(const double w_hat) const
      {
        return single_mode_backbone_frequency(omega1, b111, w_hat / std::abs(phi1_mid)) / omega1;
      }
    };

    // The 1D beam's mid-span deflection |w(L/2)| under a downward line load Q.
    double beam_deflection(const FEBeam &beam, const double Q)
    {
      dealii::Vector<double> F;
      beam.assemble_line_load(-Q, F);
      FEStatics statics(beam);
      return std::abs(beam.deflection(statics.load_path(F, 8).back().x, 0.5 * beam.length()));
    }

    // The line load that bends the beam to |w(L/2)| = target: Newton's
    // method on log w(log Q) with a secant slope (the curve runs from slope 1,
    // linear, towards 1/3, membrane), on numerics/newton.h's driver.
    double beam_load_for(const FEBeam &beam, const double target)
    {
      struct LoadForDeflection
      {
        const FEBeam &beam;
        const double target;
        double Q = 1., w = beam_deflection(beam, 1.), slope = 1.;

        NewtonState evaluate(bool)
        {
          return std::abs(w / target - 1) > 1e-9 ? NewtonState::go_on : NewtonState::converged;
        }
        void factorise() {} // the secant slope is updated by each correction
        double correct()
        {
          const double Q_next = Q * std::pow(target / w, 1. / slope), w_next = beam_deflection(beam, Q_next);
          slope                = std::log(w_next / w) / std::log(Q_next / Q);
          const double step    = std::abs(std::log(Q_next / Q));
          Q = Q_next, w = w_next;
          return step;
        }
        bool small(double) const { return false; } // converged on the deflection
      } problem{beam, target};
      NewtonControl control;
      control.max_iterations = 30;
      solve_newton(problem, control);
      const double Q = problem.Q, w = problem.w;
      if (std::abs(w / target - 1) > 1e-6)
        throw std::runtime_error("section 8: no line load found that bends the beam to " + std::to_string(target) +
                                 " m at mid-span (reached " + std::to_string(w) + " m)");
      return Q;
    }

    StripFacts beam_facts(const Scene &scene, const std::vector<double> &loads)
    {
      const auto start = std::chrono::steady_clock::now();
      StripFacts r;
      r.name = "1D FE beam (von Kármán)";
      const FEBeam beam(scene);
      r.n_dofs            = beam.n_dofs();
      const FEModes modes = compute_bending_modes(beam, n_modes);
      for (const double w : modes.omega)
        r.f_hz.push_back(w / (2 * M_PI));
      for (const double Q : loads)
        r.w_mid_over_h.push_back(beam_deflection(beam, Q) / scene.beam.thickness);
      const FEModes mode1 = compute_bending_modes(beam, 1);
      const ModalBasis basis = make_modal_basis(beam, mode1, 1);
      r.b111   = compute_coefficients(beam, mode1, basis, "ice", 0.03).fit.cubic.front().value;
      r.omega1 = basis.omega[0];
      Eigen::VectorXd phi(1), dphi(1);
      basis.evaluate(0.5 * scene.beam.length, phi, dphi);
      r.phi1_mid = phi[0];
      r.seconds  = elapsed_seconds(start);
      return r;
    }

    template <int dim>
    StripFacts solid_facts(const Scene &scene, const std::vector<double> &loads, const std::string &name)
    {
      const auto start = std::chrono::steady_clock::now();
      StripFacts r;
      r.name = name;
      const SolidModel<dim> model(scene, MPI_COMM_SELF);
      r.n_dofs               = model.n_dofs();
      const SolidModes modes = compute_solid_modes(model, n_modes);
      for (unsigned int k = 0; k < n_modes; ++k)
        r.f_hz.push_back(modes.all[modes.bending[k]].omega / (2 * M_PI));

      SolidStatics<dim> statics(model);
      dealii::PETScWrappers::MPI::Vector u, u_ghosted, F, F_previous;
      model.reinit_vector(u);
      model.reinit_vector(F_previous);
      model.reinit_ghosted_vector(u_ghosted);
      for (const double Q : loads) // increasing: each solve continues from the last
        {
          F = statics.line_load(-Q);
          statics.solve(F, u, &F_previous);
          F_previous = F;
          u_ghosted  = u;
          r.w_mid_over_h.push_back(std::abs(statics.mid_span_deflection(u_ghosted)) / scene.beam.thickness);
        }

      // b_111 by ICE on mode 1 at the beam's load level (linear response 0.03 h).
      SolidModalCoefficients<dim> coefficients(model, modes, 1);
      r.b111 = solid_cubic_fit(coefficients, "ice", scene.beam.thickness).cubic.front().value;
      r.omega1               = coefficients.omega()[0];
      const ModalBasis basis = make_solid_modal_basis(model, modes, 1, scene);
      Eigen::VectorXd phi(1), dphi(1);
      basis.evaluate(0.5 * scene.beam.length, phi, dphi);
      r.phi1_mid = phi[0];
      r.seconds  = elapsed_seconds(start);
      return r;
    }

    std::string relative(const double solid, const double beam)
    {
      return signed_fixed(100 * (solid / beam - 1), 3) + " %";
    }

    // --full: the signature move's end state, solid ROM against beam ROM.
    void adaptation_end_state(Report &report, const std::vector<std::string> &solid_overrides)
    {
      const SimulationCase &the_case = find_case("signature-move");
      std::vector<std::string> with_solid = report.overrides;
      with_solid.insert(with_solid.end(), solid_overrides.begin(), solid_overrides.end());
      EnsembleSettings settings;
      settings.n_members = 8;
      std::array<OutcomeSamples, 2> samples;
      std::array<std::string, 2> labels;
      const std::array<Scene, 2> scenes = {{read_case_scene(report.scene_file, the_case, report.overrides),
                                            read_case_scene(report.scene_file, the_case, with_solid)}};
      for (unsigned int k = 0; k < 2; ++k)
        {
          settings.model = scene_model(scenes[k], "rom");
          labels[k]      = settings.model.label() + (k == 0 ? " (beam)" : " (3D solid, nu = 0.3)");
          console() << "  section 8: ensemble of " << labels[k] << ", " << settings.n_members << " members"
                    << std::endl;
          samples[k] = outcome_samples(run_ensemble(scenes[k], settings));
        }
      const SampleComparison x = compare_samples(samples[0].final_position, samples[1].final_position);
      const SampleComparison a = compare_samples(samples[0].final_amplitude, samples[1].final_amplitude);
      CsvWriter csv(report.dir + "/solid_adaptation.csv",
                    {"outcome", "median_beam_rom", "median_solid_rom", "w1", "w1_low", "w1_high", "spread",
                     "distinguishable"});
      auto &md = report.text;
      md << "\n**Adaptation end state** (signature move, 124 Hz, 14 m/s², from x_C/L = 0.3, "
         << the_case.end_time << " s; " << settings.n_members << " members each; " << labels[0] << " against "
         << labels[1] << "):\n\n| outcome | beam ROM median | solid ROM median | W₁ [90 % interval] | "
         << "own scatter | verdict |\n|---|---|---|---|---|---|\n";
      const std::array<std::pair<std::string, const SampleComparison *>, 2> rows = {
        {{"final x_C/L", &x}, {"final amplitude / h", &a}}};
      for (unsigned int k = 0; k < 2; ++k)
        {
          const auto &sample_a = k == 0 ? samples[0].final_position : samples[0].final_amplitude;
          const auto &sample_b = k == 0 ? samples[1].final_position : samples[1].final_amplitude;
          const SampleComparison &c = *rows[k].second;
          const double m_a = quantile(sample_a, 0.5), m_b = quantile(sample_b, 0.5);
          md << "| " << rows[k].first << " | " << fixed(m_a, 4) << " | " << fixed(m_b, 4) << " | "
             << fixed(c.wasserstein, 4) << " [" << fixed(c.interval_low, 4) << ", " << fixed(c.interval_high, 4)
             << "] | " << fixed(c.spread, 4) << " | "
             << (c.distinguishable ? "distinguishable" : "indistinguishable at this ensemble size") << " |\n";
          csv.row({rows[k].first, CsvWriter::cell(m_a), CsvWriter::cell(m_b), CsvWriter::cell(c.wasserstein),
                   CsvWriter::cell(c.interval_low), CsvWriter::cell(c.interval_high), CsvWriter::cell(c.spread),
                   c.distinguishable ? "1" : "0"});
        }
      csv.close();
    }
  } // namespace

  std::vector<std::string> solid_strip_3d_overrides()
  {
    return {"Solid/Continuum=3d",
            "Solid/Poisson's ratio=0.3",
            "Solid/Elements along length=70",
            "Solid/Elements across width=4",
            "Solid/Elements through thickness=1",
            "Solid/Degree=2"};
  }

  void add_solid_section(Report &report, const Scene &scene, const bool full)
  {
    const auto start = std::chrono::steady_clock::now();
    auto &md         = report.text;
    md << "## 8. Where von Kármán stops being enough: the beam against the continuum\n\n";
    if (!scene.beam.mesh_cells.empty() || !scene.beam.point_masses.empty() || scene.solid.enabled())
      {
        md << "_Not run: the comparison needs a uniform strip described by the scene's Beam (no beam mesh, no "
              "point masses, no Solid of its own)._\n\n";
        return;
      }
    console() << "Section 8: the 1D beam against the solid strip (nu = 0 plane stress, nu = 0.3 3D) ..."
              << std::endl;
    require_petsc();
    const double h = scene.beam.thickness;
    const FEBeam beam(scene);
    std::vector<double> loads;
    for (const double d : deflections_over_h)
      loads.push_back(beam_load_for(beam, d * h));

    std::vector<std::string> overrides = report.overrides;
    const std::vector<std::string> plane = {"Solid/Continuum=plane stress", "Solid/Poisson's ratio=0",
                                            "Solid/Elements along length=140", "Solid/Elements through thickness=1",
                                            "Solid/Degree=2"};
    const std::vector<std::string> solid3 = solid_strip_3d_overrides();
    auto with = [&](const std::vector<std::string> &extra) {
      std::vector<std::string> o = overrides;
      o.insert(o.end(), extra.begin(), extra.end());
      return read_scene(report.scene_file, o);
    };
    const Scene plane_scene = with(plane), solid_scene = with(solid3);
    const std::array<StripFacts, 3> facts = {{beam_facts(scene, loads),
                                              solid_facts<2>(plane_scene, loads, "solid, nu = 0, plane stress"),
                                              solid_facts<3>(solid_scene, loads, "solid, nu = 0.3, 3D")}};

    CsvWriter csv(report.dir + "/solid_rung.csv",
                  {"quantity", "beam", "solid_nu0_plane_stress", "solid_nu03_3d"});
    md << "The 1D FE beam (Euler–Bernoulli kinematics, von Kármán strain, " << facts[0].n_dofs
       << " DoFs) against the St. Venant–Kirchhoff solid of the same strip on the same supports: with ν = 0 in "
          "plane stress (140 × 1 Q2 elements, "
       << facts[1].n_dofs << " DoFs), what beam theory assumes, and with ν = 0.3 in 3D (70 × 4 × 1 Q2, "
       << facts[2].n_dofs
       << " DoFs), the strip as built. Differences are the solid's relative to the beam "
          "(doc/physics.md §11 explains each).\n\n"
       << "| quantity | beam | solid ν = 0 | Δ | solid ν = 0.3 (3D) | Δ |\n|---|---|---|---|---|---|\n";
    auto row = [&](const std::string &name, const double b, const double s0, const double s3, const int digits) {
      md << "| " << name << " | " << fixed(b, digits) << " | " << fixed(s0, digits) << " | " << relative(s0, b)
         << " | " << fixed(s3, digits) << " | " << relative(s3, b) << " |\n";
      csv.row({name, CsvWriter::cell(b), CsvWriter::cell(s0), CsvWriter::cell(s3)});
    };
    for (unsigned int k = 0; k < n_modes; ++k)
      row("f" + std::to_string(k + 1) + " [Hz]", facts[0].f_hz[k], facts[1].f_hz[k], facts[2].f_hz[k], 2);
    for (unsigned int k = 0; k < loads.size(); ++k)
      row("w(L/2)/h at Q = " + fixed(loads[k], 1) + " N/m", facts[0].w_mid_over_h[k], facts[1].w_mid_over_h[k],
          facts[2].w_mid_over_h[k], 4);
    md << "| b_111 (ICE) [1/(s² m² kg)] | " << sci(facts[0].b111) << " | " << sci(facts[1].b111) << " | "
       << relative(facts[1].b111, facts[0].b111) << " | " << sci(facts[2].b111) << " | "
       << relative(facts[2].b111, facts[0].b111) << " |\n";
    csv.row({"b_111", CsvWriter::cell(facts[0].b111), CsvWriter::cell(facts[1].b111), CsvWriter::cell(facts[2].b111)});
    for (const double a : backbone_amplitudes_over_h)
      row("backbone ω/ω₁ at ŵ = " + fixed(a, 0) + " h", facts[0].backbone(a * h), facts[1].backbone(a * h),
          facts[2].backbone(a * h), 4);
    csv.close();

    // Attributions, from the numbers above.
    const double shear1 = facts[1].f_hz[0] / facts[0].f_hz[0] - 1, shear5 = facts[1].f_hz[4] / facts[0].f_hz[4] - 1;
    const double plate1 = facts[2].f_hz[0] / facts[1].f_hz[0] - 1;
    const double strain4 = facts[1].w_mid_over_h.back() / facts[0].w_mid_over_h.back() - 1;
    const double poisson_b = facts[2].b111 / facts[1].b111 - 1;
    md << "\n- **Shear and rotary inertia** (ν = 0 against the beam): the frequencies are lower by "
       << fixed(-100 * shear1, 3) << " % (mode 1) to " << fixed(-100 * shear5, 3)
       << " % (mode 5): the Timoshenko correction, which grows with (n h/L)² and is the only "
          "difference beam theory predicts here.\n"
       << "- **Strain measure** (ν = 0, the exact Green–Lagrange strain against von Kármán's): at the load that "
          "bends the beam to 4 h the solid deflects "
       << signed_fixed(100 * strain4, 3) << " % differently, b_111 differs by "
       << relative(facts[1].b111, facts[0].b111) << ".\n"
       << "- **Poisson and plate effect** (ν = 0.3 in 3D against ν = 0): a strip " << fixed(scene.beam.width / h, 0)
       << " times as wide as thick cannot curl anticlastically across its width, so it bends between a beam "
          "(E) and a plate in cylindrical bending (E/(1 − ν²), +4.8 % in frequency): mode 1 is "
       << signed_fixed(100 * plate1, 2) << " %, b_111 " << signed_fixed(100 * poisson_b, 2)
       << " %. This, not shear or the strain measure, is where the von Kármán beam stops describing the strip "
          "as built; the beam would need an effective modulus between E and E/(1 − ν²).\n"
       << "- Wall time: beam " << fixed(facts[0].seconds, 1) << " s, plane-stress solid " << fixed(facts[1].seconds, 1)
       << " s, 3D solid " << fixed(facts[2].seconds, 1) << " s. Table: `solid_rung.csv`.\n";
    if (full)
      adaptation_end_state(report, solid3);
    else
      md << "\nThe adaptation end state of the solid's ROM against the beam's runs with `verify --full` "
            "(an ensemble each; about 5 min).\n";
    md << "\n_Section 8 took " << seconds_since(start) << "._\n\n";
  }
} // namespace beamslider
