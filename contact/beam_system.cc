// The generic field sampler of BeamSystem (what a model gives without its own).
#include "contact/beam_system.h"

namespace beamslider
{
  BeamFieldSamples sample_by_evaluation(const BeamSystem &beam, const Eigen::VectorXd &q, const unsigned int n_samples)
  {
    if (n_samples < 3)
      throw std::invalid_argument("sample_by_evaluation: at least 3 samples needed, got " + std::to_string(n_samples));
    BeamFieldSamples g;
    const double L = beam.length();
    BeamPointKinematics p;
    for (unsigned int i = 0; i < n_samples; ++i)
      {
        const double x = L * i / (n_samples - 1);
        beam.evaluate(x, q, p);
        g.x.push_back(x);
        g.u.push_back(0.);
        g.w.push_back(p.w);
        g.dw.push_back(p.dw);
      }
    // w'' by differences of w' (one-sided at the ends).
    for (unsigned int i = 0; i < n_samples; ++i)
      {
        const unsigned int l = i == 0 ? 0 : i - 1, r = i + 1 == n_samples ? i : i + 1;
        g.curvature.push_back((g.dw[r] - g.dw[l]) / (g.x[r] - g.x[l]));
      }
    g.axial_force.assign(n_samples, std::numeric_limits<double>::quiet_NaN());
    return g;
  }

  void BeamSystem::evaluate_displacement(const double x, const Eigen::VectorXd &q, double &w, double &dw) const
  {
    evaluate(x, q, displacement_scratch_);
    w  = displacement_scratch_.w;
    dw = displacement_scratch_.dw;
  }

  void BeamSystem::evaluate_local(double, const Eigen::VectorXd &, LocalPointKinematics &) const
  {
    throw std::logic_error("BeamSystem::evaluate_local called on a model without local kinematics");
  }

  void BeamSystem::inverse_iteration_matrix_block(const unsigned int *, unsigned int, Eigen::Ref<Eigen::MatrixXd>) const
  {
    throw std::logic_error("BeamStep::inverse_iteration_matrix_block called on a model without local kinematics");
  }

  void BeamSystem::add_inverse_iteration_matrix_times(const unsigned int *, unsigned int, const double *,
                                                      Eigen::VectorXd &) const
  {
    throw std::logic_error("BeamStep::add_inverse_iteration_matrix_times called on a model without local kinematics");
  }

  BeamFieldSamples BeamSystem::sample_fields(const Eigen::VectorXd &q) const
  {
    return sample_by_evaluation(*this, q, 129);
  }
} // namespace beamslider
