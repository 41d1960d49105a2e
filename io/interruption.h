// Ctrl-C and kill without losing finished work.
//
// install_interruption_handlers() makes SIGINT and SIGTERM request a stop
// (numerics/stop_request.h) instead of killing the process. Long loops poll
// the request once per step, finish the step they are in, and stop with
// status `interrupted`; the command then writes complete rows and its
// summary and exits with 128 + the signal (130 for SIGINT, 143 for SIGTERM),
// as a shell expects. A second signal of the same kind while the first is
// being handled is ignored: the run is already stopping.
//
// It also ignores SIGXFSZ, so that a file-size limit makes a write fail (and
// OutputFile report it) instead of killing the process with a half-written
// row, and SIGPIPE, so that writing to a chart process that died makes the
// write fail rather than the run.
#pragma once

#include "numerics/stop_request.h"

namespace beamslider
{
  void install_interruption_handlers();
} // namespace beamslider
