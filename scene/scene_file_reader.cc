// The text of a scene file: a bounded regular file of scene lines, its
// `include` lines replaced by the files they name, each parameter set once.
#include "io/input_file.h"
#include "scene/printable.h"
#include "scene/scene.h"
#include "scene/scene_parameters_internal.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace beamslider
{
  namespace internal
  {
    std::string trim(const std::string &x)
    {
      const auto b = x.find_first_not_of(" \t\r");
      const auto e = x.find_last_not_of(" \t\r");
      return b == std::string::npos ? std::string() : x.substr(b, e - b + 1);
    }

    std::string SceneText::where(const unsigned int line) const
    {
      if (line == 0 || line > origins.size())
        return "Scene file";
      const Origin &o = origins[line - 1];
      return "Scene file '" + printable(o.file) + "', line " + std::to_string(o.line);
    }
  } // namespace internal

  namespace
  {
    using internal::SceneText;
    using internal::trim;

    // A scene file, and each file it includes, is a regular file of at most
    // this size: a device (/dev/zero) would be read without end, a FIFO would
    // block. The scene with its includes expanded is bounded alike (a file
    // included many times over).
    constexpr std::size_t max_scene_bytes = InputLimits::scene;
    // Includes nest at most this deep (a chain of distinct files).
    constexpr unsigned int max_include_depth = 16;

    // The first word of a scene line in lower case if deal.II takes it for
    // a keyword, which it does in lower or upper case ("set", "SET"); ""
    // for any other word ("Set").
    std::string scene_keyword(const std::string &word)
    {
      std::string lower = word, upper = word;
      std::transform(word.begin(), word.end(), lower.begin(), [](const unsigned char c) { return std::tolower(c); });
      std::transform(word.begin(), word.end(), upper.begin(), [](const unsigned char c) { return std::toupper(c); });
      return word == lower || word == upper ? lower : std::string();
    }

    // The text of one file, after checking with stat() that it is a regular
    // file of bounded size, before it is opened (a FIFO is never opened).
    // `what` names it in messages: "Scene file 'x.prm'" or the include line.
    std::string read_bounded_file(const std::string &path, const std::string &what)
    {
      struct stat info;
      if (::stat(path.c_str(), &info) != 0)
        throw InputError(what + (errno == ENOENT || errno == ENOTDIR ? " does not exist"
                                                                    : " cannot be examined: " +
                                                                        std::string(std::strerror(errno))));
      if (S_ISDIR(info.st_mode))
        throw InputError(what + " is a folder, not a scene file (.prm)");
      if (!S_ISREG(info.st_mode))
        throw InputError(what + " is not a regular file (a FIFO, device or socket); give a .prm file");
      if (static_cast<std::uintmax_t>(info.st_size) > max_scene_bytes)
        throw InputError(what + " has " + std::to_string(info.st_size) +
                         " bytes; a scene file has at most 1 MB (1048576 bytes)");
      // The read itself is the guarded one (io/input_file.h): should the
      // file have been replaced by a FIFO or have grown since, it says so.
      std::string text;
      try
        {
          text = read_text_file(path, max_scene_bytes);
        }
      catch (const FileReadError &e)
        {
          throw InputError(what + " cannot be read: " + e.what() + "; give a .prm file of at most 1 MB");
        }
      return text;
    }

    // Appends the lines of `file` to `scene`, each `include` line replaced
    // by the lines of the file it names (a path relative to the including
    // file, as Beam/Mesh file is). deal.II's own `include` would open the
    // path as given without any check; here every line is checked to be a
    // scene line first, so that a message never quotes a line of a file
    // that is not a scene (an included /etc/passwd is refused by its file
    // name and line number only). `chain` holds the files being read, the
    // outermost first: a file that includes one of them is a cycle.
    // `what` names the file for a message about the file as a whole,
    // `included_by` (" (included by 'a.prm', line 3)", or "") follows the
    // place of a message about one of its lines.
    void append_scene_file(const std::string &file, const std::string &what, const std::string &included_by,
                           std::vector<std::string> &chain, SceneText &scene)
    {
      namespace fs = std::filesystem;
      const std::string text = read_bounded_file(file, what);
      std::error_code ec;
      chain.push_back(fs::weakly_canonical(fs::absolute(file), ec).string());

      std::istringstream in(text);
      std::string line;
      unsigned int line_number = 0, depth = 0;
      bool continued = false; // the previous line ends in '\': deal.II joins the two
      while (std::getline(in, line))
        {
          ++line_number;
          const std::string where =
            "Scene file '" + printable(file) + "', line " + std::to_string(line_number) + included_by;
          for (std::size_t i = 0; i < line.size(); ++i)
            {
              const auto byte = static_cast<unsigned char>(line[i]);
              if ((byte < 0x20 && byte != '\t' && byte != '\r') || byte == 0x7f)
                throw InputError(where + " holds a byte that is not text (" + printable(std::string(1, line[i])) +
                                 " at column " + std::to_string(i + 1) + "); a scene file is text");
            }
          const std::string content = trim(line.substr(0, line.find('#')));
          const bool starts = !continued;
          continued = !trim(line).empty() && trim(line).back() == '\\';
          if (!starts || content.empty())
            {
              scene.text += line + '\n';
              scene.origins.push_back({file, line_number});
              continue;
            }
          std::istringstream words(content);
          std::string word;
          words >> word;
          const std::string keyword = scene_keyword(word), rest = trim(content.substr(word.size()));
          if (keyword == "subsection" && !rest.empty())
            ++depth;
          else if (keyword == "end" && rest.empty())
            {
              if (depth == 0)
                throw InputError(where + ": 'end' without a 'subsection' before it in this file");
              --depth;
            }
          else if (keyword == "include" && !rest.empty() && !continued)
            {
              if (chain.size() > max_include_depth)
                throw InputError(where + ": includes nest deeper than " + std::to_string(max_include_depth) +
                                 " files");
              fs::path target(rest);
              if (target.is_relative())
                target = fs::path(file).parent_path() / target;
              const std::string canonical = fs::weakly_canonical(fs::absolute(target), ec).string();
              const auto cycle = std::find(chain.begin(), chain.end(), canonical);
              if (cycle != chain.end())
                {
                  std::string names;
                  for (auto f = cycle; f != chain.end(); ++f)
                    names += "'" + printable(*f) + "' includes ";
                  throw InputError(where + ": 'include " + printable(rest) + "' is a cycle: " + names + "'" +
                                   printable(canonical) + "'; a scene cannot include itself");
                }
              const std::string place = "'" + printable(file) + "', line " + std::to_string(line_number);
              append_scene_file(target.string(), where + ": the included file '" + printable(target.string()) + "'",
                                " (included by " + place + ")", chain, scene);
              continue;
            }
          else if (keyword != "set" || rest.empty())
            throw InputError(where + " is not a scene line: a scene has only 'set Name = value', 'subsection "
                                     "Name', 'end' and 'include FILE' lines (the line is not shown, as it may "
                                     "not be from a scene file)");
          scene.text += line + '\n';
          scene.origins.push_back({file, line_number});
          if (scene.text.size() > max_scene_bytes)
            throw InputError(where + ": the scene with its included files has more than 1 MB; a scene has at "
                                     "most 1 MB (1048576 bytes)");
        }
      if (continued)
        throw InputError("Scene file '" + printable(file) + "', line " + std::to_string(line_number) + included_by +
                         ": the last line ends in '\\', which would join it to a line of another file");
      if (depth != 0)
        throw InputError("Scene file '" + printable(file) + "'" + included_by + ": " + std::to_string(depth) +
                         " 'subsection' without its 'end' (each file closes the subsections it opens)");
      chain.pop_back();
    }
  } // namespace

  namespace internal
  {
    // The text of a scene file with its includes, after checking that it is
    // one: a regular, non-empty text file of scene lines (a folder, a FIFO
    // or a device is refused before it is opened, so that reading cannot
    // hang).
    SceneText read_scene_text(const std::string &filename)
    {
      const std::string what = "Scene file '" + printable(filename) + "'";
      SceneText scene;
      std::vector<std::string> chain;
      append_scene_file(filename, what, "", chain, scene);
      if (trim(scene.text).empty())
        throw InputError(what + " is empty; a scene sets its parameters with 'set Name = value' "
                                "(see `beamslider scene-template`)");
      return scene;
    }

    // deal.II's reader lets a later `set` silently replace an earlier one; a
    // scene that sets a parameter twice is almost always an editing slip, so
    // it is refused. Also refuses a file without any `set`: it would run the
    // built-in defaults under the file's name.
    std::set<std::string> check_entries_unique(const std::string &filename, const SceneText &scene)
    {
      std::istringstream in(scene.text);
      std::vector<std::string> sections;
      std::map<std::string, unsigned int> first_line;
      std::string line;
      unsigned int line_number = 0, n_entries = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          line = trim(line.substr(0, line.find('#')));
          std::istringstream words(line);
          std::string word;
          words >> word;
          const std::string keyword = scene_keyword(word);
          if (keyword == "subsection")
            sections.push_back(trim(line.substr(keyword.size())));
          else if (keyword == "end" && !sections.empty())
            sections.pop_back();
          else if (keyword == "set")
            {
              const std::string rest = line.substr(keyword.size());
              std::string key;
              for (const auto &section : sections)
                key += section + "/";
              key += trim(rest.substr(0, rest.find('=')));
              ++n_entries;
              const auto [it, inserted] = first_line.emplace(key, line_number);
              if (!inserted)
                {
                  const SceneText::Origin &first = scene.origins[it->second - 1];
                  const bool same_file = first.file == scene.origins[line_number - 1].file;
                  throw InputError(scene.where(line_number) + ": '" + printable(key) + "' is set a second time (first " +
                                   (same_file ? "on line " + std::to_string(first.line)
                                              : "in '" + printable(first.file) + "', line " + std::to_string(first.line)) +
                                   "); a scene sets each parameter once");
                }
            }
        }
      if (n_entries == 0)
        throw InputError("Scene file '" + printable(filename) + "' sets no parameter (no 'set Name = value' line); "
                         "see `beamslider scene-template`");
      std::set<std::string> keys;
      for (const auto &[key, line] : first_line)
        keys.insert(key);
      return keys;
    }
  } // namespace internal
} // namespace beamslider
