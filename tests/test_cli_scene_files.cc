// Scene files and meshes that cannot hurt (issue 55): each case runs the
// built `beamslider` as a user would and asserts the exit status and the
// message's first line: the file or parameter named, nothing of a foreign
// file's content, no raw bytes, no stack trace. A case that used to hang
// (an included FIFO or /dev/zero) runs under a short CPU limit, so that it
// fails instead of hanging.
#include "tests/cli_runner.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace beamslider::testing;

namespace
{
  const std::string meshes = BEAMSLIDER_SOURCE_DIR "/meshes/";

  void write(const fs::path &path, const std::string &text)
  {
    std::ofstream out(path, std::ios::binary);
    out << text;
    ASSERT_TRUE(out.good()) << path;
  }

  std::string first_line(const std::string &text) { return text.substr(0, text.find('\n')); }

  // Exit status 2 and one line on stderr holding every one of `expected`;
  // no byte outside printable ASCII and no deal.II banner.
  void expect_input_error(const CliRun &run, const std::vector<std::string> &expected, const std::string &name)
  {
    EXPECT_FALSE(run.timed_out) << name << " hangs";
    EXPECT_EQ(run.exit_code, 2) << name << ": " << run.err;
    const std::string line = first_line(run.err);
    for (const std::string &text : expected)
      EXPECT_NE(line.find(text), std::string::npos) << name << ": '" << text << "' not in\n" << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << name << ": not one line:\n" << run.err;
    EXPECT_TRUE(std::all_of(run.err.begin(), run.err.end(),
                            [](const unsigned char c) { return c == '\n' || (c >= 0x20 && c < 0x7f); }))
      << name << ": raw bytes in the message";
    EXPECT_EQ(run.err.find("Stacktrace"), std::string::npos) << name << ": " << run.err;
  }

  // A scene of one steel section (tag 1) on the beam mesh `mesh_file`.
  std::string beam_scene_on(const std::string &mesh_file)
  {
    return "subsection Beam\n  set Mesh file = " + mesh_file +
           "\nend\nsubsection Sections\n  set Width = 1: 0.01404\n  set Thickness = 1: 0.001\n"
           "  set Young's modulus = 1: 2.1e11\n  set Density = 1: 7683\nend\n";
  }

  // A Gmsh 2.2 beam of two line elements with the physical tag `tag`, ending at x = `length`.
  std::string beam_msh(const double length, const std::string &tag = "1")
  {
    std::ostringstream s;
    s << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 " << length / 2 << " 0 0\n3 " << length
      << " 0 0\n$EndNodes\n$Elements\n2\n1 1 2 " << tag << " 1 1 2\n2 1 2 " << tag << " 1 2 3\n$EndElements\n";
    return s.str();
  }

  CliRun modes(const fs::path &scene, const fs::path &dir, const std::vector<std::string> &more = {})
  {
    std::vector<std::string> args = {"modes", scene.string(), "--output", (dir / "out").string()};
    args.insert(args.end(), more.begin(), more.end());
    return run_beamslider(args, CliLimits().timeout(20));
  }
} // namespace

// --- include lines -----------------------------------------------------------

TEST(SceneIncludes, CyclesAreRefusedWithTheChainNamed)
{
  const fs::path dir = fresh_folder("include_cycles");
  write(dir / "self.prm", "subsection Slider\n  set Mass = 0.05\nend\ninclude self.prm\n");
  write(dir / "a.prm", "include b.prm\n");
  write(dir / "b.prm", "# b\ninclude a.prm\n");
  CliRun run = modes(dir / "self.prm", dir);
  expect_input_error(run, {"Scene file", "self.prm', line 4", "is a cycle", "self.prm' includes"}, "self");
  EXPECT_EQ(run.signal, 0) << "crashed (was SIGSEGV)";
  run = modes(dir / "a.prm", dir);
  expect_input_error(run, {"b.prm', line 2", "is a cycle", "a.prm' includes '" + (dir / "b.prm").string() + "' includes"},
                     "mutual");
  fs::remove_all(dir);
}

