// What this build is, as every output folder records it (run.txt) and as
// a resumable study keys its records (member_runs.h): results depend on the
// source revision and, in their last bits, on the instruction set.
#pragma once

#include <string>

namespace beamslider
{
  struct BuildInfo
  {
    std::string version;   // the project's version, "0.9.0"
    std::string revision;  // git describe of the source tree when configured
    std::string built_for; // the instruction set (CMake option BEAMSLIDER_NATIVE)
  };

  // Set by CMake on this one file, so that a new revision recompiles nothing else.
  const BuildInfo &build_info();

  // "beamslider <version> <revision>".
  std::string build_revision();

  // This executable's size and modification time ("<bytes> bytes, modified
  // <ns since the epoch>"): what tells two builds of one revision with
  // uncommitted changes apart. "unknown" if it cannot be read.
  std::string executable_identity();
} // namespace beamslider
