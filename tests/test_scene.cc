// Scene files: the shipped scenes parse, and every class of bad input is
// rejected with a message that names the parameter, its value and the range.
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

using namespace beamslider;

namespace
{
  const std::string scene_dir = BEAMSLIDER_SOURCE_DIR "/meshes/";

  // Runs read_scene with one override and returns the error message ("" if none).
  std::string error_for(const std::string &assignment, const std::string &file = "mueller2023.prm",
                        const std::string &second = "")
  {
    try
      {
        std::vector<std::string> overrides = {assignment};
        if (!second.empty())
          overrides.push_back(second);
        read_scene(scene_dir + file, overrides);
      }
    catch (const InputError &e)
      {
        return e.what();
      }
    return "";
  }

  // Runs read_scene on a scene file with the given text and returns the
  // error message ("" if none).
  std::string error_for_file(const std::string &name, const std::string &text)
  {
    const std::string path = ::testing::TempDir() + name;
    {
      std::ofstream f(path);
      f << text;
    }
    std::string message;
    try
      {
        read_scene(path);
      }
    catch (const InputError &e)
      {
        message = e.what();
      }
    std::remove(path.c_str());
    return message;
  }

  void expect_contains(const std::string &message, const std::string &what)
  {
    EXPECT_NE(message.find(what), std::string::npos) << "message: " << message << "\nexpected to contain: " << what;
  }
} // namespace

TEST(SceneFiles, DefaultSceneHoldsThePublishedRig)
{
  const Scene s = read_scene(scene_dir + "mueller2023.prm");
  EXPECT_EQ(s.name, "mueller2023");
  // Beam mass 15.1 g (Müller, Beck & Krack 2023) from rho b h L.
  EXPECT_NEAR(s.beam.density * s.beam.width * s.beam.thickness * s.beam.length, 15.1e-3, 0.05e-3);
  EXPECT_FALSE(s.supports.ideal_clamp);
  EXPECT_DOUBLE_EQ(s.supports.rotational_stiffness, 125.);
  EXPECT_DOUBLE_EQ(s.slider.inertia, 3.15e-6);
  EXPECT_DOUBLE_EQ(s.window_height(), 1.05e-3);
}

TEST(SceneFiles, SupportTypesSetTheEnds)
{
  // pinned: both ends hinged, no springs needed (k_r = 0 allowed);
  // clamped-pinned: clamped at x = 0, hinged at x = L; elastic still asks
  // for positive springs.
  const Scene pinned = read_scene(scene_dir + "mueller2023.prm",
                                  {"Supports/Type=pinned", "Supports/Rotational stiffness=0"});
  EXPECT_EQ(pinned.supports.type(), "pinned");
  EXPECT_TRUE(pinned.supports.pinned_end[0] && pinned.supports.pinned_end[1]);
  EXPECT_FALSE(pinned.supports.elastic());
  EXPECT_DOUBLE_EQ(pinned.supports.membrane_stiffness(pinned.beam), pinned.beam.axial_stiffness() / pinned.beam.length);
  const Scene mixed = read_scene(scene_dir + "mueller2023.prm", {"Supports/Type=clamped-pinned"});
  EXPECT_EQ(mixed.supports.type(), "clamped-pinned");
  EXPECT_TRUE(mixed.supports.ideal_clamp && !mixed.supports.pinned_end[0] && mixed.supports.pinned_end[1]);
  EXPECT_THROW(read_scene(scene_dir + "mueller2023.prm", {"Supports/Rotational stiffness=0"}), InputError);
}

TEST(SceneFiles, AllScenesParse)
{
  EXPECT_TRUE(read_scene(scene_dir + "mueller2023-ideal.prm").supports.ideal_clamp);
  const Scene s1 = read_scene(scene_dir + "system1.prm");
  EXPECT_TRUE(s1.supports.ideal_clamp);
  // Reconstruction target: slider/beam mass ratio about 2.66.
  EXPECT_NEAR(s1.slider.mass / (s1.beam.mass_per_length() * s1.beam.length), 2.66, 0.05);
  // Its unknowns are identified, never measured, and the file says so; the
  // identified J_C is that of a block of the slider's mass with a 15-25 mm
  // edge, m (a^2 + a^2)/12.
  std::ifstream file(scene_dir + "system1.prm");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("IDENTIFIED"), std::string::npos);
  EXPECT_EQ(text.find("measured value"), std::string::npos);
  const double edge = std::sqrt(6. * s1.slider.inertia / s1.slider.mass);
  EXPECT_GT(edge, 0.015);
  EXPECT_LT(edge, 0.025);
}

