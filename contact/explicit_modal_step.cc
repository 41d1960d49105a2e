// The Moreau midpoint step of moreau_stepper.h taken on the explicit
// reduced model's own data (contact/explicit_modal_form.h) instead of
// through the BeamSystem interface. The step's skeleton
// (moreau_step_skeleton.h), the contact geometry (slider_contact.h), the
// prox solver, the checks and the works are those of the general step;
// this file supplies the stages whose form of the arithmetic differs:
//
// - the base motion's sine and cosine once per step, for the corners' w0,
//   ẇ0 and the load's ẅ0 alike;
// - a corner's w, w' from the interval's nodal values of q_M (4N products),
//   and for a closed corner the directions' beam parts as the table's
//   coefficients times the shape functions already combined with ∂g/∂w,
//   ∂g/∂w' (4N products per direction, no φ and φ' formed);
// - the works of the contact impulses from γ_E = c_free + G P (the 2m ≤ 8
//   relative velocities at the end from the Delassus matrix the solver had)
//   instead of another pass over the beam's coordinates;
// - every pass over the N modes an inline loop or Eigen expression, no calls.
//
// So its results equal the general step's to round-off, not to the bit
// (tests/test_reduced_rom_contact_beam.cc runs both for the first dozens
// of periods). Units as in moreau_stepper.h.
#include "contact/hermite_shape.h"
#include "contact/moreau_step_skeleton.h"
#include "contact/moreau_stepper.h"

#include <algorithm>
#include <cmath>

namespace beamslider
{
  namespace
  {
    // Σ a_i b_i in four running sums (one AVX2 register; short chains
    // instead of one of N dependent additions).
    double dot(const double *a, const double *b, const unsigned int n)
    {
      double s0 = 0., s1 = 0., s2 = 0., s3 = 0.;
      unsigned int i = 0;
      for (; i + 4 <= n; i += 4)
        {
          s0 += a[i] * b[i];
          s1 += a[i + 1] * b[i + 1];
          s2 += a[i + 2] * b[i + 2];
          s3 += a[i + 3] * b[i + 3];
        }
      for (; i < n; ++i)
        s0 += a[i] * b[i];
      return (s0 + s1) + (s2 + s3);
    }
  } // namespace

  // The explicit modal form's stages (moreau_step_skeleton.h), on the
  // form's data. Eigen's expressions over the N modes are inline,
  // vectorised loops (raw pointers would leave the compiler guessing at
  // aliasing).
  namespace
  {
    struct ExplicitModal; // the tag of the explicit modal form's stages
  } // namespace

  template <>
  class MoreauStepper::Stages<ExplicitModal>
  {
  public:
    explicit Stages(MoreauStepper &stepper)
      : st(stepper)
      , f(*st.modal_)
      , n(f.n_modes)
      , dt_B(0.5 * st.dt_) // θ = ½: the midpoint rule
      , dt_E(dt_B)
      , damping(f.damping, n)
      , omega_squared(f.omega_squared, n)
      , gamma(f.gamma, n)
    {}

    MoreauStepper &st;
    const ExplicitModalForm &f;
    const unsigned int n;
    const double dt_B, dt_E;

    // The slider frame and the base motion at t_M: w0 = (â/Ω²) cos Ωt,
    // ẇ0 = −(â/Ω) sin Ωt and the load's ẅ0 = −â cos Ωt from one sine and
    // cosine when the beam's load and the slider's base are one excitation.
    SliderFrame detection_frame(const double t_M, const Eigen::Vector3d &s_M)
    {
      const BaseExcitation &base = st.base_;
      SliderFrame frame;
      frame.beta     = s_M[2];
      frame.cos_beta = std::cos(s_M[2]);
      frame.sin_beta = std::sin(s_M[2]);
      if (base.angular_frequency != 0.)
        {
          const double Omega = base.angular_frequency, a_hat = base.acceleration_amplitude;
          const double phase = Omega * t_M;
          const double c = std::cos(phase), s = std::sin(phase);
          frame.base_displacement = a_hat / (Omega * Omega) * c;
          frame.base_velocity     = -a_hat / Omega * s;
          base_acceleration       = -a_hat * c;
        }
      if (f.excitation.angular_frequency != base.angular_frequency ||
          f.excitation.acceleration_amplitude != base.acceleration_amplitude)
        base_acceleration = f.excitation.acceleration(t_M);
      return frame;
    }

