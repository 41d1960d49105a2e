// Writing scenes with deal.II's ParameterHandler: the template, a scene's
// parameter file and its values, and a command's settings in the same format.
#include "scene/scene.h"
#include "scene/scene_parameters_internal.h"

#include <deal.II/base/parameter_handler.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace beamslider
{
  namespace
  {
    using dealii::ParameterHandler;
    using dealii::Patterns::Anything;
    using internal::bind_scene;
    using internal::SceneTables;
  } // namespace

  std::string scene_template() { return scene_file_text(Scene()); }

  std::string scene_file_text(const Scene &scene)
  {
    ParameterHandler prm;
    Scene bound = scene; // bind_scene needs variables; this copy is only written
    SceneTables tables;
    bind_scene(prm, bound, tables);
    std::ostringstream out;
    prm.print_parameters(out, ParameterHandler::PRM);
    return out.str();
  }

  std::map<std::string, std::string> scene_parameter_values(const Scene &scene)
  {
    ParameterHandler prm;
    Scene bound = scene; // bind_scene needs variables; this copy is only written
    SceneTables tables;
    std::map<std::string, std::string> values;
    bind_scene(prm, bound, tables, &values);
    return values;
  }

  std::string command_settings_text(const std::string &command, const std::vector<CommandSetting> &settings)
  {
    ParameterHandler prm;
    prm.enter_subsection(command);
    for (const CommandSetting &c : settings)
      prm.declare_entry(c.name, c.value, Anything(), c.description);
    prm.leave_subsection();
    std::ostringstream out;
    prm.print_parameters(out, ParameterHandler::PRM);
    return out.str();
  }
} // namespace beamslider
