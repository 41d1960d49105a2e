// Bounded fuzzing of the two ways a user gives a scene: a scene file and
// `--set Section/Name=value`. Deterministic (std::mt19937, fixed seeds), so a
// failure is reproduced by running the test again.
//
// The contract under test (scene/scene.h): read_scene either returns a scene
// that satisfies validate_scene, or throws InputError with a message; never
// another exception, never a crash or a hang. Thousands of mutated inputs go
// through the reader in this process (a start of the program costs ~1 s, the
// reader ~1 ms). A bounded sample then goes through the built program
// (`simulate SCENE --end-time 0.01`), which must end by itself (no signal,
// no sanitizer report, within the time limit) with the exit status predicted
// for it in this process, and write no NaN or infinity into a CSV file. The
// prediction: 2 for a scene the reader refuses; for one it accepts, 2 if the
// command's checks before the run refuse it (the model cannot be built from
// it, or its time step lies above the model's stability limit), else the
// same short run through the library: 0 if it completes or the slider
// reaches a support, 1 if it fails.
#include "runs/adaptation_run.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "tests/cli_runner.h"
#include "verification/cli/commands.h"
#include "verification/studies/fe_rom_study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <random>
#include <set>
#include <thread>

namespace fs = std::filesystem;
using namespace beamslider;
using namespace beamslider::testing;

namespace
{
  const std::string source_scene = std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/mueller2023.prm";

  // Values a hand, a script or a broken editor may put where a number
  // belongs: the edges of double, non-finite spellings, overflowing
  // exponents and integers, empty text, non-numbers and bytes that are not
  // text.
  const std::vector<std::string> hostile_values = {
    "0", "-0", "-1", "1", "0.5", "2", "1e308", "-1e308", "1.8e308", "1e309", "-1e309", "1e-308", "4.9e-324",
    "1e-400", "1e99999", "-1e99999", "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "", " ", "\t", "1e", "e5", ".",
    "1.2.3", "0x1p4", "--1", "+", "1,5", "99999999999999999999", "4294967297", "-2147483649", "true", "false",
    "clamped", "elastic", "=", "1 2", "1e+308e2", std::string("1\0" "2", 3), "\x01\x7f\xff", "\xc3\xa9", "#",
    std::string(400, '9')};

  std::string join_lines(const std::vector<std::string> &lines)
  {
    std::string text;
    for (const auto &l : lines)
      text += l + "\n";
    return text;
  }

  // A number of any magnitude and sign, log-uniform over the whole range of
  // double (including subnormals and values that overflow when printed back).
  std::string random_number(std::mt19937 &rng)
  {
    std::uniform_real_distribution<double> exponent(-330., 330.);
    std::ostringstream s;
    s.precision(17);
    s << (rng() % 4 == 0 ? "-" : "") << std::pow(10., exponent(rng));
    return s.str();
  }

  std::string random_bytes(std::mt19937 &rng, const unsigned int n)
  {
    std::string b;
    for (unsigned int i = 0; i < n; ++i)
      b += static_cast<char>(rng() % 256);
    return b;
  }

