// One stream for what the commands, studies and report sections tell the
// user while they work: progress, timing and the closing summary. The
// results themselves are in the output folder (CSV, Markdown, pictures), and
// errors and warnings go to standard error, so `--quiet` (set_quiet) can
// switch this stream off without losing anything.
#pragma once

#include <ostream>

namespace beamslider
{
  // Standard output, or a stream that discards everything after set_quiet(true).
  std::ostream &console();

  void set_quiet(bool quiet);
} // namespace beamslider
