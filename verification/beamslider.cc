// beamslider: one executable, one sub-command per task. Every sub-command
// reads a scene (meshes/*.prm, or its name), accepts parameter overrides
// (--set "Section/Name=value"), and writes CSV + plots into an output folder
// (default reports/<scene>/<command>).
//
//   beamslider modes SCENE [--slider-at S]   linear bending modes (SLEPc)
//   beamslider verify [SCENE] [--full]       the verification report
//   beamslider scene-template                every parameter with unit and range
#include "meshes/scene.h"
#include "verification/commands.h"

#include <deal.II/base/mpi.h>

#include <CLI/CLI.hpp>

#include <iostream>

using namespace beamslider;

int main(int argc, char **argv)
{
  // PETSc/SLEPc (the eigensolver) need MPI initialised; one process.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  CLI::App app{"beamslider: FE and reduced-order models of a beam with a sliding mass (cross-verification suite)"};
  app.require_subcommand(1);

  CommonOptions common;
  auto add_common = [&common](CLI::App *sub, const bool scene_required) {
    auto *scene = sub->add_option("scene", common.scene_file, "scene file (.prm) or name in meshes/ (default: mueller2023)");
    if (scene_required)
      scene->required();
    else
      common.scene_file = "mueller2023";
    sub->add_option("--set", common.overrides, "override a parameter: \"Section/Name=value\" (repeatable)");
    sub->add_option("--output,-o", common.output_dir, "output folder (default reports/<scene>/<command>)");
  };

  ModesOptions modes;
  auto *modes_cmd = app.add_subcommand("modes", "linear bending modes of the bare beam or with a bonded slider");
  add_common(modes_cmd, true);
  modes_cmd->add_option("--slider-at", modes.slider_at, "bond the slider at x_C/L = S (seed Eq. 5 comparison)");
  modes_cmd->add_option("--modes", modes.n_modes, "number of modes")->check(CLI::Range(1, 50));
  modes_cmd->add_option("--elements", modes.n_elements, "FE elements (default: the scene's)")->check(CLI::Range(1, 4096));

  VerifyOptions verify;
  auto *verify_cmd = app.add_subcommand("verify", "write the verification report (reports/<scene>/report.md)");
  add_common(verify_cmd, false);
  verify_cmd->add_flag("--full", verify.full, "run the long studies too");

  auto *template_cmd = app.add_subcommand("scene-template", "print a scene file with every parameter, its unit and range");

  CLI11_PARSE(app, argc, argv);

  try
    {
      if (*modes_cmd)
        return run_modes(common, modes);
      if (*verify_cmd)
        return run_verify(common, verify);
      if (*template_cmd)
        {
          std::cout << scene_template();
          return 0;
        }
    }
  catch (const InputError &e)
    {
      std::cerr << "error: " << e.what() << std::endl;
      return 2;
    }
  catch (const std::exception &e)
    {
      std::cerr << "beamslider failed: " << e.what() << std::endl;
      return 1;
    }
  return 0;
}
