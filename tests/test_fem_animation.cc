// The animation files (output/vtk_animation, `beamslider animate`) parse as
// ParaView would read them: the .pvd's time steps and parts, and every frame
// read back with VTK's XML readers, checking point counts, time values, the
// magnification and the drawn geometry against the state it came from.
#include "runs/adaptation_run.h"
#include "fem/fe_beam.h"
#include "fem/fe_beam_system.h"
#include "fem/fe_modal_basis.h"
#include "fem/fe_modes.h"
#include "fem/fe_transient.h"
#include "output/vtk_animation.h"
#include "scene/scene.h"
#include "reduced/rom_beam_system.h"
#include "verification/cli/commands.h"
#include "tests/read_text_file.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

using namespace beamslider;
using beamslider::testing::read_file;
namespace fs = std::filesystem;

namespace
{
  const std::string scene_file = BEAMSLIDER_SOURCE_DIR "/meshes/mueller2023.prm";

  struct PvdEntry
  {
    double t;
    int part;
    std::string file;
  };

  std::vector<PvdEntry> read_pvd(const std::string &path)
  {
    const std::string s = read_file(path);
    EXPECT_NE(s.find("<VTKFile type=\"Collection\""), std::string::npos);
    std::vector<PvdEntry> entries;
    const std::regex dataset(R"re(<DataSet timestep="([^"]+)"(?: group="[^"]*")? part="(\d+)" file="([^"]+)"/>)re");
    for (auto it = std::sregex_iterator(s.begin(), s.end(), dataset); it != std::sregex_iterator(); ++it)
      entries.push_back({std::stod((*it)[1]), std::stoi((*it)[2]), (*it)[3]});
    return entries;
  }

  double field(vtkDataObject *data, const char *name)
  {
    vtkDataArray *a = data->GetFieldData()->GetArray(name);
    EXPECT_NE(a, nullptr) << name;
    return a ? a->GetTuple1(0) : std::nan("");
  }

  fs::path fresh_directory(const std::string &name)
  {
    const fs::path dir = fs::temp_directory_path() / ("beamslider_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    return dir;
  }
} // namespace

TEST(FEAnimation, PvdSeriesReadsBackWithTimesPointCountsAndGeometry)
{
  Scene s = read_scene(scene_file);
  auto beam = make_fe_beam_system(s);
  const auto &fe = dynamic_cast<const FETransientBeam &>(*beam);
  RunOptions options        = RunOptions::from_scene(s);
  options.end_time          = 0.004;
  options.progress_interval = 1e9;
  AdaptationRun run(s, *beam, options);

  const fs::path dir = fresh_directory("animation");
  const double magnification = 3.;
  std::vector<double> times;
  std::vector<double> w_mid; // w0 + w at x = L/2, as simulated
  {
    VtkAnimationWriter writer(dir.string(), magnification);
    for (unsigned int k = 0; k <= 4; ++k)
      {
        run.run_until(k * 1e-3);
        const AnimationFrame frame = make_animation_frame(run.stepper());
        writer.write(frame);
        times.push_back(run.state().t);
        BeamPointKinematics point;
        fe.evaluate(0.5 * s.beam.length, run.state().q, point);
        w_mid.push_back(run.stepper().base().displacement(run.state().t) + point.w);
      }
  } // the destructor writes the .pvd

  const std::vector<PvdEntry> entries = read_pvd((dir / "animation.pvd").string());
  ASSERT_EQ(entries.size(), 3 * times.size());
  const unsigned int n_x = 4 * s.discretisation.n_elements + 1; // samples along the beam
  for (const PvdEntry &e : entries)
    {
      const unsigned int frame = &e - entries.data();
      const double t           = times[frame / 3];
      EXPECT_NEAR(e.t, t, 1e-12);
      EXPECT_EQ(e.part, int(frame % 3));
      const std::string path = (dir / e.file).string();
      ASSERT_TRUE(fs::exists(path)) << path;
      if (e.part == 0)
        {
          vtkNew<vtkXMLUnstructuredGridReader> reader;
          reader->SetFileName(path.c_str());
          reader->Update();
          vtkUnstructuredGrid *grid = reader->GetOutput();
          ASSERT_EQ(grid->GetNumberOfPoints(), 2 * n_x);
          EXPECT_EQ(grid->GetNumberOfCells(), n_x - 1);
          EXPECT_NEAR(field(grid, "TimeValue"), t, 1e-12);
          EXPECT_EQ(field(grid, "magnification"), magnification);
          for (const char *name : {"displacement", "deflection", "axial_force", "curvature"})
            EXPECT_NE(grid->GetPointData()->GetArray(name), nullptr) << name;
          // Mid-span: the drawn axis (mean of bottom and top point) at m (w0 + w).
          const unsigned int i = n_x / 2;
          double bottom[3], top[3];
          grid->GetPoint(2 * i, bottom);
          grid->GetPoint(2 * i + 1, top);
          EXPECT_NEAR(0.5 * (bottom[2] + top[2]), magnification * w_mid[frame / 3], 1e-12);
          EXPECT_NEAR(0.5 * (bottom[0] + top[0]), 0.5 * s.beam.length, 1e-6);
          EXPECT_NEAR(top[2] - bottom[2], s.beam.thickness, 1e-3 * s.beam.thickness);
        }
      else
        {
          vtkNew<vtkXMLPolyDataReader> reader;
          reader->SetFileName(path.c_str());
          reader->Update();
          vtkPolyData *poly = reader->GetOutput();
          EXPECT_NEAR(field(poly, "TimeValue"), t, 1e-12);
          EXPECT_EQ(field(poly, "magnification"), magnification);
          if (e.part == 1)
            {
              EXPECT_EQ(poly->GetNumberOfPoints(), 8); // outer box and window
              EXPECT_EQ(poly->GetNumberOfLines(), 2);
            }
          else
            {
              ASSERT_EQ(poly->GetNumberOfPoints(), 4); // the window corners
              vtkDataArray *force = poly->GetPointData()->GetArray("contact_force");
              ASSERT_NE(force, nullptr);
              EXPECT_EQ(force->GetNumberOfComponents(), 3);
              // Compressive normal forces: up on the slider at the upper
              // corners (0, 1), down at the lower ones (2, 3); friction
              // (μ = 0.2) cannot reverse the nearly vertical normal.
              for (vtkIdType k = 0; k < 4; ++k)
                EXPECT_GE(force->GetTuple3(k)[2] * (k < 2 ? 1. : -1.), 0.) << "corner " << k;
            }
        }
    }
  // The per-part collections (deal.II's write_pvd_record): each lists its
  // part of the combined one, time by time, as a single part.
  for (unsigned int k = 0; k < animation_parts.size(); ++k)
    {
      const std::string part                 = animation_parts[k].first;
      const std::vector<PvdEntry> part_entries = read_pvd((dir / ("animation_" + part + ".pvd")).string());
      ASSERT_EQ(part_entries.size(), times.size()) << part;
      for (unsigned int i = 0; i < times.size(); ++i)
        {
          EXPECT_NEAR(part_entries[i].t, times[i], 1e-12) << part << " frame " << i;
          EXPECT_EQ(part_entries[i].part, 0) << part;
          EXPECT_EQ(part_entries[i].file, entries[3 * i + k].file) << part << " frame " << i;
        }
    }
  // frames.csv, the same drawing for plots: one frame per .pvd time, at that
  // time, and the beam drawn one thickness thick at mid-span.
  std::ifstream frames((dir / "frames.csv").string());
  ASSERT_TRUE(frames) << "frames.csv";
  std::string line;
  std::map<unsigned int, double> frame_time;
  std::map<unsigned int, std::map<std::string, std::pair<double, double>>> mid; // part → (|x − L/2|, z)
  while (std::getline(frames, line))
    {
      if (line.empty() || line[0] == '#' || line.rfind("frame,", 0) == 0)
        continue;
      std::stringstream row(line);
      std::string cell;
      std::vector<std::string> c;
      while (std::getline(row, cell, ','))
        c.push_back(cell);
      ASSERT_EQ(c.size(), 7u) << line;
      const unsigned int k = std::stoul(c[0]);
      frame_time[k]        = std::stod(c[1]);
      const double dx      = std::abs(std::stod(c[3]) - 0.5 * s.beam.length);
      const auto nearest   = mid[k].find(c[2]);
      if (nearest == mid[k].end() || dx < nearest->second.first)
        mid[k][c[2]] = {dx, std::stod(c[4])};
    }
  ASSERT_EQ(frame_time.size(), times.size());
  for (const auto &[k, t] : frame_time)
    {
      ASSERT_LT(k, times.size());
      EXPECT_NEAR(t, times[k], 1e-9) << "frame " << k;
      EXPECT_NEAR(mid[k]["beam_top"].second - mid[k]["beam_bottom"].second, s.beam.thickness,
                  1e-3 * s.beam.thickness)
        << "frame " << k;
    }
  fs::remove_all(dir);
}

TEST(FEAnimation, GenericSamplerAndTheRomsFieldsAgreeWithTheFEFields)
{
  // On a static FE mode-1 shape: the generic sampler (w, w' from
  // BeamSystem::evaluate, w'' by differences) against the FE's own fields,
  // and the ROM's fields on the FE's first mode (uniform N = k_ax ½∫w'²)
  // against the FE's pointwise axial force.
  Scene s          = read_scene(scene_file);
  auto beam        = make_fe_beam_system(s);
  const auto &fe   = dynamic_cast<const FETransientBeam &>(*beam);
  Eigen::VectorXd q;
  FETransientBeam::to_eigen(fe.modes().shapes[0], q);
  q *= 1e-3 / fe.beam().deflection(fe.modes().shapes[0], 0.5 * s.beam.length); // w(L/2) = 1 mm
  const BeamFieldSamples a = beam->sample_fields(q);
  const BeamFieldSamples b = sample_by_evaluation(*beam, q, a.x.size());
  double w_max = 0, dw_err = 0, w_err = 0, k_err = 0, k_max = 0;
  for (unsigned int i = 0; i < a.x.size(); ++i)
    {
      w_max  = std::max(w_max, std::abs(a.w[i]));
      w_err  = std::max(w_err, std::abs(a.w[i] - b.w[i]));
      dw_err = std::max(dw_err, std::abs(a.dw[i] - b.dw[i]));
      k_max  = std::max(k_max, std::abs(a.curvature[i]));
      if (i > 0 && i + 1 < a.x.size())
        k_err = std::max(k_err, std::abs(a.curvature[i] - b.curvature[i]));
    }
  EXPECT_LT(w_err, 1e-14);
  EXPECT_LT(dw_err, 1e-12);
  EXPECT_LT(k_err, 0.05 * k_max); // central differences on 129 points
  EXPECT_TRUE(std::isnan(b.axial_force[0])) << "the generic sampler does not know the axial force";

  // The ROM of one mode on the same mesh's first mode, at the same w(L/2).
  const FEBeam &mesh = fe.beam();
  RomBeamSystem rom  = RomBeamSystem::from_scene(s, make_modal_basis(mesh, compute_bending_modes(mesh, 1), 1));
  BeamPointKinematics centre;
  rom.evaluate(0.5 * s.beam.length, Eigen::VectorXd::Ones(1), centre);
  const BeamFieldSamples r = rom.sample_fields(Eigen::VectorXd::Constant(1, 1e-3 / centre.w));
  ASSERT_EQ(r.x.size(), a.x.size());
  double rom_w_err = 0;
  for (unsigned int i = 0; i < a.x.size(); ++i)
    rom_w_err = std::max(rom_w_err, std::abs(a.w[i] - r.w[i]));
  EXPECT_LT(rom_w_err, 1e-9 * w_max) << "the same mode shape (two eigensolves of the same mesh)";
  // The mode shape has u = 0: the FE axial force is EA ½w'² pointwise; its
  // mean over the beam, EA/L ½∫w'², equals the membrane force of the reduced
  // model up to the springs' compliance in k_ax.
  double mean = 0;
  for (unsigned int i = 0; i + 1 < a.x.size(); ++i)
    mean += 0.5 * (a.axial_force[i] + a.axial_force[i + 1]) * (a.x[i + 1] - a.x[i]);
  mean /= s.beam.length;
  const double k_ratio = s.supports.membrane_stiffness(s.beam) * s.beam.length / s.beam.axial_stiffness();
  EXPECT_NEAR(r.axial_force[0] / (mean * k_ratio), 1., 1e-3);
  EXPECT_EQ(r.axial_force.front(), r.axial_force.back()) << "uniform along x";
}

TEST(AnimateCommand, RomRunWritesSeriesAndStills)
{
  const fs::path dir = fresh_directory("animate_cmd");
  CommonOptions common;
  common.scene_file = scene_file;
  common.output_dir = dir.string();
  AnimateOptions options;
  options.model      = "rom";
  options.end_time   = 0.004;
  options.frame_rate = 1000.;
  EXPECT_EQ(run_animate(common, options), 0);
  const std::vector<PvdEntry> entries = read_pvd((dir / "animation.pvd").string());
  ASSERT_EQ(entries.size(), 3u * 5u);
  EXPECT_NEAR(entries.back().t, 0.004, 1e-9);
  EXPECT_TRUE(fs::exists(dir / "trace.csv"));
  EXPECT_TRUE(fs::exists(dir / "frames.png")); // needs python3-matplotlib
  fs::remove_all(dir);
}
