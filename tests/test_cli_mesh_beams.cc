// Beams from Gmsh meshes, end to end: the gallery's stepped beam through
// `coefficients --method ice` and `simulate`, and every kind of bad mesh a
// clear error with exit status 2 (scene/beam_mesh.h lists them).
#include "cli_runner.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace beamslider::testing;

namespace
{
  const std::string meshes = BEAMSLIDER_SOURCE_DIR "/meshes/";

  // A Gmsh 2.2 file with the given nodes (x, y) and elements (type, physical
  // tag, node numbers from 1).
  std::string msh(const std::vector<std::pair<double, double>> &nodes,
                  const std::vector<std::tuple<int, int, std::vector<int>>> &elements)
  {
    std::ostringstream s;
    s << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << nodes.size() << '\n';
    for (std::size_t i = 0; i < nodes.size(); ++i)
      s << i + 1 << ' ' << nodes[i].first << ' ' << nodes[i].second << " 0\n";
    s << "$EndNodes\n$Elements\n" << elements.size() << '\n';
    for (std::size_t i = 0; i < elements.size(); ++i)
      {
        const auto &[type, tag, ids] = elements[i];
        s << i + 1 << ' ' << type << " 2 " << tag << ' ' << tag;
        for (const int id : ids)
          s << ' ' << id;
        s << '\n';
      }
    s << "$EndElements\n";
    return s.str();
  }

  // A scene of one steel section (tag 1) on the mesh file beside it.
  std::string scene_on(const std::string &mesh_file, const std::string &thickness_table = "1: 0.001")
  {
    return "subsection Beam\n  set Mesh file = " + mesh_file +
           "\nend\nsubsection Sections\n  set Width = 1: 0.01404\n  set Thickness = " + thickness_table +
           "\n  set Young's modulus = 1: 2.1e11\n  set Density = 1: 7683\nend\n";
  }

  void write(const std::filesystem::path &path, const std::string &text)
  {
    std::ofstream out(path);
    out << text;
    ASSERT_TRUE(out.good()) << path;
  }

  // `beamslider modes` on a scene with this mesh: exit status 2 and a
  // message with every one of `expected`.
  void expect_refused(const std::string &name, const std::string &mesh_text, const std::vector<std::string> &expected,
                      const std::string &thickness_table = "1: 0.001")
  {
    const auto dir = fresh_folder("mesh_" + name);
    write(dir / "beam.msh", mesh_text);
    write(dir / "beam.prm", scene_on("beam.msh", thickness_table));
    const CliRun run = run_beamslider({"modes", (dir / "beam.prm").string(), "--output", (dir / "out").string()});
    EXPECT_EQ(run.exit_code, 2) << name << ":\n" << run.err;
    for (const auto &text : expected)
      EXPECT_NE(run.err.find(text), std::string::npos) << name << ": '" << text << "' not in\n" << run.err;
    std::filesystem::remove_all(dir);
  }
} // namespace

TEST(MeshBeamCli, BadMeshesAreClearErrorsWithExitTwo)
{
  // The good mesh first: two elements, so that the cases below differ from
  // it in one defect each.
  {
    const auto dir = fresh_folder("mesh_good");
    write(dir / "beam.msh", msh({{0, 0}, {0.07, 0}, {0.14, 0}}, {{1, 1, {1, 2}}, {1, 1, {2, 3}}}));
    write(dir / "beam.prm", scene_on("beam.msh"));
    const CliRun run = run_beamslider({"modes", (dir / "beam.prm").string(), "--set",
                                       "Discretisation/Number of elements=32", "--output", (dir / "out").string()});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    std::filesystem::remove_all(dir);
  }
  expect_refused("missing_tag", msh({{0, 0}, {0.07, 0}, {0.14, 0}}, {{1, 1, {1, 2}}, {1, 2, {2, 3}}}),
                 {"Sections/Width", "no value for physical tag 2", "its tags: 1, 2"});
  expect_refused("unknown_tag", msh({{0, 0}, {0.07, 0}, {0.14, 0}}, {{1, 1, {1, 2}}, {1, 1, {2, 3}}}),
                 {"Sections/Thickness", "tag 5", "no element"}, "1: 0.001, 5: 0.002");
  expect_refused("decreasing_x", msh({{0, 0}, {0.07, 0}, {0.14, 0}}, {{1, 1, {1, 2}}, {1, 1, {3, 2}}}),
                 {"from x = 0.14 m to x = 0.07 m", "x must increase"});
  expect_refused("two_dimensional", msh({{0, 0}, {0.14, 0}, {0.07, 0.05}}, {{2, 1, {1, 2, 3}}}),
                 {"line elements", "2D"});
  expect_refused("gap", msh({{0, 0}, {0.06, 0}, {0.08, 0}, {0.14, 0}}, {{1, 1, {1, 2}}, {1, 1, {3, 4}}}),
                 {"a gap between elements from x = 0.06 m to x = 0.08 m"});
  expect_refused("off_axis", msh({{0, 0}, {0.07, 0.01}, {0.14, 0}}, {{1, 1, {1, 2}}, {1, 1, {2, 3}}}),
                 {"off the x axis"});
  expect_refused("empty_file", "", {"Mesh file", "beam.msh"});
  {
    const auto dir = fresh_folder("mesh_missing");
    write(dir / "beam.prm", scene_on("nothere.msh"));
    const CliRun run = run_beamslider({"modes", (dir / "beam.prm").string(), "--output", (dir / "out").string()});
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find("nothere.msh' does not exist"), std::string::npos) << run.err;
    std::filesystem::remove_all(dir);
  }
}

TEST(MeshBeamCli, SteppedBeamCoefficientsAndSimulation)
{
  const auto dir = fresh_folder("mesh_stepped");
  {
    const CliRun run = run_beamslider({"coefficients", meshes + "stepped.prm", "--method", "ice", "--modes", "3",
                                       "--output", (dir / "coefficients").string(), "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string csv = read_file(dir / "coefficients" / "coefficients.csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')).find("n,j,k,l"), 0u) << csv.substr(0, 80);
    // parameters.prm names the mesh by its absolute path, so the folder
    // repeats the run wherever it is started from.
    const std::string prm = read_file(dir / "coefficients" / "parameters.prm");
    EXPECT_NE(prm.find("set Mesh file       = " + meshes + "stepped.msh"), std::string::npos);
  }
  {
    const CliRun run = run_beamslider(
      {"simulate", meshes + "stepped.prm", "--end-time", "0.05", "--output", (dir / "simulate").string(), "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(read_file(dir / "simulate" / "periods.csv").find('\n'), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}
