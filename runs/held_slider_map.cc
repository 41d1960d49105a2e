// The held-slider system's stroboscopic map, see held_slider_map.h.
#include "runs/held_slider_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    // The largest step not above dt that divides the k periods into whole steps.
    unsigned int steps_over(const double duration, const double dt)
    {
      if (!(dt > 0.) || !std::isfinite(duration))
        throw std::invalid_argument("the held-slider map needs an excitation (finite period) and a positive time step");
      return static_cast<unsigned int>(std::ceil(duration / dt - 1e-9));
    }
  } // namespace

  std::vector<std::string> held_slider_observable_names()
  {
    return {"amplitude_over_h", "mean_fx_N", "contact_fraction", "max_solver_iterations"};
  }

  HeldSliderMap::HeldSliderMap(const Scene &scene, BeamSystem &beam, const double time_step,
                               const unsigned int periods, ProxSolverSettings solver)
    : beam_(beam)
    , stepper_(beam, SliderParameters::from_scene(scene), ContactLaw::from_scene(scene),
               BaseExcitation::from_scene(scene.excitation),
               BaseExcitation::from_scene(scene.excitation).period() * periods /
                 steps_over(BaseExcitation::from_scene(scene.excitation).period() * periods, time_step),
               solver)
    , periods_(periods)
    , steps_(steps_over(BaseExcitation::from_scene(scene.excitation).period() * periods, time_step))
    , clearance_(scene.window_height() - beam.thickness())
    , window_width_(scene.slider.window_width)
    , omega_(BaseExcitation::from_scene(scene.excitation).angular_frequency)
  {
    if (periods == 0)
      throw std::invalid_argument("the held-slider map needs at least one period");
    stepper_.set_prescribed_horizontal_position(true);
    BeamPointKinematics centre;
    beam.evaluate(0.5 * beam.length(), Eigen::VectorXd::Zero(beam.n_dofs()), centre);
    centre_grad_w_ = centre.grad_w;
  }

  Eigen::Vector4d HeldSliderMap::beam_under_slider(const double x_C, const Eigen::VectorXd &q,
                                                   const Eigen::VectorXd &u) const
  {
    BeamPointKinematics p;
    beam_.evaluate(x_C, q, p);
    const double w = p.w, dw = p.dw;
    beam_.evaluate(x_C, u, p);
    return Eigen::Vector4d(w, std::atan(dw), p.w, p.dw / (1. + dw * dw));
  }

  Eigen::VectorXd HeldSliderMap::pack(const SystemState &state) const
  {
    const Eigen::Index n = beam_.n_dofs();
    Eigen::VectorXd y(2 * n + 4);
    y.head(n)       = state.q;
    y.segment(n, n) = state.u;
    y.tail<4>()     = Eigen::Vector4d(state.s[1], state.s[2], state.v[1], state.v[2]) -
                  beam_under_slider(state.s[0], state.q, state.u);
    return y;
  }

  SystemState HeldSliderMap::unpack(const Eigen::VectorXd &y, const double x_over_L) const
  {
    const Eigen::Index n = beam_.n_dofs();
    SystemState s;
    s.t                      = 0.;
    s.q                      = y.head(n);
    s.u                      = y.segment(n, n);
    const double x_C         = x_over_L * beam_.length();
    const Eigen::Vector4d sl = y.tail<4>() + beam_under_slider(x_C, s.q, s.u);
    s.s                      = Eigen::Vector3d(x_C, sl[0], sl[1]);
    s.v                      = Eigen::Vector3d(0., sl[2], sl[3]);
    return s;
  }

  Eigen::VectorXd HeldSliderMap::resting(const double x_over_L) const
  {
    return pack(stepper_.resting_state(x_over_L * beam_.length(), 0.));
  }

  PeriodMapValue HeldSliderMap::operator()(const Eigen::VectorXd &y, const double x_over_L)
  {
    stepper_.set_state(unpack(y, x_over_L));
    double w_min = centre_grad_w_.dot(stepper_.state().q), w_max = w_min, impulse_x = 0;
    unsigned long contact_steps = 0;
    unsigned int max_iterations = 0;
    try
      {
        for (unsigned int i = 0; i < steps_; ++i)
          {
            const StepReport &r = stepper_.step();
            impulse_x += r.slider_impulse[0];
            contact_steps += r.n_active > 0;
            max_iterations     = std::max(max_iterations, r.iterations);
            const double w     = centre_grad_w_.dot(stepper_.state().q);
            w_min              = std::min(w_min, w);
            w_max              = std::max(w_max, w);
          }
      }
    catch (const std::exception &e)
      {
        // Every failure of a step (contact solver, support, unphysical or
        // non-finite state, the beam's solver) ends this period.
        throw PeriodMapFailure(e.what());
      }
    PeriodMapValue v;
    v.end         = pack(stepper_.state());
    const double duration = steps_ * stepper_.time_step();
    v.observables.resize(4);
    v.observables << 0.5 * (w_max - w_min) / beam_.thickness(), impulse_x / duration,
      static_cast<double>(contact_steps) / steps_, static_cast<double>(max_iterations);
    return v;
  }

  Eigen::VectorXd HeldSliderMap::scale(const Eigen::VectorXd &y) const
  {
    // Each beam block its largest entry, but not below the coordinates that
    // deflect the centre by the clearance (a beam at rest has no size of
    // its own); the slider's relative coordinates move within the clearance.
    const Eigen::Index n = beam_.n_dofs();
    const double q_floor = clearance_ / std::max(centre_grad_w_.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::VectorXd s(2 * n + 4);
    s.head(n).setConstant(std::max(y.head(n).cwiseAbs().maxCoeff(), q_floor));
    s.segment(n, n).setConstant(std::max(y.segment(n, n).cwiseAbs().maxCoeff(), omega_ * q_floor));
    const double z = clearance_, beta = clearance_ / window_width_;
    s.tail<4>() << z, beta, omega_ * z, omega_ * beta;
    return s;
  }

  PeriodMap HeldSliderMap::as_function()
  {
    return [this](const Eigen::VectorXd &y, const double x_over_L) { return (*this)(y, x_over_L); };
  }

  HeldSliderAttractor probe_held_slider_attractor(HeldSliderMap &map, const double x_over_L, Eigen::VectorXd y,
                                                  const unsigned int settle, const unsigned int max_k,
                                                  const unsigned int lyapunov_periods, const double tolerance)
  {
    const PeriodMap f = map.as_function();
    for (unsigned int i = 0; i < settle; ++i)
      y = f(y, x_over_L).end;
    HeldSliderAttractor a;
    a.x_over_L              = x_over_L;
    const Eigen::VectorXd s = map.scale(y);
    std::vector<Eigen::VectorXd> section;
    a.period_count          = detect_period_count(f, y, x_over_L, s, 0, max_k, tolerance, &section);
    const Eigen::Index nb   = map.n_beam_unknowns();
    for (std::size_t k = 0; k + 1 < section.size(); ++k)
      {
        const Eigen::VectorXd d = (section[k + 1] - section[0]).cwiseQuotient(s).cwiseAbs();
        a.beam_spread           = std::max(a.beam_spread, d.head(nb).maxCoeff());
        a.slider_spread         = std::max(a.slider_spread, d.tail(4).maxCoeff());
        const PeriodMapValue v  = f(section[k], x_over_L);
        a.amplitude_over_h += v.observables[0] / max_k;
        a.mean_fx += v.observables[1] / max_k;
      }
    a.state               = section.back();
    a.lyapunov_per_period = largest_lyapunov_exponent(f, a.state, x_over_L, s, lyapunov_periods);
    return a;
  }
} // namespace beamslider
