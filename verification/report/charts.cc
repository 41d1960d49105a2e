#include "verification/report/charts.h"

#include "fem/petsc_session.h"
#include "scene/source_directory.h"
#include "runtime/mpi_cells.h"

#include <iostream>

namespace beamslider
{
  namespace
  {
    std::vector<std::string> &failed_outputs()
    {
      static std::vector<std::string> failures;
      return failures;
    }
  } // namespace

  void note_output_failure(const std::string &what)
  {
    if (launch_rank() == 0 || !mpi_started()) // once, not per rank of a command on MPI
      std::cerr << "error: " << what << std::endl;
    failed_outputs().push_back(what);
  }

  const std::vector<std::string> &output_failures() { return failed_outputs(); }

  void clear_output_failures() { failed_outputs().clear(); }

  namespace
  {
    // Whether the chart's process succeeded; a failure is a result not written.
    bool drawn(const ChildResult &result, const std::string &script)
    {
      if (!result.succeeded())
        note_output_failure("the chart of " + script + " was not drawn (" + result.error +
                            "); the CSV files beside it are complete");
      return result.succeeded();
    }
  } // namespace

  bool run_plot_script(const std::string &script, const std::vector<std::string> &arguments)
  {
    // The interpreter was found once, at configure time (CMake); the script
    // and every argument go to it as separate strings, never through a shell.
    std::vector<std::string> argv = {BEAMSLIDER_PYTHON, source_directory() + "/scripts/" + script};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    return drawn(run_child(argv, ChildEnvironment::inherited, ChildGroup::own), script);
  }

  EarlyPlot::EarlyPlot(const std::string &script)
    : script_(script)
    , child_({BEAMSLIDER_PYTHON, source_directory() + "/scripts/" + script, "--arguments-from-stdin"})
  {}

  bool EarlyPlot::draw(const std::vector<std::string> &arguments)
  {
    return drawn(child_.finish(arguments), script_);
  }
} // namespace beamslider
