// Solid meshes from files (fem/solid_mesh): the Gmsh hexahedral strip gives
// what the generated strip gives, a tetrahedral mesh of it gives the same
// hardening, Gmsh's formats 2 and 4 read alike, an Abaqus deck of the strip
// gives the generated strip's modes and load, and a mesh that cannot serve
// is refused with an InputError naming the problem.
#include "fem/solid_coefficients.h"
#include "fem/solid_model.h"
#include "fem/solid_mesh.h"
#include "fem/solid_modes.h"
#include "fem/solid_statics.h"
#include "scene/scene.h"
#include "reduced/cubic_fit.h"
#include "tests/solid_tangent_check.h"

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

using namespace beamslider;
namespace fs = std::filesystem;
using dealii::PETScWrappers::MPI::SparseMatrix;
using dealii::PETScWrappers::MPI::Vector;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  std::vector<double> bending_frequencies(const Scene &scene, const unsigned int n)
  {
    const SolidModel<3> model(scene, MPI_COMM_WORLD);
    const SolidModes modes = compute_solid_modes(model, n);
    std::vector<double> f;
    for (unsigned int j = 0; j < n; ++j)
      f.push_back(modes.all[modes.bending[j]].omega / (2 * M_PI));
    return f;
  }

  // b_111 by ICE on mode 1 (the static hardening of the first mode).
  double ice_b111(const Scene &scene)
  {
    const SolidModel<3> model(scene, MPI_COMM_WORLD);
    const SolidModes modes = compute_solid_modes(model, 1);
    SolidModalCoefficients<3> coefficients(model, modes, 1);
    IceSettings ice;
    ice.omega      = coefficients.omega();
    ice.amplitudes = coefficients.amplitudes(0.03 * scene.beam.thickness);
    const CubicFit fit =
      identify_cubic_ice([&](const Eigen::VectorXd &f) { return coefficients.modal_static_response(f); }, ice);
    return fit.cubic.at(0).value;
  }
} // namespace

// strip-hex.msh holds the cells of the generated 70 × 4 × 1 strip (another
// vertex numbering, another cell order): the same modes. Below bending mode
// 5 lie two torsion modes; the second twists one way at one end and the
// other way at the other, so its correlation with y over the whole strip
// vanishes and only its order across the width (1: φ_z ∝ y) tells it from
// bending.
TEST(SolidMesh, GmshHexStripGivesTheGeneratedStripsModes)
{
  const auto generated = bending_frequencies(read_scene(scene_dir + "mueller2023-ideal-solid.prm"), 5);
  const auto from_file = bending_frequencies(read_scene(scene_dir + "strip-hex.prm"), 5);
  for (unsigned int j = 0; j < 5; ++j)
    EXPECT_NEAR(from_file[j] / generated[j], 1., 1e-8) << "bending mode " << j + 1;

  const SolidModel<3> model(read_scene(scene_dir + "strip-hex.prm"), MPI_COMM_WORLD);
  const SolidModes modes = compute_solid_modes(model, 5);
  std::vector<const SolidMode *> torsion;
  for (const SolidMode &m : modes.all)
    {
      if (m.shape == "torsion")
        torsion.push_back(&m);
      else if (m.shape == "bending")
        {
          EXPECT_LT(m.width_order, 0.1) << m.omega / (2 * M_PI) << " Hz: bending is nearly uniform across the width";
        }
    }
  ASSERT_EQ(torsion.size(), 2u);
  EXPECT_NEAR(torsion[1]->omega / torsion[0]->omega, 2., 0.05) << "the second torsion mode of a clamped strip";
  EXPECT_LT(torsion[1]->twist_correlation, 0.1);
  EXPECT_NEAR(torsion[1]->width_order, 1., 0.01);
}

