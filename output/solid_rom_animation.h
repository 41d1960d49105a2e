// The animation of a solid scene's reduced-model run on the solid itself
// (issue 26 item 9): `animate` on a scene with a Solid runs the reduced model
// built from the solid (fem/solid_reduced_model.h), whose coordinates q_n are
// the amplitudes of the solid's bending modes φ_n(X). The displacement of
// the whole strip is then
//
//   u(X, t) = w0(t) e_z + Σ_n q_n(t) φ_n(X)
//
// (w0 the base displacement, which moves the clamps and everything with
// them), written per frame as a .pvtu record with one .vtu piece, and listed
// with its physical time in <name>.pvd. Point data, both in metres:
//   displacement  u (true size: ParaView's "Warp By Vector" with the
//                 animation's magnification as scale factor draws it as the
//                 beam-line animation beside it is drawn),
//   deflection    Σ q_n φ_n, the part relative to the moving base.
//
// The solid's modes are recomputed here, by the same code and on the same
// communicator (MPI_COMM_SELF) as the reduced model's, so they are the same
// vectors with the same signs (fem/solid_modes.h fixes each sign); a few
// seconds on the 3D strip.
#pragma once

#include "scene/scene.h"

#include <Eigen/Dense>

#include <memory>
#include <string>

namespace beamslider
{
  class SolidRomAnimation
  {
  public:
    // Builds the scene's solid (scene.solid.enabled()) and its first n_modes
    // bending modes; writes into `directory` (which must exist). Starts
    // PETSc if needed. Throws InputError on a scene without a solid.
    SolidRomAnimation(const Scene &scene, unsigned int n_modes, const std::string &directory,
                      const std::string &name = "solid");
    ~SolidRomAnimation();

    // Writes frame n_frames() at time t [s]: base displacement w0 [m], modal
    // coordinates q (n_modes entries). Throws OutputError if a file cannot
    // be written.
    void write(double t, double base_displacement, const Eigen::VectorXd &q);
    // Writes <name>.pvd (also rewritten every 25 frames, so that an
    // interrupted run leaves a valid series).
    void finish();

    // u_z of Σ q_n φ_n averaged over the cross-section x [m] (0 <= x < L):
    // the solid's own reading of a frame's deflection, to hold against the
    // reduced model's w(x).
    double section_deflection(const Eigen::VectorXd &q, double x) const;

    unsigned int n_frames() const;
    std::string pvd_file() const;

    class Implementation;

  private:
    std::unique_ptr<Implementation> implementation;
  };
} // namespace beamslider