TEST(SceneFiles, OverrideChangesAValue)
{
  const Scene s = read_scene(scene_dir + "mueller2023.prm", {"Excitation/Frequency=126"});
  EXPECT_DOUBLE_EQ(s.excitation.frequency_hz, 126.);
}

// A run writes its scene with scene_file_text (parameters.prm in every
// output folder); reading that text back must give the same scene bit for
// bit, for every support type and values that do not print short in decimal.
TEST(SceneFiles, WrittenSceneReadsBackBitForBit)
{
  const std::string file = ::testing::TempDir() + "written_scene.prm";
  for (const std::string type : {"elastic", "clamped", "pinned", "clamped-pinned"})
    {
      Scene s                          = read_scene(scene_dir + "mueller2023.prm", {"Supports/Type=" + type});
      s.beam.thickness                 = 1e-3 / 3.;             // 0.000333…: 17 digits to read back
      s.excitation.frequency_hz        = 0.1 + 0.2 + 123.;      // not 123.3 in binary
      s.contact.friction_coefficient   = std::nextafter(0.2, 1.);
      s.discretisation.geometric_nonlinearity = false;
      s.contact.solver                 = "exact-local";
      s.supports.rotational_stiffness  = 0.;
      if (type == "elastic")
        s.supports.rotational_stiffness = 125.;
      std::ofstream(file) << scene_file_text(s);
      const Scene r = read_scene(file);
      EXPECT_EQ(r.supports.type(), type);
      EXPECT_EQ(r.beam.thickness, s.beam.thickness) << type;
      EXPECT_EQ(r.excitation.frequency_hz, s.excitation.frequency_hz);
      EXPECT_EQ(r.contact.friction_coefficient, s.contact.friction_coefficient);
      EXPECT_FALSE(r.discretisation.geometric_nonlinearity);
      EXPECT_EQ(r.contact.solver, "exact-local");
      EXPECT_EQ(scene_file_text(r), scene_file_text(s)) << "every other parameter";
    }
  std::remove(file.c_str());
}

// The built-in defaults (scene.h, the template's values) and the default
// scene file describe the same rig: one is not allowed to drift from the
// other unnoticed.
TEST(SceneFiles, BuiltInDefaultsAreTheDefaultSceneFile)
{
  EXPECT_EQ(scene_file_text(Scene()), scene_file_text(read_scene(scene_dir + "mueller2023.prm")));
}

TEST(SceneErrors, NegativeThicknessNamesTheParameter)
{
  const std::string m = error_for("Beam/Thickness=-1e-3");
  expect_contains(m, "Beam/Thickness");
  expect_contains(m, "-1e-3");
}

TEST(SceneErrors, ZeroThicknessIsRejected)
{
  const std::string m = error_for("Beam/Thickness=0");
  expect_contains(m, "Beam/Thickness");
  expect_contains(m, "> 0");
}

TEST(SceneErrors, WindowNotTallerThanBeam)
{
  const std::string m = error_for("Slider/Window height ratio=1.0");
  expect_contains(m, "Slider/Window height ratio");
  expect_contains(m, "must be > 1");
}

TEST(SceneErrors, SliderWiderThanBeam)
{
  const std::string m = error_for("Slider/Window width=0.2");
  expect_contains(m, "Slider/Window width");
  expect_contains(m, "0.2");
  expect_contains(m, "narrower than the beam");
}

TEST(SceneErrors, SliderOutsideTheBeam)
{
  // The pattern [0,1] admits 0.01, but the window (B/2 = 5 mm) would overhang.
  const std::string m = error_for("Initial state/Slider position=0.01");
  expect_contains(m, "Initial state/Slider position");
  expect_contains(m, "0.01");
  expect_contains(m, "must lie in [");
  const std::string m2 = error_for("Initial state/Slider position=1.5");
  expect_contains(m2, "Initial state/Slider position");
  expect_contains(m2, "1.5");
}

TEST(SceneErrors, NegativeDamping)
{
  const std::string m = error_for("Damping/Modal damping ratio=-0.01");
  expect_contains(m, "Damping/Modal damping ratio");
  expect_contains(m, "-0.01");
}

