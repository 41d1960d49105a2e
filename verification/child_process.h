// Starting helper programs (the matplotlib scripts) without a shell.
//
// Paths and scene names come from the user; pasted into a shell command line
// they would be code (`--output "x';touch PWNED;'"`). A child is therefore
// started with posix_spawn and an argument vector: every argument reaches the
// program as one string, whatever characters it holds.
#pragma once

#include <string>
#include <vector>

namespace beamslider
{
  struct ChildResult
  {
    bool started   = false; // the program could be started at all
    int exit_code  = -1;    // its exit status, when it exited normally
    int signal     = 0;     // the signal that ended it, else 0
    std::string error;      // why it could not be started / did not succeed

    bool succeeded() const { return started && signal == 0 && exit_code == 0; }
  };

  // Runs argv[0] (an absolute path, or a name looked up in PATH) with the
  // arguments argv[1...], waits for it, and says how it ended.
  ChildResult run_child(const std::vector<std::string> &argv);
} // namespace beamslider