// An Abaqus input deck in Abaqus/CAE's layout (a part, element sets, element
// surfaces SS1-SS3, a solid section of Material-1; strip-hex-abaqus.py wrote
// it) with the generated strip's cells: the same bending frequencies, the
// clamps on its surfaces 1 and 2, and the line load on surface 3 (the top)
// that of the generated strip.
TEST(SolidMesh, AbaqusDeckOfTheStripGivesTheGeneratedStripsModesAndLoad)
{
  const Scene generated = read_scene(scene_dir + "mueller2023-ideal-solid.prm");
  const Scene abaqus    = read_scene(scene_dir + "strip-hex-abaqus.prm");
  const auto f_generated = bending_frequencies(generated, 5), f_abaqus = bending_frequencies(abaqus, 5);
  for (unsigned int j = 0; j < 5; ++j)
    EXPECT_NEAR(f_abaqus[j] / f_generated[j], 1., 1e-8) << "bending mode " << j + 1;

  // The load vector's entries sum to its resultant in z less the share of
  // the clamped DoFs: on quadratic elements a uniform pressure puts 1/6 of
  // an element's load on each end node row (Simpson's weights), so with
  // n_x = 70 elements along x the clamps take 2 (1/6) / n_x of Q L.
  const double Q = 300, n_x = 70; // N/m, elements along x in both meshes
  std::vector<double> resultant;
  for (const Scene *scene : {&generated, &abaqus})
    {
      const SolidModel<3> model(*scene, MPI_COMM_WORLD);
      const SolidStatics<3> statics(model);
      const auto F = statics.line_load(Q);
      resultant.push_back(F.mean_value() * F.size());
      EXPECT_NEAR(resultant.back() / (Q * scene->beam.length), 1. - 1. / (3 * n_x), 1e-10) << scene->name;
    }
  EXPECT_NEAR(resultant[1] / resultant[0], 1., 1e-10);
}

// The published elastic supports on a mesh file: its two clamped groups (the
// end faces) become the rigid plates on the springs, as on the generated
// strip: strip-hex.msh on them gives mueller2023-solid's modes. A clamped
// group that is not an end face (strip-blocks: the blocks' outer faces) is
// refused, naming it.
TEST(SolidMesh, ElasticSupportsOnAMeshFileActAsOnTheGeneratedStrip)
{
  const auto generated = bending_frequencies(read_scene(scene_dir + "mueller2023-solid.prm"), 5);
  const auto from_file = bending_frequencies(read_scene(scene_dir + "strip-hex.prm", {"Supports/Type=elastic"}), 5);
  for (unsigned int j = 0; j < 5; ++j)
    EXPECT_NEAR(from_file[j] / generated[j], 1., 1e-8) << "bending mode " << j + 1;
  const auto clamped = bending_frequencies(read_scene(scene_dir + "strip-hex.prm"), 1);
  EXPECT_LT(from_file[0] / clamped[0], 0.99) << "the supports' springs lower f1 (the published rig's 2 %)";

  try
    {
      const SolidModel<3> model(read_scene(scene_dir + "strip-blocks.prm", {"Supports/Type=elastic"}),
                                MPI_COMM_WORLD);
      ADD_FAILURE() << "elastic supports on the blocks' faces were accepted";
    }
  catch (const InputError &e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find("is not an end face"), std::string::npos) << message;
      EXPECT_NE(message.find("Supports/Type"), std::string::npos) << message;
    }
}

// Gmsh format 2 and format 4 of one tetrahedral mesh: the same model.
TEST(SolidMesh, GmshFormatsTwoAndFourReadAlike)
{
  const auto v4 = bending_frequencies(read_scene(scene_dir + "strip-tet.prm"), 2);
  const auto v2 = bending_frequencies(read_scene(scene_dir + "strip-tet.prm", {"Solid/Mesh file=strip-tet-v2.msh"}), 2);
  for (unsigned int j = 0; j < 2; ++j)
    EXPECT_NEAR(v2[j] / v4[j], 1., 1e-10) << "bending mode " << j + 1;
}

// The tangent of quadratic tetrahedra (simplex quadrature, the simplex
// mapping) is the derivative of their internal force: the cubic law makes
// the Richardson combination of central differences exact.
TEST(SolidMesh, TangentOnTetrahedraIsTheDerivativeOfTheInternalForce)
{
  const SolidModel<3> model(read_scene(scene_dir + "strip-tet.prm"), MPI_COMM_WORLD);
  EXPECT_TRUE(model.simplex());
  EXPECT_LT(beamslider::testing::tangent_defect(model, 11), 1e-10);
}

