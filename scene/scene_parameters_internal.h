// What the files that read, check and write scenes (scene/scene_*.cc) share:
// the bound entry declarations, a scene's text with its includes and the
// check that text parameters are recordable. Internal to beamslider_scene.
#pragma once

#include "scene/scene.h"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace beamslider
{
  namespace internal
  {
    // The shortest text that reads back to the same double (scene_parameters.cc).
    std::string num(const double x);

    // `x` without leading and trailing blanks (scene_file_reader.cc).
    std::string trim(const std::string &x);

    // The tables of a scene, as read: the sections by tag and the point
    // bodies by position, assembled into the beam by build_beam().
    struct SceneTables
    {
      std::map<std::string, std::map<unsigned int, double>> sections; // "Width" -> tag -> value
      std::map<double, double> masses, inertias;                      // x -> m, x -> J
    };

    // Every entry of a scene bound to the fields of `s` and `tables`
    // (scene_parameters.cc).
    void bind_scene(dealii::ParameterHandler &prm, Scene &s, SceneTables &tables,
                    std::map<std::string, std::string> *values = nullptr);

    // The lines of a scene after its `include` lines are replaced by the
    // files they name, with where each line comes from, so that a message
    // names the file and the line the user wrote.
    struct SceneText
    {
      struct Origin
      {
        std::string file;
        unsigned int line;
      };
      std::string text;            // every line, '\n'-terminated
      std::vector<Origin> origins; // of line i + 1 of text

      // "Scene file 'F', line N" for line `line` (from 1) of text.
      std::string where(const unsigned int line) const;
    };

    // The text of a scene file with its includes, checked to be a scene
    // (scene_file_reader.cc).
    SceneText read_scene_text(const std::string &filename);

    // The parameters a scene sets, each set once (scene_file_reader.cc).
    std::set<std::string> check_entries_unique(const std::string &filename, const SceneText &scene);

    // A text parameter that parameters.prm can record (scene_validation.cc).
    void require_recordable(const std::string &parameter, const std::string &value);

    // Every text parameter of a scene, as parameters.prm would write it.
    void require_recordable(const Scene &s);
  } // namespace internal
} // namespace beamslider
