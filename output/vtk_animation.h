// ParaView animation of a beam–slider run: a `.pvd` time series (physical
// time t [s]) with three parts per frame,
//   beam_NNNNN.vtu      the beam as a strip of quads with its thickness h in
//                       the x–z plane, deformed; point data: displacement
//                       (u − z w', 0, w0 + w) [m] (true, not magnified),
//                       deflection w relative to the base [m], axial force
//                       N = EA ε [N], curvature w'' [1/m];
//   slider_NNNNN.vtp    the slider as a rigid box outline (a drawing
//                       convention: wall B/5 around the window, centroid at
//                       the centre of mass) and its window B × R, as lines;
//   contacts_NNNNN.vtp  the four window corners with the contact force on
//                       the slider there, (P_N n + P_T t)/Δt [N], as vectors
//                       (zero when a corner is open).
// Every file carries field data TimeValue [s] and magnification [-].
//
// Magnification m: drawn transverse positions are m (w0 + w) for the beam's
// axis and m z for the slider's window centre S, slopes m w' and the slider
// rotation atan(m tan β); sizes (h, B, R) are drawn true. For m = 1 the
// drawing is the physical geometry; for m > 1 the picture stays consistent
// up to (m − 1) times the clearance (R − h)/2.
//
// The combined <name>.pvd lists the three parts of each time as parts 0, 1,
// 2; <name>_beam.pvd, <name>_slider.pvd and <name>_contacts.pvd (written by
// deal.II's DataOutBase::write_pvd_record) list one part each, for opening
// them as separate sources with separate colour maps.
//
// Alongside, frames.csv holds the drawn geometry of every frame (columns
// frame, t_s, part, x_m, z_m, fx_N, fz_N) for scripts/plot_frames.py, which
// renders a strip of stills to PNG.
#pragma once

#include "io/csv_writer.h"
#include "contact/moreau_stepper.h"

#include <Eigen/Dense>

#include <array>
#include <optional>
#include <utility>
#include <string>
#include <vector>

namespace beamslider
{
  // The beam at one instant: its fields (BeamSystem::sample_fields), the
  // base displacement and the thickness it is drawn with.
  struct BeamFrameGeometry : BeamFieldSamples
  {
    double base_displacement = 0; // w0(t) [m]
    std::vector<double> thickness; // h at each sample x [m]; a step is two samples at one x
  };

  // The slider at one instant.
  struct SliderFrameGeometry
  {
    Eigen::Vector3d s = Eigen::Vector3d::Zero(); // (x_C [m], z_C [m], β [rad])
    double window_width = 0, window_height = 0, com_offset = 0; // B, R, d [m]
    std::array<Eigen::Vector2d, n_slider_corners> corner; // absolute corner positions [m]
    std::array<Eigen::Vector2d, n_slider_corners> force;  // contact force on the slider [N]
  };

  struct AnimationFrame
  {
    double t = 0; // [s]
    BeamFrameGeometry beam;
    SliderFrameGeometry slider;
  };

  // The frame of the stepper's current state: the beam's fields as its model
  // samples them (BeamSystem::sample_fields: the FE's own fields, the ROM's
  // modes with its uniform membrane force), the slider and the contact forces
  // of the last step (corner impulses / Δt).
  AnimationFrame make_animation_frame(const MoreauStepper &stepper);

  // The parts of every frame, in the order of their part numbers in the
  // combined .pvd: name (the files' prefix) and file extension.
  inline const std::array<std::pair<const char *, const char *>, 3> animation_parts{
    {{"beam", ".vtu"}, {"slider", ".vtp"}, {"contacts", ".vtp"}}};

  class VtkAnimationWriter
  {
  public:
    // Writes into `directory` (created if needed): `<name>.pvd`, the frame
    // files and frames.csv.
    VtkAnimationWriter(const std::string &directory, double magnification, const std::string &name = "animation");
    ~VtkAnimationWriter();

    void write(const AnimationFrame &frame);
    // Writes the .pvd (also rewritten every 25 frames, so an interrupted
    // run leaves a valid series) and flushes frames.csv.
    void finish();

    unsigned int n_frames() const { return times_.size(); }
    std::string pvd_file() const;
    // The collection of one part alone (`part` one of animation_parts).
    std::string part_pvd_file(const std::string &part) const;
    const std::string &directory() const { return directory_; }

  private:
    void write_pvd() const;
    // The three parts of frame `index` (write() in this order), each with its
    // rows of frames.csv; the slider and the contacts where the slider is drawn.
    struct DrawnSlider;
    void write_beam(const AnimationFrame &frame, unsigned int index);
    void write_slider(const AnimationFrame &frame, unsigned int index, const DrawnSlider &drawn);
    void write_contacts(const AnimationFrame &frame, unsigned int index, const DrawnSlider &drawn);

    std::string directory_, name_;
    double magnification_;
    std::vector<double> times_;
    std::optional<CsvWriter> csv_; // frames.csv, opened once the folder exists
    void csv_row(unsigned int frame, double t, const std::string &part, const Eigen::Vector2d &p,
                 const Eigen::Vector2d &force);
  };
} // namespace beamslider