    // u_free = u_B + Δt h with h = −c∘u_B − ω²∘q_M − N K'q_M + γ ẅ0 and
    // N = ½ k_ax q_Mᵀ K' q_M.
    void free_velocity(double /*t_M*/, const Eigen::Vector3d & /*s_M*/, const SliderFrame & /*frame*/)
    {
      const Eigen::VectorXd &q_M = st.q_M_, &u_B = st.state_.u;
      double axial_force = 0.;
      if (f.membrane_stiffness != 0.)
        {
          st.stretch_q_.setZero();
          for (unsigned int j = 0; j < n; ++j)
            st.stretch_q_ += Eigen::Map<const Eigen::VectorXd>(f.stretch + static_cast<std::size_t>(j) * n, n) * q_M[j];
          axial_force = 0.5 * f.membrane_stiffness * dot(q_M.data(), st.stretch_q_.data(), n);
        }
      st.u_free_.array() = u_B.array() + st.dt_ * (-damping * u_B.array() - omega_squared * q_M.array() -
                                                   axial_force * st.stretch_q_.array() + gamma * base_acceleration);
    }

    // The corner's gap from w, w' at x_P, from the interval's nodal values of
    // q_M (4N products); for a closed corner the directions' beam parts as
    // the table's coefficients times the shape functions already combined
    // with ∂g/∂w, ∂g/∂w' (slider_contact.h has the formulas and their
    // derivation).
    bool closed_corner(const unsigned int k, const SliderFrame &frame, const Eigen::Vector3d &s_M, const double t_B,
                       const unsigned int m)
    {
      const double px = st.corner_position_[k][0], pz = st.corner_position_[k][1];
      const double r_x = frame.cos_beta * px - frame.sin_beta * pz;
      const double r_z = frame.sin_beta * px + frame.cos_beta * pz;
      const double x_P = s_M[0] + r_x, z_P = s_M[1] + r_z;

      const unsigned int e = interval_holding(f.vertices, f.n_intervals, x_P);
      const double h_e = f.vertices[e + 1] - f.vertices[e], inv_h = 1. / h_e;
      std::array<double, 4> N, dN;
      hermite_shape((x_P - f.vertices[e]) * inv_h, h_e, inv_h, N, dN);
      const double *coefficients = f.coefficients + 4 * static_cast<std::size_t>(n) * e;
      const double *q_M          = st.q_M_.data();
      using Nodal = Eigen::Map<const Eigen::Vector4d>; // one mode's (w0, θ0, w1, θ1) on the interval
      Eigen::Vector4d nodal = Eigen::Vector4d::Zero();  // the same of Σ φ_n q_M,n
      for (unsigned int i = 0; i < n; ++i)
        nodal += Nodal(coefficients + 4 * static_cast<std::size_t>(i)) * q_M[i];
      const double w  = N[0] * nodal[0] + N[1] * nodal[1] + N[2] * nodal[2] + N[3] * nodal[3];
      const double dw = dN[0] * nodal[0] + dN[1] * nodal[1] + dN[2] * nodal[2] + dN[3] * nodal[3];

      const double thickness = f.thickness->at(x_P);
      const CornerContactGeometry g(corner_zeta(k), z_P, frame.base_displacement, w, dw, thickness);
      if (!st.corner_is_closed(k, g.gap(), thickness, t_B))
        return false;

      const double n_x = g.normal_x(), n_z = g.normal_z();
      const double t_x = g.tangent_x(), t_z = g.tangent_z();
      // W_b's columns: Σ_a coefficient_a (∂g/∂w N_a + ∂g/∂w' N'_a) per mode.
      const Eigen::Map<const Eigen::Vector4d> N_(N.data()), dN_(dN.data());
      const Eigen::Vector4d shape_normal  = g.dgap_dw() * N_ + g.dgap_ddw() * dN_;
      const Eigen::Vector4d shape_tangent = g.dtangent_dw() * N_ + g.dtangent_ddw() * dN_;
      double *W_normal = st.W_b_.col(2 * m).data(), *W_tangent = st.W_b_.col(2 * m + 1).data();
      for (unsigned int i = 0; i < n; ++i)
        {
          const Nodal c_i(coefficients + 4 * static_cast<std::size_t>(i));
          W_normal[i]  = c_i.dot(shape_normal);
          W_tangent[i] = c_i.dot(shape_tangent);
        }
      st.W_s_.col(2 * m)     = Eigen::Vector3d(n_x, n_z, -r_z * n_x + r_x * n_z);
      st.W_s_.col(2 * m + 1) = Eigen::Vector3d(t_x, t_z, -r_z * t_x + r_x * t_z);
      st.imposed_[2 * m]     = -n_z * frame.base_velocity;
      st.imposed_[2 * m + 1] = -t_z * frame.base_velocity;
      return true;
    }