TEST(SceneErrors, UnknownParameterIsAnError)
{
  expect_contains(error_for("Beam/Thicknes=1e-3"), "unknown parameter 'Beam/Thicknes'");
}

TEST(SceneErrors, UnknownParameterInAFileIsAnError)
{
  expect_contains(error_for_file("bad_scene.prm", "subsection Beam\n  set Lenght = 0.1\nend\n"), "Lenght");
}

// deal.II takes a keyword in upper case too ("SET"); so does the check for
// a parameter set twice, and a mixed-case "Set" is no keyword at all.
TEST(SceneErrors, KeywordsInUpperCaseAreKeywordsToo)
{
  expect_contains(error_for_file("upper_scene.prm", "SUBSECTION Slider\n  set Mass = 0.05\n  SET Mass = 0.06\nEND\n"),
                  "line 3: 'Slider/Mass' is set a second time (first on line 2)");
  expect_contains(error_for_file("mixed_scene.prm", "subsection Slider\n  Set Mass = 0.05\nend\n"),
                  "line 2 is not a scene line");
}

// Each file of an include chain stands on its own: it closes the
// subsections it opens and does not end in a continued line (which would
// join a line of the file after it), and the chain is at most 16 deep.
TEST(SceneErrors, EachIncludedFileStandsOnItsOwn)
{
  const std::string dir = ::testing::TempDir();
  const auto write = [&dir](const std::string &name, const std::string &text) { std::ofstream(dir + name) << text; };
  const auto error = [&dir](const std::string &name) {
    try
      {
        read_scene(dir + name);
      }
    catch (const InputError &e)
      {
        return std::string(e.what());
      }
    return std::string();
  };
  write("open_part.prm", "subsection Slider\n  set Mass = 0.05\n");
  write("open_scene.prm", "include open_part.prm\nend\n");
  expect_contains(error("open_scene.prm"), "open_part.prm' (included by '");
  expect_contains(error("open_scene.prm"), "1 'subsection' without its 'end'");

  write("continued_part.prm", "subsection Slider\n  set Mass = 0.05\nend\nset x = \\\n");
  write("continued_scene.prm", "include continued_part.prm\n");
  expect_contains(error("continued_scene.prm"), "continued_part.prm', line 4 (included by '");

  for (int i = 0; i < 20; ++i)
    write("chain_" + std::to_string(i) + ".prm", "include chain_" + std::to_string(i + 1) + ".prm\n");
  expect_contains(error("chain_0.prm"), "chain_16.prm', line 1 (included by '");
  expect_contains(error("chain_0.prm"), "includes nest deeper than 16 files");
  for (int i = 0; i < 20; ++i)
    std::remove((dir + "chain_" + std::to_string(i) + ".prm").c_str());

  // deal.II's own errors (an unknown subsection, an unknown parameter) are
  // counted in the expanded text; they name the file and line the text
  // came from: here line 5 of the including file, after the lines of the
  // scene and the part it includes; and line 2 of the included part.
  write("after_part.prm", "subsection Slider\nend\n");
  write("after_scene.prm", std::string("include ") + BEAMSLIDER_SOURCE_DIR +
                             "/meshes/mueller2023.prm\ninclude after_part.prm\n\n\nsubsection Nonsense\nend\n");
  expect_contains(error("after_scene.prm"),
                  "after_scene.prm', line 5: There is no such subsection to be entered: Nonsense");
  write("unknown_part.prm", "subsection Slider\n  set Mas = 0.05\nend\n");
  write("unknown_scene.prm", "include unknown_part.prm\n");
  expect_contains(error("unknown_scene.prm"), "unknown_part.prm', line 2: No entry with name <Mas>");
  for (const char *name : {"open_part.prm", "open_scene.prm", "continued_part.prm", "continued_scene.prm",
                           "after_part.prm", "after_scene.prm", "unknown_part.prm", "unknown_scene.prm"})
    std::remove((dir + name).c_str());
}

TEST(SceneErrors, MissingFile)
{
  std::string m;
  try
    {
      read_scene(scene_dir + "no-such-scene.prm");
    }
  catch (const InputError &e)
    {
      m = e.what();
    }
  expect_contains(m, "no-such-scene.prm");
  expect_contains(m, "does not exist");
}