TEST(SceneIncludes, OnlyRegularFilesOfAtMostOneMegabyteAreRead)
{
  const fs::path dir = fresh_folder("include_kinds");
  ASSERT_EQ(mkfifo((dir / "pipe.prm").c_str(), 0644), 0);
  write(dir / "zero.prm", "include /dev/zero\n");
  write(dir / "fifo.prm", "include pipe.prm\n");
  write(dir / "folder.prm", "include .\n");
  write(dir / "large.prm", "subsection Slider\n  set Mass = 0.05\nend\n" + std::string(1100000, '#') + "\n");
  write(dir / "big.prm", "include large.prm\n");
  for (const auto &[file, words] : std::vector<std::pair<std::string, std::vector<std::string>>>{
         {"zero.prm", {"zero.prm', line 1", "'/dev/zero' is not a regular file"}},
         {"fifo.prm", {"fifo.prm', line 1", "pipe.prm' is not a regular file"}},
         {"folder.prm", {"folder.prm', line 1", "is a folder"}},
         {"big.prm", {"big.prm', line 1", "large.prm' has 11000", "at most 1 MB"}},
         {"large.prm", {"large.prm' has 11000", "at most 1 MB"}}})
    {
      // /dev/zero used to grow to 2.2 GB, the FIFO to block: 10 s of CPU
      // (200 s of wall time) stop either.
      const CliRun run = run_beamslider({"modes", (dir / file).string(), "--output", (dir / "out").string()},
                                        CliLimits().timeout(10));
      expect_input_error(run, words, file);
    }
  fs::remove_all(dir);
}

