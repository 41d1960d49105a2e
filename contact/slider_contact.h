// The rigid slider and its four contact corners (seed §2.3, doc/physics.md §4;
// Krack et al. 2017; Müller et al. 2023).
//
// Slider coordinates s = (x_C, z_C, β): centre of mass in absolute
// coordinates [m] and rotation [rad]; mass block diag(m, m, J_C); gravity −m g
// on z_C. Slider frame: origin S at the centre of the inner window, centre of
// mass at (0, −d) from S. Contact corners at (±B/2, ζ R/2) from S; ζ = +1 for
// the two upper corners (they touch the beam's top surface), ζ = −1 for the
// two lower ones (bottom surface).
//
// For a corner P at x_P, with w, w' the beam's displacement relative to the
// base and its slope there (c = cos α = 1/√(1+w'²)):
//   n   = ζ(−sin α, cos α),  t = ζ(−cos α, −sin α)
//   r_B = (x_P, w0 + w) + ζ (h/2)(−w', 1)
//   g_N = n·(r_P − r_B) = ζ c (z_P − w0 − w) − (h/2)/c             [m]
// with h = h(x_P), the thickness under the corner (BeamSystem::thickness_at;
// constant per element, so a step of a mesh beam between the corners is not
// a contact point of the model).
// Force directions: W_N = (∂g_N/∂(q, s))ᵀ, and the explicit time dependence
// ∂g_N/∂t = −n_z ẇ0 (the imposed velocity). The tangential direction has no
// gap function; W_T is the tangential relative velocity of the two material
// points, t·(v_P − v_B), where the beam's surface point moves with
// (−ζ(h/2) ẇ', ẇ0 + ẇ) (axial inertia neglected, doc/physics.md §5).
// The slider part of W_N neglects ∂w'/∂x_P (the beam's curvature times
// ∂g/∂w' ≈ −w' c h): BeamPointKinematics carries no w''; the term is of order
// h w'' relative to the kept w' term, below 1e-3 for the beams here.
#pragma once

#include "contact/base_excitation.h"
#include "contact/beam_system.h"
#include "scene/scene.h"

#include <Eigen/Dense>

#include <array>
#include <cmath>

namespace beamslider
{
  // Geometry and inertia of the slider, all SI.
  struct SliderParameters
  {
    double mass          = 0; // m [kg]
    double inertia       = 0; // J_C about the centre of mass [kg m²]
    double window_width  = 0; // B [m]
    double window_height = 0; // R [m]
    double com_offset    = 0; // d, centre of mass below S [m]
    double gravity       = 0; // g [m/s²]

    static SliderParameters from_scene(const Scene &scene);
    // Throws std::invalid_argument naming a parameter outside its range.
    void validate(double beam_thickness) const;
  };

  // Contact law of every corner.
  struct ContactLaw
  {
    double friction_coefficient = 0; // μ [-]
    double restitution          = 0; // e_N [-], tangential restitution is 0
    // The compliant normal law (doc/physics.md §4): k_N [N/m] and c_N
    // [N s/m] per corner; k_N = 0 is the rigid corner with Newton's law.
    double normal_stiffness = 0;
    double normal_damping   = 0;

    bool compliant() const { return normal_stiffness > 0.; }

    // c_N from e_N, k_N and the slider's mass: the slider landing flat on
    // two corners of a rigid surface leaves with e_N times its speed.
    static ContactLaw from_scene(const Scene &scene);
  };

  constexpr unsigned int n_slider_corners = 4;

  // Corner k: sx = −1, +1, −1, +1 and ζ = +1, +1, −1, −1.
  inline double corner_side(const unsigned int k) { return (k % 2 == 0) ? -1. : 1.; }
  inline double corner_zeta(const unsigned int k) { return (k < 2) ? 1. : -1.; }

  // A corner's gap and the derivatives that make its force directions, from
  // the beam's w, w' and thickness h under it (the formulas of this file's
  // header): the one place both Moreau steps take them from (the general
  // one through SliderGeometry::evaluate, the explicit modal one in
  // explicit_modal_step.cc). gap() first: an open corner needs nothing else.
  struct CornerContactGeometry
  {
    double zeta, dw, thickness; // ζ, w' [-], h [m]
    double secant, c, dz;       // 1/cos α, cos α, z_P − w0 − w [m]

    // z_P: the corner's height, w0: the base's displacement [m].
    CornerContactGeometry(const double zeta_, const double z_P, const double w0, const double w, const double dw_,
                          const double thickness_)
      : zeta(zeta_)
      , dw(dw_)
      , thickness(thickness_)
      , secant(std::sqrt(1. + dw_ * dw_))
      , c(1. / secant)
      , dz(z_P - w0 - w)
    {}
    double gap() const { return zeta * c * dz - 0.5 * thickness * secant; } // g_N [m]

