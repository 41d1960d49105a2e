// ParaView animation of a beam–slider run, see vtk_animation.h.
#include "output/vtk_animation.h"

#include "io/output_file.h"
#include "output/vtk_xml_file.h"

#include <deal.II/base/data_out_base.h>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkQuad.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace beamslider
{
  namespace
  {
    std::string frame_file(const std::string &part, const unsigned int index, const char *extension)
    {
      std::ostringstream s;
      s << part << "_" << std::setw(5) << std::setfill('0') << index << extension;
      return s.str();
    }

    void add_field(vtkDataObject &data, const char *name, const double value)
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(name);
      a->InsertNextValue(value);
      data.GetFieldData()->AddArray(a);
    }

    vtkNew<vtkDoubleArray> make_array(const char *name, const int components)
    {
      vtkNew<vtkDoubleArray> a;
      a->SetName(name);
      a->SetNumberOfComponents(components);
      return a;
    }
  } // namespace

  AnimationFrame make_animation_frame(const MoreauStepper &stepper)
  {
    AnimationFrame f;
    const SystemState &state = stepper.state();
    f.t                      = state.t;
    const BeamSystem &beam = stepper.beam();
    const BeamFieldSamples samples = beam.sample_fields(state.q);
    // Each sample with the thickness to its right; where the thickness
    // changes at a sample (a step of a mesh beam at an element boundary), the
    // sample is repeated with the thickness to its left, so that the drawn
    // surface has the step instead of a ramp.
    for (std::size_t i = 0; i < samples.x.size(); ++i)
      {
        const double h = beam.thickness_at(samples.x[i]);
        const bool step = i > 0 && h != f.beam.thickness.back();
        for (int copy = step ? 1 : 0; copy >= 0; --copy)
          {
            f.beam.x.push_back(samples.x[i]);
            f.beam.u.push_back(samples.u[i]);
            f.beam.w.push_back(samples.w[i]);
            f.beam.dw.push_back(samples.dw[i]);
            f.beam.curvature.push_back(samples.curvature[i]);
            f.beam.axial_force.push_back(samples.axial_force[i]);
            f.beam.thickness.push_back(copy == 1 ? f.beam.thickness.back() : h);
          }
      }
    f.beam.base_displacement = stepper.base().displacement(state.t);

    const SliderParameters &p = stepper.slider();
    f.slider.s                = state.s;
    f.slider.window_width     = p.window_width;
    f.slider.window_height    = p.window_height;
    f.slider.com_offset       = p.com_offset;
    BeamPointKinematics point;
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      {
        f.slider.corner[k] = state.s.head<2>() + stepper.geometry().corner_offset(k, state.s[2]);
        const Eigen::Vector2d P = stepper.corner_impulses()[k] / stepper.time_step();
        f.slider.force[k].setZero();
        if (P.isZero())
          continue;
        // n = ζ(−sin α, cos α), t = ζ(−cos α, −sin α) at the beam point under the corner.
        const double x = std::clamp(f.slider.corner[k][0], 0., stepper.beam().length());
        stepper.beam().evaluate(x, state.q, point);
        const double alpha = std::atan(point.dw), zeta = corner_zeta(k);
        const Eigen::Vector2d n(-zeta * std::sin(alpha), zeta * std::cos(alpha));
        const Eigen::Vector2d t(-zeta * std::cos(alpha), -zeta * std::sin(alpha));
        f.slider.force[k] = P[0] * n + P[1] * t;
      }
    return f;
  }

  VtkAnimationWriter::VtkAnimationWriter(const std::string &directory, const double magnification,
                                         const std::string &name)
    : directory_(directory)
    , name_(name)
    , magnification_(magnification)
  {
    if (!(magnification > 0.))
      throw std::invalid_argument("animation: magnification " + std::to_string(magnification) + " must be positive");
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec)
      throw std::runtime_error("animation: cannot create '" + directory_ + "': " + ec.message());
    std::ostringstream comment;
    comment << "drawn geometry of each frame (magnification " << magnification_
            << "); parts: beam_top, beam_bottom, slider_outer, slider_window (closed polylines), contact (force on "
               "the slider at a corner)";
    CsvOptions options;
    options.comment     = comment.str();
    options.flush_every = 0; // with the .pvd, every 25 frames (write())
    options.in_place    = true;
    csv_.emplace(directory_ + "/frames.csv",
                 std::vector<std::string>{"frame", "t_s", "part", "x_m", "z_m", "fx_N", "fz_N"}, options);
  }

  VtkAnimationWriter::~VtkAnimationWriter()
  {
    try
      {
        finish();
      }
    catch (...)
      {}
  }

  std::string VtkAnimationWriter::pvd_file() const { return directory_ + "/" + name_ + ".pvd"; }

  // The slider as drawn: the window centre S at m times its true height,
  // turned by atan(m tan β); a point given in the window's frame (origin
  // S, x along the window) goes to S_drawn + R(β_drawn) local.
  struct VtkAnimationWriter::DrawnSlider
  {
    DrawnSlider(const SliderFrameGeometry &s, const double m)
      : rot_drawn(std::atan(m * std::tan(s.s[2])))
    {
      const Eigen::Rotation2Dd rot_true(s.s[2]);
      const Eigen::Vector2d S_true = s.s.head<2>() + rot_true * Eigen::Vector2d(0., s.com_offset);
      S_drawn = Eigen::Vector2d(S_true[0], m * S_true[1]);
    }
    Eigen::Vector2d operator()(const Eigen::Vector2d &local) const { return S_drawn + rot_drawn * local; }

    Eigen::Rotation2Dd rot_drawn;
    Eigen::Vector2d S_drawn;
  };

  void VtkAnimationWriter::write(const AnimationFrame &frame)
  {
    const unsigned int index = times_.size();
    const double m           = magnification_;
    const BeamFrameGeometry &b = frame.beam;
    const unsigned int n_x   = b.x.size();
    if (n_x < 2 || b.w.size() != n_x || b.dw.size() != n_x || b.u.size() != n_x || b.curvature.size() != n_x ||
        b.axial_force.size() != n_x || b.thickness.size() != n_x)
      throw std::invalid_argument("animation: beam samples of inconsistent length");

    write_beam(frame, index);
    const DrawnSlider drawn(frame.slider, m);
    write_slider(frame, index, drawn);
    write_contacts(frame, index, drawn);

    times_.push_back(frame.t);
    if (times_.size() % 25 == 0)
      {
        write_pvd();
        csv_->flush();
      }
  }

  // Beam: bottom and top surface points of the drawn axis.
  void VtkAnimationWriter::write_beam(const AnimationFrame &frame, const unsigned int index)
  {
    const double m             = magnification_;
    const BeamFrameGeometry &b = frame.beam;
    const unsigned int n_x     = b.x.size();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble(); // µm deflections on a 0.14 m beam
    auto displacement = make_array("displacement", 3);
    auto deflection   = make_array("deflection", 1);
    auto axial_force  = make_array("axial_force", 1);
    auto curvature    = make_array("curvature", 1);
    std::vector<Eigen::Vector2d> top, bottom;
    for (unsigned int i = 0; i < n_x; ++i)
      {
        const double z_axis = m * (b.base_displacement + b.w[i]), slope = m * b.dw[i], h = b.thickness[i];
        const double c = 1. / std::sqrt(1. + slope * slope);
        for (const double zeta : {-1., 1.})
          {
            const Eigen::Vector2d p(b.x[i] + m * b.u[i] - zeta * 0.5 * h * slope * c, z_axis + zeta * 0.5 * h * c);
            points->InsertNextPoint(p[0], 0., p[1]);
            (zeta < 0 ? bottom : top).push_back(p);
            const double d[3] = {b.u[i] - zeta * 0.5 * h * b.dw[i], 0., b.base_displacement + b.w[i]};
            displacement->InsertNextTuple(d);
            deflection->InsertNextValue(b.w[i]);
            axial_force->InsertNextValue(b.axial_force[i]);
            curvature->InsertNextValue(b.curvature[i]);
          }
      }
    vtkNew<vtkUnstructuredGrid> grid;
    grid->SetPoints(points);
    for (unsigned int i = 0; i + 1 < n_x; ++i)
      {
        const vtkIdType ids[4] = {vtkIdType(2 * i), vtkIdType(2 * i + 2), vtkIdType(2 * i + 3), vtkIdType(2 * i + 1)};
        grid->InsertNextCell(VTK_QUAD, 4, ids);
      }
    for (auto *a : {displacement.Get(), deflection.Get(), axial_force.Get(), curvature.Get()})
      grid->GetPointData()->AddArray(a);
    add_field(*grid, "TimeValue", frame.t);
    add_field(*grid, "magnification", m);
    add_field(*grid, "base_displacement", b.base_displacement);
    write_vtk_xml<vtkXMLUnstructuredGridWriter>(*grid, directory_ + "/" + frame_file("beam", index, ".vtu"));

    for (const auto &[part, line] : {std::pair{"beam_top", &top}, std::pair{"beam_bottom", &bottom}})
      for (const auto &p : *line)
        csv_row(index, frame.t, part, p, Eigen::Vector2d::Zero());
  }

  // Slider: drawn window centre S and rotation; outer box and window as closed polylines.
  void VtkAnimationWriter::write_slider(const AnimationFrame &frame, const unsigned int index,
                                        const DrawnSlider &drawn)
  {
    const double m = magnification_;
    const SliderFrameGeometry &s = frame.slider;
    const double B = s.window_width, R = s.window_height, d = s.com_offset, wall = 0.2 * B;
    const double top = 0.5 * R + wall, bottom = -2. * d - 0.5 * R - wall; // centroid at the centre of mass (0, −d)
    const std::array<Eigen::Vector2d, 4> outer = {{Eigen::Vector2d(-0.5 * B - wall, bottom),
                                                   Eigen::Vector2d(0.5 * B + wall, bottom),
                                                   Eigen::Vector2d(0.5 * B + wall, top),
                                                   Eigen::Vector2d(-0.5 * B - wall, top)}};
    const std::array<Eigen::Vector2d, 4> window = {{Eigen::Vector2d(-0.5 * B, -0.5 * R),
                                                    Eigen::Vector2d(0.5 * B, -0.5 * R),
                                                    Eigen::Vector2d(0.5 * B, 0.5 * R),
                                                    Eigen::Vector2d(-0.5 * B, 0.5 * R)}};
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble(); // µm deflections on a 0.14 m beam
    vtkNew<vtkCellArray> lines;
    for (const auto &[part, box] : {std::pair{"slider_outer", &outer}, std::pair{"slider_window", &window}})
      {
        const vtkIdType first = points->GetNumberOfPoints();
        for (const auto &local : *box)
          {
            const Eigen::Vector2d p = drawn(local);
            points->InsertNextPoint(p[0], 0., p[1]);
          }
        const vtkIdType ids[5] = {first, first + 1, first + 2, first + 3, first};
        lines->InsertNextCell(5, ids);
        for (unsigned int k = 0; k <= 4; ++k)
          {
            const Eigen::Vector2d p = drawn((*box)[k % 4]);
            csv_row(index, frame.t, part, p, Eigen::Vector2d::Zero());
          }
      }
    vtkNew<vtkPolyData> poly;
    poly->SetPoints(points);
    poly->SetLines(lines);
    add_field(*poly, "TimeValue", frame.t);
    add_field(*poly, "magnification", m);
    add_field(*poly, "x_C", s.s[0]);
    add_field(*poly, "z_C", s.s[1]);
    add_field(*poly, "beta", s.s[2]);
    write_vtk_xml<vtkXMLPolyDataWriter>(*poly, directory_ + "/" + frame_file("slider", index, ".vtp"));
  }

  // Contacts: the four window corners (drawn) with the force on the slider.
  void VtkAnimationWriter::write_contacts(const AnimationFrame &frame, const unsigned int index,
                                          const DrawnSlider &drawn)
  {
    const double m = magnification_;
    const SliderFrameGeometry &s = frame.slider;
    const double B = s.window_width, R = s.window_height;
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble(); // µm deflections on a 0.14 m beam
    vtkNew<vtkCellArray> vertices;
    auto force  = make_array("contact_force", 3);
    auto normal = make_array("force_magnitude", 1);
    for (unsigned int k = 0; k < n_slider_corners; ++k)
      {
        const Eigen::Vector2d p = drawn(Eigen::Vector2d(corner_side(k) * 0.5 * B, corner_zeta(k) * 0.5 * R));
        const vtkIdType id      = points->InsertNextPoint(p[0], 0., p[1]);
        vertices->InsertNextCell(1, &id);
        const double F[3] = {s.force[k][0], 0., s.force[k][1]};
        force->InsertNextTuple(F);
        normal->InsertNextValue(s.force[k].norm());
        csv_row(index, frame.t, "contact", p, s.force[k]);
      }
    vtkNew<vtkPolyData> poly;
    poly->SetPoints(points);
    poly->SetVerts(vertices);
    poly->GetPointData()->AddArray(force);
    poly->GetPointData()->AddArray(normal);
    poly->GetPointData()->SetActiveVectors("contact_force");
    add_field(*poly, "TimeValue", frame.t);
    add_field(*poly, "magnification", m);
    write_vtk_xml<vtkXMLPolyDataWriter>(*poly, directory_ + "/" + frame_file("contacts", index, ".vtp"));
  }

  void VtkAnimationWriter::write_pvd() const
  {
    std::ostringstream out;
    out << "<?xml version=\"1.0\"?>\n"
        << "<!-- beam-slider animation; magnification " << magnification_
        << " (transverse displacements and slopes drawn m times; sizes true) -->\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n"
        << std::setprecision(12);
    for (unsigned int i = 0; i < times_.size(); ++i)
      {
      for (unsigned int k = 0; k < animation_parts.size(); ++k)
        out << "    <DataSet timestep=\"" << times_[i] << "\" part=\"" << k << "\" file=\""
            << frame_file(animation_parts[k].first, i, animation_parts[k].second) << "\"/>\n";
      }
    out << "  </Collection>\n</VTKFile>\n";
    // Atomically: a viewer (or a stopped run) never sees half a collection.
    write_file_atomically(pvd_file(), out.str());

    // One collection per part as well, by deal.II's writer (it has no parts:
    // every entry is part 0, hence the combined file above is our own).
    // Opened alone, each part gets its own pipeline source in ParaView and
    // so its own colour map: the beam by N or w'', the forces by magnitude.
    for (const auto &[part, extension] : animation_parts)
      {
        std::vector<std::pair<double, std::string>> series;
        for (unsigned int i = 0; i < times_.size(); ++i)
          series.emplace_back(times_[i], frame_file(part, i, extension));
        std::ostringstream record;
        dealii::DataOutBase::write_pvd_record(record, series);
        write_file_atomically(part_pvd_file(part), record.str());
      }
  }

  std::string VtkAnimationWriter::part_pvd_file(const std::string &part) const
  {
    return directory_ + "/" + name_ + "_" + part + ".pvd";
  }

  void VtkAnimationWriter::finish()
  {
    write_pvd();
    csv_->flush();
  }

  void VtkAnimationWriter::csv_row(const unsigned int frame, const double t, const std::string &part,
                                   const Eigen::Vector2d &p, const Eigen::Vector2d &force)
  {
    // 9 significant digits; a zero force is written "0".
    auto c = [](const double x) { return CsvWriter::cell(x, 9); };
    csv_->row({CsvWriter::cell(frame), c(t), part, c(p[0]), c(p[1]), c(force[0]), c(force[1])});
  }
} // namespace beamslider
