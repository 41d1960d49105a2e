#include "verification/coefficient_methods.h"

#include "fem/fe_modal_basis.h"
#include "fem/fe_statics.h"
#include "meshes/scene.h"
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
    r.seconds         = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }
} // namespace beamslider