    // G = W_bᵀ W_b + W_sᵀ M_s⁻¹ W_s (S = I), and the relative velocities
    // at the start, γ_B = W_bᵀ u_B + W_sᵀ v_B + imposed, and of the free
    // motion, c_free = W_bᵀ u_free + W_sᵀ v_free + imposed.
    void contact_problem(const Eigen::Index m2, const Eigen::Vector3d &v_B, const Eigen::Vector3d &v_free,
                         const Eigen::Vector3d &inv_mass)
    {
      const auto &W_b = st.W_b_;
      const auto &W_s = st.W_s_;
      const double *u = st.state_.u.data(), *u_free = st.u_free_.data();
      auto G          = st.G_.topLeftCorner(m2, m2);
      for (unsigned int j = 0; j < m2; ++j)
        {
          const double *W_j = W_b.col(j).data();
          for (unsigned int i = 0; i <= j; ++i)
            {
              const double g = dot(W_b.col(i).data(), W_j, n) + W_s(0, i) * inv_mass[0] * W_s(0, j) +
                               W_s(1, i) * inv_mass[1] * W_s(1, j) + W_s(2, i) * inv_mass[2] * W_s(2, j);
              G(i, j) = G(j, i) = g;
            }
          st.gamma_B_[j] = dot(W_j, u, n) + W_s.col(j).dot(v_B) + st.imposed_[j];
          c_free[j]      = dot(W_j, u_free, n) + W_s.col(j).dot(v_free) + st.imposed_[j];
        }
      st.c_.head(m2) = c_free.head(m2);
    }

    void add_beam_impulse(const Eigen::Index m2)
    {
      for (unsigned int j = 0; j < m2; ++j)
        st.u_E_ += st.W_b_.col(j) * st.P_[j];
    }

    // With the end's relative velocities
    // γ_E = W_bᵀ u_E + W_sᵀ v_E + imposed = c_free + G P
    // (the Delassus matrix the solver had) instead of another pass over the
    // beam's coordinates.
    void contact_work(const Eigen::Index m2, const Eigen::Vector3d & /*v_B*/, const Eigen::Vector3d & /*v_E*/)
    {
      const auto G = st.G_.topLeftCorner(m2, m2);
      const auto P = st.P_.head(m2);
      for (unsigned int i = 0; i < m2; ++i)
        {
          const double gamma_mean = 0.5 * (st.gamma_B_[i] + c_free[i] + G.row(i).dot(P));
          (i % 2 == 0 ? st.report_.work_impact : st.report_.work_friction) += P[i] * gamma_mean;
        }
    }

    // The works of the damping forces −c∘u_B and of the load γ ẅ0: impulse
    // times the mean velocity (moreau_stepper.h).
    void finish_beam()
    {
      const auto u_mean          = 0.5 * (st.state_.u.array() + st.u_E_.array());
      st.report_.work_damping    = -st.dt_ * (damping * st.state_.u.array() * u_mean).sum();
      st.report_.work_excitation = st.dt_ * base_acceleration * (gamma * u_mean).sum();
    }

  private:
    using ConstArray = Eigen::Map<const Eigen::ArrayXd>;
    const ConstArray damping, omega_squared, gamma;
    double base_acceleration = 0.; // ẅ0(t_M) of the load
    Eigen::Matrix<double, max_unknowns, 1> c_free;
  };

  const StepReport &MoreauStepper::step_explicit_modal()
  {
    Stages<ExplicitModal> stages(*this);
    return take_step(stages);
  }
} // namespace beamslider