  // The index of a random line that starts with `set` (after blanks).
  std::size_t random_set_line(const std::vector<std::string> &lines, std::mt19937 &rng)
  {
    std::vector<std::size_t> set_lines;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].find("set ") != std::string::npos)
        set_lines.push_back(i);
    if (set_lines.empty())
      return rng() % std::max<std::size_t>(lines.size(), 1);
    return set_lines[rng() % set_lines.size()];
  }

  struct SceneCase
  {
    std::string text;
    std::string mutations; // what was done, for messages
    bool mangled_value = false;
  };

  // One mutated scene file: 1 to 3 edits of the published scene, and now and
  // then a cut at a random byte.
  SceneCase mutate_scene(const std::vector<std::string> &original, std::mt19937 &rng)
  {
    SceneCase c;
    std::vector<std::string> lines = original;
    const unsigned int n_edits     = 1 + rng() % 3;
    for (unsigned int e = 0; e < n_edits && !lines.empty(); ++e)
      {
        const std::size_t i = rng() % lines.size();
        switch (rng() % 8)
          {
            case 0:
              c.mutations += "drop line " + std::to_string(i) + "; ";
              lines.erase(lines.begin() + i);
              break;
            case 1:
              c.mutations += "duplicate line " + std::to_string(i) + "; ";
              lines.insert(lines.begin() + i, lines[i]);
              break;
            case 2:
              {
                const std::size_t j = rng() % lines.size();
                c.mutations += "swap lines " + std::to_string(i) + ", " + std::to_string(j) + "; ";
                std::swap(lines[i], lines[j]);
                break;
              }
            case 3:
            case 4:
              {
                // A value replaced: a hostile spelling or a number of any size.
                const std::size_t k = random_set_line(lines, rng);
                const auto eq       = lines[k].find('=');
                if (eq == std::string::npos)
                  break;
                const std::string value =
                  rng() % 2 ? hostile_values[rng() % hostile_values.size()] : random_number(rng);
                c.mutations += "line " + std::to_string(k) + " value '" + value + "'; ";
                lines[k]        = lines[k].substr(0, eq + 1) + " " + value;
                c.mangled_value = true;
                break;
              }
            case 5:
              {
                const std::string bytes = random_bytes(rng, 1 + rng() % 8);
                const std::size_t at    = rng() % (lines[i].size() + 1);
                c.mutations += "garbage bytes into line " + std::to_string(i) + "; ";
                lines[i].insert(at, bytes);
                break;
              }
            case 6:
              {
                // An unknown name: a parameter or a section misspelt.
                const std::size_t k = rng() % 2 ? random_set_line(lines, rng) : i;
                const auto at       = std::min(lines[k].size(), lines[k].find_first_not_of(" ") + 4 + rng() % 8);
                c.mutations += "misspell line " + std::to_string(k) + "; ";
                lines[k].insert(at, std::string(1, static_cast<char>('a' + rng() % 26)));
                break;
              }
            case 7:
              {
                // The syntax itself: keywords and the '=' of a line.
                const std::vector<std::pair<std::string, std::string>> edits = {
                  {"set ", "sett "}, {"set ", ""}, {"=", ""}, {"=", "=="}, {"end", "ends"},
                  {"end", ""}, {"subsection ", "subsection"}, {"subsection ", "set "}};
                const auto &[from, to] = edits[rng() % edits.size()];
                if (const auto at = lines[i].find(from); at != std::string::npos)
                  {
                    c.mutations += "'" + from + "' -> '" + to + "' in line " + std::to_string(i) + "; ";
                    lines[i].replace(at, from.size(), to);
                  }
                break;
              }
          }
      }
    c.text = join_lines(lines);
    if (rng() % 10 == 0)
      {
        const std::size_t cut = rng() % (c.text.size() + 1);
        c.mutations += "cut at byte " + std::to_string(cut) + "; ";
        c.text.resize(cut);
      }
    return c;
  }

  std::vector<SceneCase> scene_cases(const unsigned int n)
  {
    const std::vector<std::string> original = split_lines(read_file(source_scene));
    std::mt19937 rng(20260923);
    std::vector<SceneCase> cases;
    for (unsigned int k = 0; k < n; ++k)
      cases.push_back(mutate_scene(original, rng));
    return cases;
  }

  // Every parameter of the scene template, as "Section/Sub/Name".
  std::vector<std::string> template_parameters()
  {
    std::vector<std::string> names, sections;
    for (const auto &raw : split_lines(scene_template()))
      {
        const auto b = raw.find_first_not_of(" \t");
        if (b == std::string::npos || raw[b] == '#')
          continue;
        const std::string line = raw.substr(b);
        if (line.rfind("subsection ", 0) == 0)
          sections.push_back(line.substr(11));
        else if (line == "end")
          sections.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            std::string name = line.substr(4, line.find('=') - 4);
            name.erase(name.find_last_not_of(' ') + 1);
            std::string path;
            for (const auto &s : sections)
              path += s + "/";
            names.push_back(path + name);
          }
      }
    return names;
  }

  // --set lists: every parameter with every hostile value, with random
  // numbers, two at once, and assignments that are malformed as such.
  std::vector<std::vector<std::string>> override_cases()
  {
    const std::vector<std::string> parameters = template_parameters();
    std::mt19937 rng(4711);
    std::vector<std::vector<std::string>> cases;
    for (const auto &p : parameters)
      {
        for (const auto &v : hostile_values)
          cases.push_back({p + "=" + v});
        for (unsigned int k = 0; k < 30; ++k)
          cases.push_back({p + "=" + random_number(rng)});
      }
    for (unsigned int k = 0; k < 300; ++k)
      {
        const std::string a = parameters[rng() % parameters.size()], b = parameters[rng() % parameters.size()];
        cases.push_back({a + "=" + random_number(rng), b + "=" + hostile_values[rng() % hostile_values.size()]});
      }
    for (const char *bad :
         {"", "=", "Beam", "Beam/", "/Length=0.1", "Beam//Length=0.1", "Beam/Length", "Beam/Length==0.1",
          "Beam/Length =0.1", " Beam/Length=0.1", "beam/length=0.1", "Beam/Length/=0.1", "Nowhere/Length=0.1",
          "Beam/Nothing=1", "Beam/Sub/Length=0.1", "Time stepping=1", "Slider/Mass=0.1=0.2", "/=", "//=",
          "Beam/Length=0.1\nset Width = 1"})
      cases.push_back({std::string(bad)});
    return cases;
  }

  enum class Outcome
  {
    accepted,
    refused,
    wrong_exception
  };

  // The reader's contract for one input; `what` receives the message of a
  // refusal or of a wrong exception.
  Outcome read(const std::string &file, const std::vector<std::string> &overrides, std::string &what, Scene *scene = nullptr)
  {
    try
      {
        const Scene s = read_scene(file, overrides);
        try
          {
            validate_scene(s);
          }
        catch (const std::exception &e)
          {
            what = std::string("read_scene returned a scene that validate_scene refuses: ") + e.what();
            return Outcome::wrong_exception;
          }
        if (scene)
          *scene = s;
        return Outcome::accepted;
      }
    catch (const InputError &e)
      {
        what = e.what();
        if (what.empty())
          {
            what = "InputError without a message";
            return Outcome::wrong_exception;
          }
        return Outcome::refused;
      }
    catch (const std::exception &e)
      {
        what = std::string("exception other than InputError: ") + e.what();
        return Outcome::wrong_exception;
      }
    catch (...)
      {
        what = "exception of unknown type";
        return Outcome::wrong_exception;
      }
  }

  // The file a case is written to; after a crash it holds the input that
  // caused it.
  fs::path case_file(const std::string &folder)
  {
    return fs::temp_directory_path() / ("beamslider_fuzz_" + folder + "_" + std::to_string(getpid())) / "case.prm";
  }

  void write(const fs::path &file, const std::string &text)
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
  }

  // Data rows of every CSV file in a folder that hold a non-finite number.
  std::string non_finite_rows(const fs::path &dir)
  {
    std::string found;
    if (!fs::is_directory(dir))
      return found;
    for (const auto &entry : fs::directory_iterator(dir))
      {
        if (entry.path().extension() != ".csv")
          continue;
        std::istringstream in(read_file(entry.path()));
        std::string line;
        std::getline(in, line); // the header names columns
        while (std::getline(in, line))
          {
            std::string lower = line;
            std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
            if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos)
              {
                found += entry.path().filename().string() + ": " + line + "\n";
                break;
              }
          }
      }
    return found;
  }

  // The run of the fuzzed program cases.
  constexpr double program_end_time = 0.01; // [s]

  // The exit status of `simulate` on a scene the reader accepted, predicted
  // by what the command does before and during the run (command_simulate.cc),
  // done here through the library: InputError and std::invalid_argument are
  // the program's exit 2, any other error and a failed run its exit 1.
  int predicted_exit(Scene scene, std::string &why)
  {
    try
      {
        scene.time_stepping.end_time = program_end_time;
        validate_scene(scene); // the step count at the new end time
        if (program_end_time * scene.time_stepping.output_rate > SimulateOptions::max_trace_rows)
          {
            why = "more trace rows than allowed";
            return 2;
          }
        const ModelSetting setting    = scene_model(scene, "rom");
        scene.time_stepping.time_step = setting.time_step;
        const std::unique_ptr<BeamSystem> beam = make_beam_model(scene, setting);
        if (!(scene.time_stepping.time_step <= beam->max_stable_time_step()))
          {
            why = "time step above the stability limit " + std::to_string(beam->max_stable_time_step()) + " s";
            return 2;
          }
        AdaptationRun run(scene, *beam, RunOptions::from_scene(scene));
        const RunResult result = run.run();
        why                    = "the run: " + to_string(result.status) + " " + result.message;
        return result.status == RunStatus::completed || result.status == RunStatus::slider_at_support ? 0 : 1;
      }
    catch (const InputError &e)
      {
        why = e.what();
        return 2;
      }
    catch (const std::invalid_argument &e)
      {
        why = e.what();
        return 2;
      }
    catch (const std::exception &e)
      {
        why = e.what();
        return 1;
      }
  }

  // The built program on one input; the checks every run must pass.
  struct ProgramCase
  {
    std::string description;
    std::vector<std::string> args;
    fs::path output;
    int expected_exit = 0;
    std::string why; // of the prediction
  };

  void check_program_run(const ProgramCase &c, const CliRun &run)
  {
    SCOPED_TRACE(c.description);
    EXPECT_FALSE(run.timed_out) << "hangs";
    EXPECT_EQ(run.signal, 0) << "killed by signal " << run.signal << "\n" << run.err;
    EXPECT_EQ(run.exit_code, c.expected_exit) << "predicted from " << c.why << "\n" << run.err;
    EXPECT_EQ(run.err.find("Sanitizer"), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("runtime error:"), std::string::npos) << run.err;
    // Not a deal.II exception banner with its stack trace.
    EXPECT_EQ(run.err.find("Stacktrace"), std::string::npos) << run.err;
    if (run.exit_code == 2)
      {
        EXPECT_FALSE(run.err.empty()) << "an input error without a message";
      }
    EXPECT_EQ(non_finite_rows(c.output), "");
  }

  // Runs the cases, three programs at a time (each spends much of its ~1 s
  // starting MPI and Python, not computing).
  void run_program_cases(const std::vector<ProgramCase> &cases)
  {
    std::vector<CliRun> runs(cases.size());
    std::atomic<std::size_t> next{0};
    CliLimits limits;
    limits.timeout_seconds = 60;
    auto worker = [&]() {
      for (std::size_t k; (k = next++) < cases.size();)
        runs[k] = run_beamslider(cases[k].args, limits);
    };
    std::vector<std::thread> workers;
    for (int t = 0; t < 3; ++t)
      workers.emplace_back(worker);
    for (auto &w : workers)
      w.join();
    for (std::size_t k = 0; k < cases.size(); ++k)
      check_program_run(cases[k], runs[k]);
  }

  // The failures of one batch, reported once each, at most 20 of them.
  struct FailureLog
  {
    unsigned int count = 0;
    void add(const std::string &input, const std::string &what)
    {
      if (++count <= 20)
        ADD_FAILURE() << what << "\ninput:\n" << input;
    }
  };
} // namespace