TEST(SceneIncludes, AForeignFileIsNamedNeverQuoted)
{
  const fs::path dir = fresh_folder("include_foreign");
  write(dir / "secret.txt", "root:TOPSECRET:19000:0:99999:7:::\nset nothing\n");
  write(dir / "peek.prm", "subsection Slider\n  set Mass = 0.05\nend\ninclude secret.txt\n");
  // Included, and given as the scene itself.
  for (const auto &[scene, words] : std::vector<std::pair<std::string, std::vector<std::string>>>{
         {"peek.prm", {"secret.txt', line 1 (included by '", "peek.prm', line 4)", "is not a scene line"}},
         {"secret.txt", {"secret.txt', line 1", "is not a scene line"}}})
    {
      const CliRun run = modes(dir / scene, dir);
      expect_input_error(run, words, scene);
      EXPECT_EQ(run.err.find("TOPSECRET"), std::string::npos) << run.err;
      EXPECT_EQ(run.err.find("root"), std::string::npos) << run.err;
    }
  // A system file too (the first line of /etc/passwd names root).
  write(dir / "passwd.prm", "include /etc/passwd\n");
  const CliRun run = modes(dir / "passwd.prm", dir);
  expect_input_error(run, {"'/etc/passwd', line 1 (included by '", "is not a scene line"}, "/etc/passwd");
  EXPECT_EQ(run.err.find("root"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

TEST(SceneIncludes, AnIncludedSceneIsReadRelativeToItsFileAndItsErrorsNameItsLines)
{
  const fs::path dir = fresh_folder("include_good");
  fs::create_directories(dir / "parts");
  // mueller2023 without its Slider subsection, which comes from parts/.
  std::ifstream in(meshes + "mueller2023.prm");
  std::string text, line;
  bool slider = false;
  while (std::getline(in, line))
    {
      if (line.rfind("subsection Slider", 0) == 0)
        slider = true;
      if (slider)
        {
          if (line.rfind("end", 0) == 0)
            slider = false;
          continue;
        }
      text += line + "\n";
    }
  write(dir / "scene.prm", text + "include parts/slider.prm\n");
  write(dir / "parts" / "slider.prm",
        "subsection Slider\n  set Mass = 0.0506\n  set Rotary inertia = 3.15e-6\nend\n");
  const fs::path out = dir / "o";
  CliRun run = run_beamslider({"simulate", (dir / "scene.prm").string(), "--end-time", "0.01", "-q", "--output", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The folder's parameters.prm repeats the run.
  run = run_beamslider({"simulate", (out / "parameters.prm").string(), "--end-time", "0.01", "-q", "--output",
                        (dir / "again").string()});
  EXPECT_EQ(run.exit_code, 0) << run.err;

  // An error in the included file names that file and its own line.
  write(dir / "parts" / "slider.prm", "subsection Slider\n  set Mass = 0.0506\n  set Mass tuning = 3\nend\n");
  run = run_beamslider({"simulate", (dir / "scene.prm").string(), "--output", out.string()});
  expect_input_error(run, {"slider.prm', line 3", "Mass tuning"}, "bad entry");
  write(dir / "parts" / "slider.prm", "subsection Slider\n  set Mass = 0.0506\n  set Mass = 0.06\nend\n");
  run = run_beamslider({"simulate", (dir / "scene.prm").string(), "--output", out.string()});
  expect_input_error(run, {"slider.prm', line 3", "set a second time (first on line 2)"}, "twice");
  fs::remove_all(dir);
}

// --- parameters.prm records every value ----------------------------------

TEST(SceneRoundTrip, APathParametersPrmCannotRecordIsRefused)
{
  const fs::path dir = fresh_folder("roundtrip");
  // A folder with '#': the mesh path resolved against the scene's folder holds it.
  fs::create_directories(dir / "a#b");
  write(dir / "a#b" / "beam.msh", beam_msh(0.14));
  write(dir / "a#b" / "beam.prm", beam_scene_on("beam.msh"));
  CliRun run = modes(dir / "a#b" / "beam.prm", dir);
  expect_input_error(run, {"Parameter 'Beam/Mesh file' = '" + (dir / "a#b" / "beam.msh").string() + "'", "'#'",
                           "parameters.prm"},
                     "hash");
  // A newline and an escape sequence through --set: escaped in the message.
  write(dir / "beam.msh", beam_msh(0.14));
  write(dir / "beam.prm", beam_scene_on("beam.msh"));
  run = modes(dir / "beam.prm", dir, {"--set", "Beam/Mesh file=be\nam\x1b[2J.msh"});
  expect_input_error(run, {"Parameter 'Beam/Mesh file' = 'be\\nam\\x1b[2J.msh'", "control character"}, "newline");
  run = modes(meshes + "strip-blocks.prm", dir, {"--set", "Solid/Loaded boundary=top #1"});
  expect_input_error(run, {"Parameter 'Solid/Loaded boundary' = 'top #1'", "'#'"}, "group");
  // Any value the user gives is echoed on one line, its control bytes escaped.
  run = modes(meshes + "mueller2023.prm", dir, {"--set", "Slider/Mass=1\n\x1b[2Jx"});
  expect_input_error(run, {"'Slider/Mass' = '1\\n\\x1b[2Jx'"}, "number");
  run = modes(meshes + "mueller2023.prm", dir, {"--set", "Slider/Ma\nss=1"});
  expect_input_error(run, {"unknown parameter 'Slider/Ma\\nss'"}, "name");
  fs::remove_all(dir);
}

// --- bounds checked before work starts ---------------------------------------

TEST(SceneBounds, OutOfRangeValuesAreExitTwoWithParameterValueAndRange)
{
  const fs::path dir = fresh_folder("bounds");
  const std::string beam = meshes + "mueller2023.prm", solid = meshes + "mueller2023-solid.prm",
                    blocks = meshes + "strip-blocks.prm";
  const std::string steel = "2.1e11 0.3 7683";
  const std::vector<std::tuple<std::string, std::string, std::vector<std::string>>> cases = {
    {beam, "Slider/Window height ratio=1e300", {"'Slider/Window height ratio' = 1e+300", "(1, B/h = 10)"}},
    {beam, "Slider/Window height ratio=10", {"'Slider/Window height ratio' = 10", "(1, B/h = 10)"}},
    {blocks, "Solid/Materials=strip: 1e-300 0.3 7683, blocks: " + steel,
     {"'Solid/Materials' entry 'strip: 1e-300 0.3 7683'", "E = 1e-300 Pa", "[1e6, 1e13]"}},
    {blocks, "Solid/Materials=strip: 2.1e11 0.5 7683, blocks: " + steel, {"'Solid/Materials'", "nu = 0.5", "[0, 0.5)"}},
    {blocks, "Solid/Materials=strip: 2.1e11 0.3 1e9, blocks: " + steel, {"'Solid/Materials'", "rho = 1e+09", "[1, 1e5]"}},
    {blocks, "Solid/Materials=strip: " + steel + ", blocks: " + steel + ", strip: 7e10 0.3 2700",
     {"'Solid/Materials' gives the region 'strip' twice"}},
    // A name and a tag of one region: found once the mesh is read, before any solve.
    {blocks, "Solid/Materials=strip: " + steel + ", blocks: " + steel + ", 1: 7e10 0.3 2700",
     {"'Solid/Materials' gives the region of tag 1 twice, as 'strip' and as '1'"}},
    {solid, "Solid/Elements along length=100000",
     {"'Solid/Elements along length' = 100000", "need at least", "GB of memory", "memory of"}},
  };
  for (const auto &[scene, assignment, words] : cases)
    {
      std::vector<std::string> more = {"--set", assignment};
      if (assignment.rfind("Solid/Elements", 0) == 0)
        more.insert(more.end(), {"--set", "Solid/Elements across width=10000"});
      expect_input_error(modes(scene, dir, more), words, assignment);
    }

  // A beam mesh longer than Beam/Length's 10 m (was exit 1, ExcValueDoesNotMatchPattern).
  write(dir / "long.msh", beam_msh(12));
  write(dir / "long.prm", beam_scene_on("long.msh"));
  expect_input_error(modes(dir / "long.prm", dir), {"long.msh': the beam is 12 m long", "[1e-3, 10] m"}, "12 m");
  fs::remove_all(dir);
}

// --- one-line messages -------------------------------------------------------

TEST(MeshMessages, BadMeshFilesGiveOneLineNamingTheFile)
{
  const fs::path dir = fresh_folder("mesh_messages");
  // A truncated Abaqus deck: deal.II printed a 28-line stack trace first.
  {
    std::ifstream in(meshes + "strip-hex-abaqus.inp");
    std::string deck((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ifstream scene_in(meshes + "strip-hex-abaqus.prm");
    std::string scene((std::istreambuf_iterator<char>(scene_in)), std::istreambuf_iterator<char>());
    scene.replace(scene.find("strip-hex-abaqus.inp"), std::string("strip-hex-abaqus.inp").size(), "cut.inp");
    write(dir / "cut.prm", scene);
    // Cut in the nodes, and in the elements (a cell's vertex missing).
    for (const std::size_t size : {600, 20000})
      {
        write(dir / "cut.inp", deck.substr(0, size));
        expect_input_error(modes(dir / "cut.prm", dir),
                           {"Solid mesh '" + (dir / "cut.inp").string() + "'", "Abaqus", "converting the deck failed: "},
                           "truncated .inp, " + std::to_string(size) + " bytes");
      }
  }
  // A binary file given as a Gmsh mesh: its bytes escaped, the message bounded.
  {
    std::string bytes = "\x7f" "ELF\x02\x01\x01";
    for (int i = 0; i < 5000; ++i)
      bytes += static_cast<char>(i * 37 % 256);
    write(dir / "binary.msh", bytes);
    write(dir / "binary.prm", beam_scene_on("binary.msh"));
    const CliRun run = modes(dir / "binary.prm", dir);
    expect_input_error(run, {"Mesh file '" + (dir / "binary.msh").string() + "'"}, "binary .msh");
    EXPECT_LT(run.err.size(), 1000u) << run.err;
  }
  // A negative Gmsh tag, on a beam's elements and in a solid's $PhysicalNames.
  {
    write(dir / "negative.msh", beam_msh(0.14, "-1"));
    write(dir / "negative.prm", beam_scene_on("negative.msh"));
    const CliRun run = modes(dir / "negative.prm", dir);
    expect_input_error(run, {"negative.msh'", "physical tag -1"}, "negative beam tag");
    EXPECT_EQ(run.err.find("4294967295"), std::string::npos) << run.err;

    std::ifstream in(meshes + "strip-blocks.msh");
    std::string mesh((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    mesh.replace(mesh.find("3 2 \"blocks\""), 12, "3 -2 \"blocks\"");
    write(dir / "strip-blocks.msh", mesh);
    fs::copy_file(meshes + "strip-blocks.prm", dir / "strip-blocks.prm");
    const CliRun solid = modes(dir / "strip-blocks.prm", dir);
    expect_input_error(solid, {"strip-blocks.msh'", "'blocks' the tag -2"}, "negative solid tag");
    EXPECT_EQ(solid.err.find("4294967294"), std::string::npos) << solid.err;
  }
  fs::remove_all(dir);
}

TEST(MeshMessages, SceneTemplateToAFullDiskIsExitOneWithTheReason)
{
  const fs::path dir = fresh_folder("template_full");
  const fs::path err = dir / "stderr";
  const pid_t pid = fork();
  if (pid == 0)
    {
      const int full = open("/dev/full", O_WRONLY);
      const int e    = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(full, 1);
      dup2(e, 2);
      execl(BEAMSLIDER_EXECUTABLE, BEAMSLIDER_EXECUTABLE, "scene-template", static_cast<char *>(nullptr));
      _exit(127);
    }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  const std::string message = read_file(err);
  EXPECT_EQ(WEXITSTATUS(status), 1) << message;
  EXPECT_NE(first_line(message).find("scene template"), std::string::npos) << message;
  EXPECT_NE(first_line(message).find("No space left on device"), std::string::npos) << message;
  fs::remove_all(dir);
}
