#include "numerics/elapsed.h"
#include "verification/studies/coefficient_methods.h"

#include "fem/fe_conservative_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_statics.h"
#include "scene/scene.h"
#include "reduced/harmonic_balance.h"
#include "reduced/rom_operator.h"

#include <chrono>

namespace beamslider
{
  const std::vector<std::string> &coefficient_methods()
  {
    static const std::vector<std::string> methods{"analytic", "step", "step-condensed", "ice"};
    return methods;
  }

  CoefficientResult compute_coefficients(const FEBeam &beam, const FEModes &modes, const ModalBasis &basis,
                                         const std::string &method, const double amplitude_over_h)
  {
    const unsigned int N = basis.n_modes();
    const auto start     = std::chrono::steady_clock::now();
    CoefficientResult r;
    r.method = method;

    const Eigen::VectorXd amplitudes =
      step_amplitudes(max_abs_deflection(beam, modes, N), amplitude_over_h * beam.beam_data().thickness);
    const Eigen::MatrixXd omega2 = basis.omega.array().square().matrix().asDiagonal();
    FEStatics statics(beam, modes, N);

    if (method == "analytic")
      {
        r.fit.cubic      = ReducedOrderModel(basis, 0.).analytic_cubic_terms();
        r.fit.amplitudes = Eigen::VectorXd::Zero(N);
      }
    else if (method == "step")
      r.fit = identify_cubic_step([&](const Eigen::VectorXd &q) { return statics.modal_force_plain(q); }, {amplitudes, omega2});
    else if (method == "step-condensed")
      r.fit = identify_cubic_step([&](const Eigen::VectorXd &q) { return statics.modal_force_condensed(q); },
                                  {amplitudes, omega2});
    else if (method == "ice")
      {
        IceSettings settings;
        settings.omega      = basis.omega;
        settings.amplitudes = amplitudes;
        r.fit = identify_cubic_ice([&](const Eigen::VectorXd &f) { return statics.modal_static_response(f); }, settings);
      }
    else
      throw InputError("--method '" + method + "' is not one of analytic, step, step-condensed, ice");

    r.n_static_solves = statics.n_static_solves();
    r.n_linear_solves = statics.n_linear_solves();
    r.seconds         = elapsed_seconds(start);
    return r;
  }
} // namespace beamslider

// ---------------------------------------------------------------------------
// FE-implied b_111 (see the header).

namespace beamslider
{
  FEImpliedCoefficient fe_implied_b111(const FEBeam &beam, const FEModes &modes, const unsigned int n_harmonics)
  {
    const auto start = std::chrono::steady_clock::now();
    const double L = beam.beam_data().length, h = beam.beam_data().thickness;
    const FEConservativeSystem fe = make_fe_conservative_system(beam);

    BackboneSettings settings;
    settings.hb.n_harmonics = n_harmonics;
    settings.output         = fe.deflection_at(0.5 * L);
    settings.mode           = 0;
    settings.start_amplitude = 0.05 * h;
    settings.end_amplitude   = 0.3 * h;
    settings.method          = BackboneSettings::Method::amplitude;
    settings.initial_step = settings.max_step = 0.05 / 0.3 * 0.5; // ŵ/h steps of 0.025
    const Backbone backbone = compute_backbone(fe.system, settings);
    if (!backbone.completed)
      throw std::runtime_error("FE-implied b_111: the FE backbone stopped before ŵ/h = 0.3: " + backbone.message);

    FEImpliedCoefficient r;
    r.omega_1     = modes.omega[0];
    r.n_harmonics = n_harmonics;
    r.n_points    = backbone.points.size();
    Eigen::MatrixXd A(r.n_points, 2);
    Eigen::VectorXd y(r.n_points);
    for (unsigned int i = 0; i < r.n_points; ++i)
      {
        const double a = backbone.points[i].amplitude / h;
        A(i, 0)        = a * a;
        A(i, 1)        = a * a * a * a;
        y[i]           = std::pow(backbone.points[i].omega / r.omega_1, 2) - 1.;
      }
    const Eigen::Vector2d cd = A.colPivHouseholderQr().solve(y);
    r.c = cd[0];
    r.d = cd[1];
    const double phi_centre = beam.deflection(modes.shapes[0], 0.5 * L);
    r.b_111   = 4. * r.c * phi_centre * phi_centre * r.omega_1 * r.omega_1 / (3. * h * h);
    r.seconds = elapsed_seconds(start);
    return r;
  }
} // namespace beamslider
