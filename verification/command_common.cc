#include "meshes/scene.h"
#include "verification/commands.h"

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace beamslider
{
  namespace fs = std::filesystem;

  std::string resolve_scene_path(const std::string &scene)
  {
    if (fs::exists(scene))
      return scene;
    for (const std::string &candidate : {std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/" + scene,
                                        std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/" + scene + ".prm"})
      if (fs::exists(candidate))
        return candidate;
    throw InputError("Scene '" + scene + "' not found (looked for the path as given and in " +
                     std::string(BEAMSLIDER_SOURCE_DIR) + "/meshes/)");
  }

  std::string prepare_output_dir(const CommonOptions &common, const std::string &scene_name, const std::string &command)
  {
    const fs::path dir = !common.output_dir.empty() ? fs::path(common.output_dir)
                         : command.empty()           ? fs::path("reports") / scene_name
                                                     : fs::path("reports") / scene_name / command;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec)
      throw InputError("--output '" + dir.string() + "' cannot be created: " + ec.message());
    return dir.string();
  }

  bool run_plot_script(const std::string &script, const std::vector<std::string> &arguments)
  {
    std::string command = std::string(BEAMSLIDER_PYTHON) + " " + BEAMSLIDER_SOURCE_DIR + "/scripts/" + script;
    for (const auto &a : arguments)
      command += " '" + a + "'";
    const int status = std::system(command.c_str());
    if (status != 0)
      std::cerr << "warning: plotting failed (" << command << "); the CSV files are complete\n";
    return status == 0;
  }
} // namespace beamslider