// Thousands of mutated scene files through the reader.
TEST(FuzzSceneFile, EveryMutationIsAValidSceneOrAnInputError)
{
  const std::vector<SceneCase> cases = scene_cases(3000);
  const fs::path file                = case_file("scene");
  fs::create_directories(file.parent_path());
  unsigned int accepted = 0, refused = 0;
  FailureLog failures;
  for (const SceneCase &c : cases)
    {
      write(file, c.text);
      std::string what;
      switch (read(file.string(), {}, what))
        {
          case Outcome::accepted:
            ++accepted;
            break;
          case Outcome::refused:
            ++refused;
            break;
          case Outcome::wrong_exception:
            failures.add(c.mutations + "\n" + c.text, what);
            break;
        }
    }
  fs::remove_all(file.parent_path());
  std::cout << cases.size() << " mutated scene files: " << accepted << " accepted, " << refused << " refused"
            << std::endl;
  EXPECT_EQ(failures.count, 0u);
  // Both outcomes occur: the mutations neither all break the file nor all
  // miss it.
  EXPECT_GT(accepted, 100u);
  EXPECT_GT(refused, 100u);
}

// Every parameter of the template with hostile and random values.
TEST(FuzzSetOption, EveryValueOfEveryParameterIsAValidSceneOrAnInputError)
{
  const auto cases = override_cases();
  // The published scene sets every parameter once: as many as the template.
  const std::string published = read_file(source_scene);
  std::size_t n_set_lines     = 0;
  for (std::size_t at = 0; (at = published.find("\n  set ", at)) != std::string::npos; ++at)
    ++n_set_lines;
  ASSERT_EQ(template_parameters().size(), n_set_lines) << "the template parser misses parameters";
  unsigned int accepted = 0, refused = 0;
  FailureLog failures;
  for (const auto &overrides : cases)
    {
      std::string what;
      switch (read(source_scene, overrides, what))
        {
          case Outcome::accepted:
            ++accepted;
            break;
          case Outcome::refused:
            ++refused;
            break;
          case Outcome::wrong_exception:
            {
              std::string input;
              for (const auto &o : overrides)
                input += "--set \"" + o + "\" ";
              failures.add(input, what);
              break;
            }
        }
    }
  std::cout << cases.size() << " --set lists: " << accepted << " accepted, " << refused << " refused" << std::endl;
  EXPECT_EQ(failures.count, 0u);
  EXPECT_GT(accepted, 100u);
  EXPECT_GT(refused, 100u);
}

