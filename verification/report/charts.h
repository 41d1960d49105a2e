// Charts: the matplotlib scripts of scripts/, drawn by Debian's python3 as
// child processes with an argument vector (no shell), and the record of
// results that could not be written (a chart not drawn is one), which makes
// a command end with status 1.
#pragma once

#include "runtime/child_process.h"

#include <string>
#include <vector>

namespace beamslider
{
  // Runs a plotting script from scripts/ with Debian's python3 + matplotlib,
  // as a child process with an argument vector (no shell). A chart that could
  // not be drawn is a result not written: it is recorded (note_output_failure)
  // and the command exits with status 1 at its end; returns whether it worked.
  bool run_plot_script(const std::string &script, const std::vector<std::string> &arguments);

  // The same script started before its data exist, so that Python and
  // matplotlib load (~0.35 s) while the run computes: the script is started
  // with --arguments-from-stdin and waits; draw() hands it the arguments and
  // waits for the chart, with run_plot_script's failure handling. Destroyed
  // without draw() (a failed or interrupted run), the script exits without
  // drawing.
  class EarlyPlot
  {
  public:
    explicit EarlyPlot(const std::string &script);
    bool draw(const std::vector<std::string> &arguments);

  private:
    std::string script_;
    EarlyChild child_;
  };

  // A result that could not be written but need not stop the command (a
  // chart): printed on stderr at once and remembered; main() exits with 1.
  void note_output_failure(const std::string &what);
  const std::vector<std::string> &output_failures();
  // Forgets them: a new command starts (the Python module runs many in one process).
  void clear_output_failures();
} // namespace beamslider