// The hardening of mode 1 does not depend on the cell type: ICE's b_111 on
// the hexahedral and on the tetrahedral mesh of the strip (the same 70 × 4 × 1
// boxes, each cut into 6 quadratic tetrahedra) agree within 1 %.
TEST(SolidMesh, HexAndTetMeshesGiveTheSameHardening)
{
  const double hex = ice_b111(read_scene(scene_dir + "strip-hex.prm"));
  const double tet = ice_b111(read_scene(scene_dir + "strip-tet.prm"));
  std::cout << "ICE b_111: hexahedra " << hex << ", tetrahedra " << tet << " (" << 100 * (tet / hex - 1) << " %)\n";
  EXPECT_NEAR(tet / hex, 1., 0.01);
}

namespace
{
  // A two-hexahedron strip in Gmsh format 2 (x ∈ [0, L] in two cells, the
  // Beam's width and thickness), with `edit` applied to its text first.
  struct BadMesh
  {
    fs::path folder;
    BadMesh()
      : folder(fs::temp_directory_path() / ("beamslider_bad_mesh_" + std::to_string(::getpid())))
    {
      fs::create_directories(folder);
    }
    ~BadMesh() { fs::remove_all(folder); }

    static std::string text(const std::string &nodes_override = "", const std::string &second_hex_tag = "1",
                            const bool with_volumes = true, const std::string &names = "")
    {
      const double L = 0.14, b = 0.01404, h = 0.001;
      std::ostringstream s;
      s.precision(17);
      s << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
      s << "$PhysicalNames\n"
        << (names.empty() ? "4\n2 1 \"clamp_left\"\n2 2 \"clamp_right\"\n3 1 \"steel\"\n3 2 \"block\"\n" : names)
        << "$EndPhysicalNames\n";
      s << "$Nodes\n12\n";
      if (nodes_override.empty())
        {
          int id = 1;
          for (const double z : {-h / 2, h / 2})
            for (const double y : {-b / 2, b / 2})
              for (const double x : {0., L / 2, L})
                s << id++ << " " << x << " " << y << " " << z << "\n";
        }
      else
        s << nodes_override;
      s << "$EndNodes\n$Elements\n" << (with_volumes ? 4 : 2) << "\n";
      // Node n(i, j, k) = 1 + i + 3 j + 6 k; the end faces as quads (type 3).
      s << "1 3 2 1 1 1 4 10 7\n2 3 2 2 2 3 6 12 9\n";
      if (with_volumes)
        for (int i = 0; i < 2; ++i)
          {
            auto n = [i](int di, int j, int k) { return 1 + i + di + 3 * j + 6 * k; };
            s << 3 + i << " 5 2 " << (i == 0 ? "1" : second_hex_tag) << " 1 " << n(0, 0, 0) << " " << n(1, 0, 0)
              << " " << n(1, 1, 0) << " " << n(0, 1, 0) << " " << n(0, 0, 1) << " " << n(1, 0, 1) << " "
              << n(1, 1, 1) << " " << n(0, 1, 1) << "\n";
          }
      s << "$EndElements\n";
      return s.str();
    }

    // The error that building the solid on this mesh gives ("" if none).
    std::string error(const std::string &mesh_text, const std::vector<std::string> &settings = {}) const
    {
      const fs::path mesh = folder / "bad.msh";
      std::ofstream(mesh) << mesh_text;
      std::vector<std::string> overrides = {"Solid/Mesh file=" + mesh.string()};
      overrides.insert(overrides.end(), settings.begin(), settings.end());
      try
        {
          const Scene scene = read_scene(scene_dir + "strip-hex.prm", overrides);
          const SolidModel<3> model(scene, MPI_COMM_WORLD);
        }
      catch (const InputError &e)
        {
          return e.what();
        }
      return "";
    }
  };

  // The nodes of BadMesh with node `id` moved to (x, y, z).
  std::string nodes_with(const int moved, const double x, const double y, const double z)
  {
    const double L = 0.14, b = 0.01404, h = 0.001;
    std::ostringstream s;
    s.precision(17);
    int id = 1;
    for (const double zz : {-h / 2, h / 2})
      for (const double yy : {-b / 2, b / 2})
        for (const double xx : {0., L / 2, L})
          {
            if (id == moved)
              s << id++ << " " << x << " " << y << " " << z << "\n";
            else
              s << id++ << " " << xx << " " << yy << " " << zz << "\n";
          }
    return s.str();
  }
} // namespace