// A sample of the same inputs through the built program: 20 scene files the
// reader accepted (14 with a changed value), 4 it refused, and 6 --set
// values it accepted (one per parameter, extreme ones), each with the exit
// status predicted for it (predicted_exit). Only runs of bounded
// work are sampled (at most 10^4 time steps and 1024 elements at --end-time
// 0.01): a scene that asks for a long run is slow, not hung.
TEST(FuzzProgram, SampledInputsEndWithThePredictedExitAndFiniteCsv)
{
  const fs::path dir = fresh_folder("fuzz_program");
  auto bounded       = [](const Scene &s) {
    return s.time_stepping.time_step >= 1e-6 && s.discretisation.n_elements <= 1024;
  };

  std::vector<ProgramCase> program_cases;
  unsigned int n_mangled = 0, n_other = 0, n_refused = 0;
  const fs::path probe = dir / "probe.prm";
  const auto cases     = scene_cases(3000);
  for (std::size_t k = 0; k < cases.size() && n_mangled + n_other + n_refused < 24; ++k)
    {
      write(probe, cases[k].text);
      std::string what;
      Scene scene;
      const Outcome outcome = read(probe.string(), {}, what, &scene);
      ProgramCase c;
      c.output = dir / ("out" + std::to_string(k));
      if (outcome == Outcome::accepted && bounded(scene))
        {
          if (cases[k].mangled_value ? n_mangled >= 14 : n_other >= 6)
            continue;
          ++(cases[k].mangled_value ? n_mangled : n_other);
          c.expected_exit = predicted_exit(scene, c.why);
        }
      else if (outcome == Outcome::refused && n_refused < 4)
        {
          ++n_refused;
          c.expected_exit = 2;
          c.why           = "the reader: " + what;
        }
      else
        continue;
      const fs::path scene_file = dir / ("case" + std::to_string(k) + ".prm");
      write(scene_file, cases[k].text);
      c.description = "scene case " + std::to_string(k) + " (" + cases[k].mutations + ")\n" + cases[k].text;
      c.args        = {"simulate", scene_file.string(), "--end-time", std::to_string(program_end_time), "--output",
                       c.output.string()};
      program_cases.push_back(c);
    }

  // --set values the reader accepts, the extreme ones first.
  unsigned int n_set = 0;
  std::set<std::string> parameters_run; // one value per parameter
  for (const auto &overrides : override_cases())
    {
      if (n_set >= 6 || overrides.size() != 1 || overrides[0].find('=') == std::string::npos)
        continue;
      const std::string parameter = overrides[0].substr(0, overrides[0].find('='));
      const std::string value     = overrides[0].substr(overrides[0].find('=') + 1);
      if (parameters_run.count(parameter))
        continue;
      const bool extreme      = value.find("e+") != std::string::npos || value.find("e-") != std::string::npos ||
                           value.find("e308") != std::string::npos || value == "0";
      std::string what;
      Scene scene;
      if (!extreme || read(source_scene, overrides, what, &scene) != Outcome::accepted || !bounded(scene))
        continue;
      ++n_set;
      parameters_run.insert(parameter);
      ProgramCase c;
      c.output        = dir / ("set" + std::to_string(n_set));
      c.description   = "--set \"" + overrides[0] + "\"";
      c.args          = {"simulate", source_scene, "--set", overrides[0], "--end-time", std::to_string(program_end_time),
                         "--output", c.output.string()};
      c.expected_exit = predicted_exit(scene, c.why);
      program_cases.push_back(c);
    }
  unsigned int n_predicted[3] = {0, 0, 0};
  for (const ProgramCase &c : program_cases)
    {
      ++n_predicted[c.expected_exit];
      if (c.expected_exit == 1)
        std::cout << "predicted to fail: " << one_line(c.description).substr(0, 100) << ": " << one_line(c.why)
                  << std::endl;
    }
  std::cout << program_cases.size() << " program runs: " << n_mangled << " accepted scenes with a changed value, "
            << n_other << " other accepted scenes, " << n_refused << " refused scenes, " << n_set
            << " --set values; predicted exits 0, 1, 2: " << n_predicted[0] << ", " << n_predicted[1] << ", "
            << n_predicted[2] << std::endl;
  EXPECT_EQ(n_mangled + n_other, 20u);
  EXPECT_EQ(n_refused, 4u);
  EXPECT_EQ(n_set, 6u);
  run_program_cases(program_cases);
  fs::remove_all(dir);
}
