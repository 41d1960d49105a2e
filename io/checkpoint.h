// Checkpoint files of a running simulation: a state's bytes
// (numerics/state_bytes.h) in a checked file.
//
// File layout (checkpoint_file_bytes): a magic line, the format number, the
// program's version, the payload's length, the payload, and an FNV-1a 64-bit
// checksum of the payload. read_checkpoint_file refuses a file of another
// format or version, a truncated file and a checksum that does not match;
// the caller compares the scene's content hash stored in the payload, and
// (simulate) the run's identity and the digests of the files it continues.
#pragma once

#include "numerics/state_bytes.h"

#include <cstdint>
#include <string>

namespace beamslider
{
  // The format of the payload; raise it whenever what is saved changes.
  // 2: simulate's run description carries the whole model setting (θ, integrator, damped set).
  // 3: and the run's identity (command, model, scene) and digests of the files it continues.
  // 4: the model setting carries its static corrections and their Ritz blocks.
  // 5: a Python Run's checkpoint carries its last result (status, message, time).
  constexpr std::uint64_t checkpoint_format = 5;

  // The complete file around a payload, and back (throws CheckpointError).
  std::string checkpoint_file_bytes(const std::string &payload);
  std::string read_checkpoint_file(const std::string &path);
} // namespace beamslider
