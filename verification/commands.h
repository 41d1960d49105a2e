// The sub-commands of the `beamslider` executable. Each reads a scene, writes
// CSV (named columns, SI units) and plots into an output folder, and returns
// the process exit code. User errors are thrown as InputError.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace beamslider
{
  struct CommonOptions
  {
    std::string scene_file;             // path to a .prm scene
    std::vector<std::string> overrides; // "Section/Name=value"
    std::string output_dir;             // "" = reports/<scene name>/<command>
  };

  struct ModesOptions
  {
    unsigned int n_modes = 7;
    std::optional<double> slider_at; // x_C/L of a bonded slider
    unsigned int n_elements = 0;     // 0 = the scene's mesh
  };
  int run_modes(const CommonOptions &common, const ModesOptions &options);

  struct VerifyOptions
  {
    bool full = false; // the long studies (minutes to hours)
  };
  int run_verify(const CommonOptions &common, const VerifyOptions &options);

  // Resolves a scene argument: the path as given, else relative to the
  // source tree's meshes/ (so `beamslider modes mueller2023` works anywhere).
  std::string resolve_scene_path(const std::string &scene);
  // Creates (if needed) and returns the output folder for a command.
  std::string prepare_output_dir(const CommonOptions &common, const std::string &scene_name, const std::string &command);
  // Runs a plotting script from scripts/ with Debian's python3 + matplotlib;
  // returns false (with a warning printed) if plotting is unavailable.
  bool run_plot_script(const std::string &script, const std::vector<std::string> &arguments);
} // namespace beamslider