TEST(SolidMesh, BadMeshesAreRefusedWithTheirProblemNamed)
{
  const BadMesh bad;
  const std::string materials = "Solid/Materials=steel: 2.1e11 0.3 7683";
  // The well-formed mesh is accepted: what follows fails for its one defect.
  EXPECT_EQ(bad.error(BadMesh::text()), "");

  // No clamped group: the file names none of the scene's groups.
  const std::string no_clamp = bad.error(
    BadMesh::text("", "1", true, "1\n3 1 \"steel\"\n"));
  EXPECT_NE(no_clamp.find("Solid/Clamped boundaries"), std::string::npos) << no_clamp;
  EXPECT_NE(no_clamp.find("clamp_left"), std::string::npos) << no_clamp;

  // A clamped group no face carries.
  const std::string unused = bad.error(BadMesh::text(), {"Solid/Clamped boundaries=clamp_left, 7"});
  EXPECT_NE(unused.find("no boundary face"), std::string::npos) << unused;

  // A cell folded over itself: node 11 (x = L/2, top, y = b/2) pulled past
  // the cell's left end; a flat cell: node 12 (x = L, top, y = b/2) dropped
  // onto the bottom face.
  const std::string folded = bad.error(BadMesh::text(nodes_with(11, -0.1, 0.00702, 0.0005)));
  EXPECT_NE(folded.find("cell"), std::string::npos) << folded;
  EXPECT_TRUE(folded.find("inverted") != std::string::npos || folded.find("degenerate") != std::string::npos) << folded;
  const std::string flat = bad.error(BadMesh::text(nodes_with(12, 0.14, 0.00702, -0.0005)));
  EXPECT_NE(flat.find("degenerate"), std::string::npos) << flat;

  // A surface mesh given to a 3d scene.
  const std::string surface = bad.error(BadMesh::text("", "1", false));
  EXPECT_NE(surface.find("3D"), std::string::npos) << surface;

  // A cell region the Materials entry does not list, and one it lists that
  // no cell carries.
  const std::string unlisted = bad.error(BadMesh::text("", "2"), {materials});
  EXPECT_NE(unlisted.find("region 2 have no material"), std::string::npos) << unlisted;
  const std::string absent = bad.error(BadMesh::text(), {materials + ", block: 2.1e11 0.3 7850"});
  EXPECT_NE(absent.find("no cell"), std::string::npos) << absent;
  for (const std::string &message : {no_clamp, unused, folded, flat, surface, unlisted, absent})
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

// A hexahedron whose two faces are listed the other way round (the top face
// first: a mirrored, left-handed cell) is turned by deal.II's reader into the
// right-handed cell it describes, and accepted: the same mesh, as
// doc/scenes.md §2b says. Only a cell folded over itself or flat is refused
// (above).
TEST(SolidMesh, AHexahedronWithItsFacesSwappedIsReorientedAndAccepted)
{
  const BadMesh bad;
  const std::string mesh = BadMesh::text(), first_hex = "3 5 2 1 1 1 2 5 4 7 8 11 10\n";
  std::string swapped = mesh;
  const auto at = swapped.find(first_hex);
  ASSERT_NE(at, std::string::npos) << mesh;
  swapped.replace(at, first_hex.size(), "3 5 2 1 1 7 8 11 10 1 2 5 4\n");
  EXPECT_EQ(bad.error(swapped), "");

  const auto cell_volumes = [&bad](const std::string &text) {
    const fs::path file = bad.folder / "volumes.msh";
    std::ofstream(file) << text;
    const Scene scene = read_scene(scene_dir + "strip-hex.prm", {"Solid/Mesh file=" + file.string()});
    dealii::Triangulation<3> tria;
    make_solid_mesh(scene, tria);
    std::vector<double> volumes;
    for (const auto &cell : tria.active_cell_iterators())
      volumes.push_back(cell->measure());
    return volumes;
  };
  const std::vector<double> original = cell_volumes(mesh), reoriented = cell_volumes(swapped);
  ASSERT_EQ(reoriented.size(), original.size());
  for (std::size_t c = 0; c < original.size(); ++c)
    {
      EXPECT_GT(reoriented[c], 0.) << "cell " << c;
      EXPECT_NEAR(reoriented[c], original[c], 1e-12 * original[c]) << "cell " << c;
    }
}
