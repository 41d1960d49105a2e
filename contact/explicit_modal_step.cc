// The Moreau midpoint step of moreau_stepper.h taken on the explicit
// reduced model's own data (contact/explicit_modal_form.h) instead of
// through the BeamSystem interface. The scheme, the contact geometry
// (slider_contact.h), the prox solver, the checks and the works are those
// of MoreauStepper::step(); what differs is the form of the arithmetic:
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

  const StepReport &MoreauStepper::step_explicit_modal()
  {
    const ExplicitModalForm &f = *modal_;
    const unsigned int n       = f.n_modes;
    const double t_B           = state_.t;
    const double half_dt       = 0.5 * dt_; // θ = ½: the midpoint rule
    const double t_M           = t_B + half_dt;
    report_                    = StepReport();

    Eigen::Vector3d v_B = state_.v;
    if (prescribed_x_)
      v_B[0] = 0.;
    const Eigen::Vector3d s_M = state_.s + half_dt * v_B;

    // The slider frame and the base motion at t_M: w0 = (â/Ω²) cos Ωt,
    // ẇ0 = −(â/Ω) sin Ωt and the load's ẅ0 = −â cos Ωt from one sine and
    // cosine when the beam's load and the slider's base are one excitation.
    SliderFrame frame;
    frame.beta     = s_M[2];
    frame.cos_beta = std::cos(s_M[2]);
    frame.sin_beta = std::sin(s_M[2]);
    double base_acceleration = 0.;
    if (base_.angular_frequency != 0.)
      {
        const double Omega = base_.angular_frequency, a_hat = base_.acceleration_amplitude;
        const double phase = Omega * t_M;
        const double c = std::cos(phase), s = std::sin(phase);
        frame.base_displacement = a_hat / (Omega * Omega) * c;
        frame.base_velocity     = -a_hat / Omega * s;
        base_acceleration       = -a_hat * c;
      }
    if (f.excitation.angular_frequency != base_.angular_frequency ||
        f.excitation.acceleration_amplitude != base_.acceleration_amplitude)
      base_acceleration = f.excitation.acceleration(t_M);
    check_corners_on_beam(t_B, s_M, frame);

    // q_M, and the free velocity u_free = u_B + Δt h with
    // h = −c∘u_B − ω²∘q_M − N K'q_M + γ ẅ0 and N = ½ k_ax q_Mᵀ K' q_M.
    // Eigen's expressions over the N modes: inline, vectorised loops (raw
    // pointers would leave the compiler guessing at aliasing).
    using ConstArray = Eigen::Map<const Eigen::ArrayXd>;
    const ConstArray damping(f.damping, n), omega_squared(f.omega_squared, n), gamma(f.gamma, n);
    const double *u = state_.u.data();
    q_M_ = state_.q + half_dt * state_.u;
    double axial_force = 0.;
    if (f.membrane_stiffness != 0.)
      {
        stretch_q_.setZero();
        for (unsigned int j = 0; j < n; ++j)
          stretch_q_ += Eigen::Map<const Eigen::VectorXd>(f.stretch + static_cast<std::size_t>(j) * n, n) * q_M_[j];
        axial_force = 0.5 * f.membrane_stiffness * dot(q_M_.data(), stretch_q_.data(), n);
      }
    u_free_.array() = state_.u.array() + dt_ * (-damping * state_.u.array() - omega_squared * q_M_.array() -
                                                axial_force * stretch_q_.array() + gamma * base_acceleration);
    const double *q_M = q_M_.data(), *u_free = u_free_.data();
    const Eigen::Vector3d v_free = v_B + dt_ * Eigen::Vector3d(0., -slider_.gravity, 0.);
    const Eigen::Vector3d inv_mass(prescribed_x_ ? 0. : 1. / slider_.mass, 1. / slider_.mass, 1. / slider_.inertia);

    // The corners at the midpoint: gaps, and for a closed corner its
    // directions (slider_contact.h has the formulas and their derivation).
    std::array<unsigned int, n_slider_corners> active{};
    unsigned int m = 0;
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      {
        const double px = corner_position_[k][0], pz = corner_position_[k][1];
        const double r_x = frame.cos_beta * px - frame.sin_beta * pz;
        const double r_z = frame.sin_beta * px + frame.cos_beta * pz;
        const double x_P = s_M[0] + r_x, z_P = s_M[1] + r_z;

        const unsigned int e = interval_holding(f.vertices, f.n_intervals, x_P);
        const double h_e = f.vertices[e + 1] - f.vertices[e], inv_h = 1. / h_e;
        std::array<double, 4> N, dN;
        hermite_shape((x_P - f.vertices[e]) * inv_h, h_e, inv_h, N, dN);
        const double *coefficients = f.coefficients + 4 * static_cast<std::size_t>(n) * e;
        using Nodal = Eigen::Map<const Eigen::Vector4d>; // one mode's (w0, θ0, w1, θ1) on the interval
        Eigen::Vector4d nodal = Eigen::Vector4d::Zero();  // the same of Σ φ_n q_M,n
        for (unsigned int i = 0; i < n; ++i)
          nodal += Nodal(coefficients + 4 * static_cast<std::size_t>(i)) * q_M[i];
        const double w  = N[0] * nodal[0] + N[1] * nodal[1] + N[2] * nodal[2] + N[3] * nodal[3];
        const double dw = dN[0] * nodal[0] + dN[1] * nodal[1] + dN[2] * nodal[2] + dN[3] * nodal[3];

        const double thickness = f.thickness->at(x_P);
        const CornerContactGeometry g(corner_zeta(k), z_P, frame.base_displacement, w, dw, thickness);
        if (!corner_is_closed(k, g.gap(), thickness, t_B))
          continue;

        const double n_x = g.normal_x(), n_z = g.normal_z();
        const double t_x = g.tangent_x(), t_z = g.tangent_z();
        // W_b's columns: Σ_a coefficient_a (∂g/∂w N_a + ∂g/∂w' N'_a) per mode.
        const Eigen::Map<const Eigen::Vector4d> N_(N.data()), dN_(dN.data());
        const Eigen::Vector4d shape_normal  = g.dgap_dw() * N_ + g.dgap_ddw() * dN_;
        const Eigen::Vector4d shape_tangent = g.dtangent_dw() * N_ + g.dtangent_ddw() * dN_;
        double *W_normal = W_b_.col(2 * m).data(), *W_tangent = W_b_.col(2 * m + 1).data();
        for (unsigned int i = 0; i < n; ++i)
          {
            const Nodal c_i(coefficients + 4 * static_cast<std::size_t>(i));
            W_normal[i]  = c_i.dot(shape_normal);
            W_tangent[i] = c_i.dot(shape_tangent);
          }
        W_s_.col(2 * m)     = Eigen::Vector3d(n_x, n_z, -r_z * n_x + r_x * n_z);
        W_s_.col(2 * m + 1) = Eigen::Vector3d(t_x, t_z, -r_z * t_x + r_x * t_z);
        imposed_[2 * m]     = -n_z * frame.base_velocity;
        imposed_[2 * m + 1] = -t_z * frame.base_velocity;
        active[m++]         = k;
      }
    report_.n_active = m;

    std::array<Eigen::Vector2d, n_slider_corners> new_warm;
    for (auto &p : new_warm)
      p.setZero();
    u_E_ = u_free_;
    Eigen::Vector3d v_E = v_free;
    if (m > 0)
      {
        const unsigned int m2 = 2 * m;
        // G = W_bᵀ W_b + W_sᵀ M_s⁻¹ W_s (S = I), and the relative velocities
        // at the start, γ_B = W_bᵀ u_B + W_sᵀ v_B + imposed, and of the free
        // motion, c_free = W_bᵀ u_free + W_sᵀ v_free + imposed.
        auto G = G_.topLeftCorner(m2, m2);
        Eigen::Matrix<double, max_unknowns, 1> c_free;
        for (unsigned int j = 0; j < m2; ++j)
          {
            const double *W_j = W_b_.col(j).data();
            for (unsigned int i = 0; i <= j; ++i)
              {
                const double g = dot(W_b_.col(i).data(), W_j, n) + W_s_(0, i) * inv_mass[0] * W_s_(0, j) +
                                 W_s_(1, i) * inv_mass[1] * W_s_(1, j) + W_s_(2, i) * inv_mass[2] * W_s_(2, j);
                G(i, j) = G(j, i) = g;
              }
            gamma_B_[j] = dot(W_j, u, n) + W_s_.col(j).dot(v_B) + imposed_[j];
            c_free[j]   = dot(W_j, u_free, n) + W_s_.col(j).dot(v_free) + imposed_[j];
          }
        c_.head(m2) = c_free.head(m2);
        solve_contact_impulses(t_B, active, m, gamma_B_);
        const auto P = P_.head(m2);

        // u_E = u_free + W_b P, v_E = v_free + M_s⁻¹ W_s P.
        for (unsigned int j = 0; j < m2; ++j)
          u_E_ += W_b_.col(j) * P[j];
        report_.slider_impulse.noalias() = W_s_.leftCols(m2).lazyProduct(P);
        v_E += inv_mass.cwiseProduct(report_.slider_impulse);
        for (unsigned int i = 0; i < m; ++i)
          new_warm[active[i]] = P.segment<2>(2 * i);

        // Contact work: impulse × mean relative velocity, with the end's
        // relative velocities γ_E = W_bᵀ u_E + W_sᵀ v_E + imposed = c_free + G P.
        for (unsigned int i = 0; i < m2; ++i)
          {
            const double gamma_mean = 0.5 * (gamma_B_[i] + c_free[i] + G.row(i).dot(P));
            (i % 2 == 0 ? report_.work_impact : report_.work_friction) += P[i] * gamma_mean;
          }
        report_.work_base_contact = -P.dot(imposed_.head(m2));
      }

    // The end state, checked before it replaces the old one.
    q_next_ = q_M_ + half_dt * u_E_;
    const Eigen::Vector3d s_E = s_M + half_dt * v_E;
    if (!q_next_.allFinite() || !u_E_.allFinite() || !s_E.allFinite() || !v_E.allFinite())
      throw_non_finite_end(t_B);

    // The works of gravity, of the damping forces −c∘u_B and of the load
    // γ ẅ0: impulse times the mean velocity (moreau_stepper.h).
    report_.work_gravity = -slider_.mass * slider_.gravity * (s_E[1] - state_.s[1]);
    const auto u_mean       = 0.5 * (state_.u.array() + u_E_.array());
    report_.work_damping    = -dt_ * (damping * state_.u.array() * u_mean).sum();
    report_.work_excitation = dt_ * base_acceleration * (gamma * u_mean).sum();

    accept_step(s_E, v_E, new_warm);
    return report_;
  }
} // namespace beamslider