    // n = ζ c (−w', 1), t = ζ c (−1, −w')
    double normal_x() const { return -zeta * c * dw; }
    double normal_z() const { return zeta * c; }
    double tangent_x() const { return -zeta * c; }
    double tangent_z() const { return -zeta * c * dw; }
    // Beam part of W_N = ∂g_N/∂q: ∂g/∂w = −ζ c, ∂g/∂w' = −w' c (ζ Δz c² + h/2).
    double dgap_dw() const { return -zeta * c; }
    double dgap_ddw() const { return -dw * c * (zeta * dz * c * c + 0.5 * thickness); }
    // Beam part of W_T = −t·v_B with v_B = (−ζ(h/2) ẇ', ẇ) (+ the base part).
    double dtangent_dw() const { return -tangent_z(); }
    double dtangent_ddw() const { return zeta * 0.5 * thickness * tangent_x(); }
  };

  // Everything the Moreau step needs about one corner at one configuration.
  struct CornerKinematics
  {
    double x = 0;   // x_P [m]
    double gap = 0; // g_N [m]
    double thickness = 0; // h(x_P), the beam's thickness under the corner [m]
    Eigen::VectorXd beam_normal;  // ∂γ_N/∂u (beam part of W_N)
    Eigen::VectorXd beam_tangent; // ∂γ_T/∂u (beam part of W_T)
    Eigen::Vector3d slider_normal;  // slider part of W_N
    Eigen::Vector3d slider_tangent; // slider part of W_T
    double imposed_normal  = 0; // ∂g_N/∂t through ẇ0 [m/s]
    double imposed_tangent = 0; // tangential relative velocity due to ẇ0 [m/s]
    // The beam parts on the coordinates they touch, for a model with local
    // kinematics (BeamSystem::has_local_kinematics; n_local = 0 otherwise):
    // beam_normal = Σ_a local_normal[a] e_{local_index[a]}, likewise the tangent.
    unsigned int n_local = 0;
    std::array<unsigned int, LocalPointKinematics::capacity> local_index{};
    std::array<double, LocalPointKinematics::capacity> local_normal{}, local_tangent{};
  };

  // What SliderGeometry::evaluate fills in.
  enum class CornerDetail
  {
    // Every corner everything, the beam parts dense (and local too, for a
    // model with local kinematics).
    full,
    // What the Moreau step needs: an open corner (g_N > 0) only x, thickness
    // and gap; a closed one its directions, their beam parts local for a
    // model with local kinematics (beam_normal, beam_tangent untouched) and
    // dense otherwise.
    for_step
  };

  // What the four corners share at one configuration and time: the
  // rotation's cosine and sine and the base motion, computed once per step
  // rather than once per corner (the transcendental functions were a tenth
  // of a reduced-order step).
  struct SliderFrame
  {
    double beta = 0, cos_beta = 1, sin_beta = 0; // [rad], [-], [-]
    double base_displacement = 0, base_velocity = 0; // w0 [m], ẇ0 [m/s]
  };

  class SliderGeometry
  {
  public:
    // beam_thickness: the beam's largest thickness, which the window must clear.
    SliderGeometry(const SliderParameters &slider, double beam_thickness);

    // Position of corner k relative to the centre of mass, in absolute axes,
    // for rotation β [m].
    Eigen::Vector2d corner_offset(unsigned int k, double beta) const;
    Eigen::Vector2d corner_offset(unsigned int k, const SliderFrame &frame) const;
    // Absolute x of corner k [m]; used to keep beam evaluations inside [0, L].
    double corner_x(unsigned int k, const Eigen::Vector3d &s) const { return s[0] + corner_offset(k, s[2])[0]; }

    // The shared part of the corners' kinematics at time t, rotation β.
    static SliderFrame frame(double t, const BaseExcitation &base, double beta);

    // Gap and force directions of corner k at time t for beam coordinates q
    // and slider coordinates s. The caller guarantees x_P ∈ [0, L].
    void evaluate(unsigned int k, double t, const BeamSystem &beam, const BaseExcitation &base,
                  const Eigen::VectorXd &q, const Eigen::Vector3d &s, CornerKinematics &out) const;
    // The same with the frame of (t, s[2]) computed by the caller, filled
    // in as `detail` says.
    void evaluate(unsigned int k, const SliderFrame &frame, const BeamSystem &beam, const Eigen::VectorXd &q,
                  const Eigen::Vector3d &s, CornerKinematics &out, CornerDetail detail = CornerDetail::full) const;

    // Slider coordinates with the window's upper edge resting on the beam at
    // x_C (β from the local slope, both upper gaps ≥ 0 and the smaller one 0).
    Eigen::Vector3d resting_position(double x_C, double t, const BeamSystem &beam, const BaseExcitation &base,
                                     const Eigen::VectorXd &q) const;

  private:
    SliderParameters slider_;
    mutable BeamPointKinematics point_; // scratch, avoids allocations per step
    mutable LocalPointKinematics local_point_;
  };
} // namespace beamslider
