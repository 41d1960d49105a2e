// The `beamslider` command line as a library function (command_line.cc),
// shared by the executable and the Python module.
#pragma once

#include <ostream>

namespace beamslider
{
  // Parses argv (argv[0] the program name, argv[1] the sub-command) and runs
  // the sub-command. Returns the exit status: 0 success; 1 a run or solver
  // failed, or a result file could not be written; 2 bad input; 128 + signal
  // when interrupted. Each error is one line on `errors` ("error: …" for bad
  // input, "beamslider failed: …" for a failure); progress goes to console().
  // The caller installs the interruption handlers and records the command line.
  // `handover` (the Python module's study objects) computes a study without
  // writing it, or writes one computed before (commands.h, StudyHandover).
  struct StudyHandover;
  int run_beamslider(int argc, char **argv, std::ostream &errors, StudyHandover *handover = nullptr);
} // namespace beamslider
