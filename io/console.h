// One stream for what the commands, studies and report sections tell the
// user while they work: progress, timing and the closing summary. The
// results themselves are in the output folder (CSV, Markdown, pictures), and
// errors and warnings go to standard error, so `--quiet` (set_quiet) can
// switch this stream off without losing anything.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace beamslider
{
  // Standard output, or a stream that discards everything after set_quiet(true).
  std::ostream &console();

  void set_quiet(bool quiet);
  bool is_quiet();

  // Sends console() to `sink`, one call per line (without its '\n'), instead
  // of standard output; an empty function restores standard output. The
  // Python module hands progress to a user's callback this way.
  void set_console_sink(std::function<void(const std::string &)> sink);
} // namespace beamslider
