// The layers look down only: every #include "folder/..." of the project's
// sources names a layer at or below the including file's. The order is
// doc/architecture.md's:
//   numerics (Newton, a state's bytes, the stop request), io (files),
//   scene (the Scene and its files) ← contact (the contact step) ← reduced ← fem
//   ← output (the FE model's files), runs (runs and traces), runtime
//   (child processes, MPI ranks, threads, the build) ← verification/studies ← verification/report ← the front ends:
//   verification/cli, python and verification/benchmarks.
// The models (contact/, reduced/, fem/) do not include io/: they write no
// file; what they save for a checkpoint goes through numerics/state_bytes.h.
// Nor do the studies (verification/studies/): a study returns its results
// and hands rows and progress to its caller's callbacks; report/ and cli/
// write the files and the console.
// A study or a report section that needs something of the command line
// (running a case as `simulate` does) takes it as a function argument
// (simulation_cases.h: CaseRunner), never by including cli/.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
  // Layer folders and their rank, lowest first; a front end is rank 7.
  const int studies_rank = 5;
  const std::vector<std::pair<std::string, int>> layers = {
    {"numerics", 0}, {"io", 0}, {"scene", 0}, {"contact", 1}, {"reduced", 2}, {"fem", 3}, {"output", 4},
    {"runs", 4}, {"runtime", 4}, {"verification/studies", studies_rank}, {"verification/report", 6}, {"verification/cli", 7},
    {"python", 7}, {"verification/benchmarks", 7}};

  bool is_model(const std::string &path)
  {
    for (const std::string folder : {"contact/", "reduced/", "fem/"})
      if (path.rfind(folder, 0) == 0)
        return true;
    return false;
  }

  // The rank of a path relative to the source tree (-1: not a layer).
  int rank_of(const std::string &path)
  {
    int rank = -1;
    std::size_t matched = 0;
    for (const auto &[folder, r] : layers)
      if (path.rfind(folder + "/", 0) == 0 && folder.size() > matched)
        {
          rank    = r;
          matched = folder.size();
        }
    return rank;
  }

  struct Include
  {
    std::string file; // relative to the source tree
    int line;
    std::string target;
  };

  std::vector<Include> project_includes()
  {
    const fs::path root = BEAMSLIDER_SOURCE_DIR;
    const std::regex include_line(R"re(^\s*#\s*include\s*"([^"]+)")re");
    std::vector<Include> found;
    for (const auto &[folder, rank] : layers)
      for (const auto &entry : fs::recursive_directory_iterator(root / folder))
        {
          const std::string ext = entry.path().extension().string();
          if (!entry.is_regular_file() || (ext != ".h" && ext != ".cc"))
            continue;
          const std::string file = fs::relative(entry.path(), root).generic_string();
          if (rank_of(file) != rank) // a sub-folder that is a layer of its own
            continue;
          std::ifstream in(entry.path());
          std::string text;
          std::smatch m;
          for (int line = 1; std::getline(in, text); ++line)
            if (std::regex_search(text, m, include_line))
              {
                // A relative include ("../cli/commands.h") is ranked by the
                // file it reaches, as one from the source tree is.
                std::string target = m[1];
                const fs::path beside = entry.path().parent_path() / target;
                if (!fs::exists(root / target) && fs::exists(beside))
                  target = fs::relative(fs::weakly_canonical(beside), fs::weakly_canonical(root)).generic_string();
                found.push_back({file, line, target});
              }
        }
    return found;
  }
} // namespace

TEST(Architecture, EveryIncludeLooksDown)
{
  const std::vector<Include> includes = project_includes();
  // The scan must see the code: the project has several hundred includes
  // between its folders, and cli/ includes studies/.
  std::size_t between_layers = 0;
  bool cli_includes_studies  = false;
  std::size_t model_includes = 0;
  for (const Include &i : includes)
    {
      const int from = rank_of(i.file), to = rank_of(i.target);
      if (to < 0)
        continue; // a header beside the file, or a system one
      between_layers += from != to;
      cli_includes_studies = cli_includes_studies || (i.file.rfind("verification/cli/", 0) == 0 && to == studies_rank);
      EXPECT_LE(to, from) << i.file << ":" << i.line << " includes \"" << i.target
                          << "\", a layer above its own (doc/architecture.md)";
      // io/input_file.h, the one guarded way to read a file, is open to
      // every layer: it reads, it writes nothing.
      const bool writes = i.target.rfind("io/", 0) == 0 && i.target != "io/input_file.h";
      if (i.file.rfind("verification/studies/", 0) == 0)
        EXPECT_FALSE(writes)
          << i.file << ":" << i.line << " includes \"" << i.target << "\": a study writes and prints nothing";
      if (is_model(i.file))
        {
          ++model_includes;
          EXPECT_FALSE(writes) << i.file << ":" << i.line << " includes \"" << i.target
                               << "\": a model writes no file";
        }
    }
  EXPECT_GT(model_includes, 100u);
  EXPECT_GT(between_layers, 200u);
  EXPECT_TRUE(cli_includes_studies);
}

namespace
{
  // The project's libraries and their layer's rank (as `layers` above); the
  // Python module (beamslider_python) and the executables are front ends.
  const std::map<std::string, int> library_ranks = {
    {"beamslider_numerics", 0}, {"beamslider_io", 0},     {"beamslider_scene", 0},      {"beamslider_contact", 1},
    {"beamslider_reduced", 2},  {"beamslider_fem", 3},    {"beamslider_output", 4}, {"beamslider_runs", 4},
    {"beamslider_runtime", 4},  {"beamslider_studies", 5},  {"beamslider_report", 6}, {"beamslider_cli", 7}};

  // "A links B" for every target_link_libraries(A ... B ...) of a library
  // in `cmake` (the text of CMakeLists.txt files) whose B ranks above A.
  std::vector<std::string> upward_links(const std::string &cmake)
  {
    const std::regex link_call(R"re(target_link_libraries\s*\(\s*([A-Za-z0-9_]+)([^)]*)\))re");
    const std::regex word(R"re([A-Za-z0-9_]+)re");
    std::vector<std::string> upward;
    for (std::sregex_iterator m(cmake.begin(), cmake.end(), link_call), end; m != end; ++m)
      {
        const auto from = library_ranks.find((*m)[1]);
        if (from == library_ranks.end())
          continue;
        const std::string linked = (*m)[2];
        for (std::sregex_iterator w(linked.begin(), linked.end(), word); w != end; ++w)
          if (const auto to = library_ranks.find(w->str()); to != library_ranks.end() && to->second > from->second)
            upward.push_back(from->first + " links " + to->first);
      }
    return upward;
  }

  std::string cmake_files_text()
  {
    std::string text;
    for (const auto &entry : fs::recursive_directory_iterator(BEAMSLIDER_SOURCE_DIR))
      if (entry.is_regular_file() && entry.path().filename() == "CMakeLists.txt" &&
          entry.path().string().find("/build") == std::string::npos)
        {
          std::ifstream in(entry.path());
          text += std::string(std::istreambuf_iterator<char>(in), {}) + "\n";
        }
    return text;
  }
} // namespace

// The libraries are the layers: none links one above it (a study cannot
// reach the report or the command line even through the linker). The check
// sees the tree's links, and it fails on a planted upward link.
TEST(Architecture, EveryLibraryLinksOnlyTheLayersBelowIt)
{
  const std::string cmake = cmake_files_text();
  for (const auto &[library, rank] : library_ranks)
    EXPECT_NE(cmake.find("add_library(" + library + " "), std::string::npos) << library << " is not a library";
  EXPECT_NE(cmake.find("target_link_libraries(beamslider_cli beamslider_report"), std::string::npos);
  for (const std::string &link : upward_links(cmake))
    ADD_FAILURE() << link << ", a layer above its own (doc/architecture.md)";
  const std::vector<std::string> planted =
    upward_links(cmake + "\ntarget_link_libraries(beamslider_studies\n  beamslider_fem beamslider_cli)\n");
  ASSERT_EQ(planted.size(), 1u);
  EXPECT_EQ(planted.front(), "beamslider_studies links beamslider_cli");
}

// The folders of the source tree are the folders doc/architecture.md's
// table names (§2, a row "| `folder/` |" each), no more and no fewer: the
// layout a reader learns there is the tree's. Build folders (build*,
// ignored by git) and hidden ones are not the project's layout.
TEST(Architecture, TheTopLevelFoldersAreTheOnesTheArchitectureNames)
{
  const fs::path root = BEAMSLIDER_SOURCE_DIR;
  std::set<std::string> named, present;
  std::ifstream in(root / "doc" / "architecture.md");
  const std::regex row(R"re(^\| `([a-z_]+)/` \|)re");
  for (std::string line; std::getline(in, line);)
    if (std::smatch m; std::regex_search(line, m, row))
      named.insert(m[1]);
  for (const auto &entry : fs::directory_iterator(root))
    {
      const std::string name = entry.path().filename().string();
      if (entry.is_directory() && name[0] != '.' && name.rfind("build", 0) != 0)
        present.insert(name);
    }
  EXPECT_GE(named.size(), 10u); // the table was found
  EXPECT_EQ(named, present);
}

// README.md and doc/ name only files and folders that exist: a path of the
// project's folders in the text (`fem/fe_modes.h`, `scripts/setup.sh`) is
// there; one without an extension names a module (its .h or .cc is there).
// Left out: generated report folders other than the published one, globs
// and placeholders (`tests/test_*.cc`, `command_<name>.cc`), and the scene a
// step of doc/architecture.md §4 creates.
TEST(Architecture, TheDocsNameOnlyPathsThatExist)
{
  const fs::path root = BEAMSLIDER_SOURCE_DIR;
  const std::regex path_in_text(
    R"re((^|[^A-Za-z0-9_/.-])((numerics|io|runs|runtime|contact|reduced|fem|output|scene|meshes|verification|tests|scripts|python|doc|reports)/[A-Za-z0-9_./-]*[A-Za-z0-9_])([*<]?))re");
  std::vector<fs::path> docs = {root / "README.md"};
  for (const auto &entry : fs::directory_iterator(root / "doc"))
    if (entry.path().extension() == ".md")
      docs.push_back(entry.path());
  std::size_t checked = 0;
  for (const fs::path &doc : docs)
    {
      std::ifstream in(doc);
      std::string text;
      for (int line = 1; std::getline(in, text); ++line)
        for (std::sregex_iterator m(text.begin(), text.end(), path_in_text), end; m != end; ++m)
          {
            const std::string path = (*m)[2];
            if (!(*m)[4].str().empty() || path == "meshes/myscene.prm" ||
                (path.rfind("reports/", 0) == 0 && path.rfind("reports/mueller2023-full", 0) != 0))
              continue;
            ++checked;
            const bool exists = fs::exists(root / path) || fs::exists(root / (path + ".h")) ||
                                fs::exists(root / (path + ".cc"));
            EXPECT_TRUE(exists) << fs::relative(doc, root).string() << ":" << line << " names " << path
                                << ", which does not exist";
          }
    }
  EXPECT_GT(checked, 100u); // the docs name many files: the scan sees them
}