// Found by tests/test_cli_fuzz.cc: a value below the smallest normal double
// (2.2e-308) passes deal.II's Double pattern, but deal.II's conversion to a
// double refuses it with its own exception (the program exited 1 with a
// deal.II banner). It is an input error like any other.
TEST(SceneErrors, UnderflowingValueIsAnInputErrorNamingTheParameter)
{
  for (const std::string value : {"1e-320", "4.9e-324", "1e-400"})
    {
      const std::string m = error_for("Contact/Restitution=" + value);
      expect_contains(m, "'Contact/Restitution' = '" + value + "'");
      expect_contains(m, "smallest normal double");
    }
  // The same from a file: the value reaches the scene through the entry's
  // action inside ParameterHandler::parse_input, whose failure must still
  // arrive as this InputError, not as a deal.II exception.
  const std::string m =
    error_for_file("underflow_scene.prm", "subsection Contact\n  set Restitution = 1e-320\nend\n");
  expect_contains(m, "'Contact/Restitution' = '1e-320'");
  expect_contains(m, "smallest normal double");
}

// Found by tests/test_cli_fuzz.cc: when the base displacement amplitude
// a/Omega^2 overflows (then at 1e-182 Hz; within the frequency range at the
// largest accelerations), the slider starts at z = inf and trace.csv
// received a row with "inf".
TEST(SceneErrors, BaseDisplacementThatOverflowsIsRefused)
{
  const std::string m = error_for("Excitation/Acceleration amplitude=1e308", "mueller2023.prm", "Excitation/Frequency=0.1");
  expect_contains(m, "'Excitation/Frequency' = 0.1");
  expect_contains(m, "base displacement amplitude");
}

// Found by tests/test_cli_fuzz.cc: a thickness whose cube underflows gave the
// beam no bending stiffness (PETSc "zero pivot" dump from the eigensolver,
// exit 1), a width near the largest double an infinite one.
TEST(SceneErrors, SectionPropertiesOutsideTheNormalDoublesAreRefused)
{
  std::string m = error_for("Beam/Thickness=3.1340791372151129e-286");
  // Values in messages are written exactly (the shortest text of the same double).
  expect_contains(m, "'Beam/Thickness' = 3.134079137215113e-286");
  expect_contains(m, "bending stiffness EI");
  m = error_for("Beam/Width=1e308");
  expect_contains(m, "'Beam/Width' = 1e+308");
  expect_contains(m, "stiffness EI = E b h^3/12 = inf");
}

TEST(SceneErrors, FETimeStepMustBePositiveAndResolveTheExcitation)
{
  std::string m = error_for("Time stepping/FE time step=-1e-6");
  expect_contains(m, "Time stepping/FE time step");
  expect_contains(m, "-1e-6");
  m = error_for("Time stepping/FE time step=0");
  expect_contains(m, "Time stepping/FE time step");
  expect_contains(m, "> 0");
  // 124 Hz: a twentieth of the period is 4.03e-4 s.
  m = error_for("Time stepping/FE time step=1e-3");
  expect_contains(m, "Time stepping/FE time step");
  expect_contains(m, "a twentieth of the excitation period");
}

TEST(SceneErrors, FEThetaMustLieBetweenTheMidpointRuleAndImplicitEuler)
{
  for (const std::string value : {"0.4", "1.5", "-1"})
    {
      const std::string m = error_for("Time stepping/FE theta=" + value);
      expect_contains(m, "Time stepping/FE theta");
      expect_contains(m, value);
    }
  EXPECT_EQ(read_scene(scene_dir + "mueller2023.prm", {"Time stepping/FE theta=0.51"}).time_stepping.fe_theta, 0.51);
}

TEST(SceneErrors, CompliantCornersNeedAStiffnessAtLeastZeroAndARestitutionTheirDashpotReaches)
{
  expect_contains(error_for("Contact/Normal stiffness=-1"), "Contact/Normal stiffness");
  EXPECT_EQ(error_for("Contact/Normal stiffness=1e7"), "");
  // A dashpot that only pushes returns at least 13.5 % up to critical damping.
  const std::string message = error_for("Contact/Normal stiffness=1e7", "mueller2023.prm", "Contact/Restitution=0.1");
  expect_contains(message, "Contact/Restitution");
  expect_contains(message, "0.135");
  EXPECT_EQ(error_for("Contact/Restitution=0.1"), ""); // rigid corners take any e_N in [0, 1]
}
