// The one way beamslider reads a file: scenes, meshes, checkpoints, the
// model-choice cache, another run's members.csv or pcs.csv, a map's
// settings and rows, a part of the report written by a second process.
//
// Every file is checked before it is opened: a regular file (a FIFO, a
// device such as /dev/zero, a socket or a folder is refused by its type, so
// a read can neither block for a writer nor run without end), of at most
// the size its format can have (InputLimits). It is opened without waiting
// (O_NONBLOCK: a file swapped for a FIFO after the check is refused by
// fstat, not waited on) and read whole. Any failure is a FileReadError
// naming the file and the reason; the command line exits with status 2.
// Plain C++: no deal.II, no model; every layer may use it.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace beamslider
{
  // A file could not be read (not there, not a regular file, larger than
  // its format allows, no permission, an I/O error). Callers rethrow it as
  // their own kind where they can say more (a scene file, a checkpoint).
  class FileReadError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // The largest file of each kind the program reads [bytes]: far above what
  // a run writes (a 1000-member ensemble's members.csv is ~0.1 MB, a 1000 ×
  // 1000-point map's rows ~100 MB), far below what would exhaust memory.
  struct InputLimits
  {
    static constexpr std::size_t MiB        = std::size_t(1) << 20;
    static constexpr std::size_t scene      = 1 * MiB;   // a .prm with its includes, each file
    static constexpr std::size_t mesh       = 256 * MiB; // a Gmsh or Abaqus mesh
    static constexpr std::size_t checkpoint = 64 * MiB;  // a run's state (FE: kB; a sweep: its rows)
    static constexpr std::size_t table      = 512 * MiB; // a CSV a run wrote (members, rows, cache)
    static constexpr std::size_t text       = 16 * MiB;  // a summary, settings, a report part
  };

  // The whole of `path`, byte for byte, checked as above. Throws
  // FileReadError.
  std::string read_text_file(const std::string &path, std::size_t max_bytes = InputLimits::table);

  // The same, or "" if nothing is at `path` (a folder a run is about to
  // start in); anything that is there but cannot be read still throws.
  std::string read_text_file_if_present(const std::string &path, std::size_t max_bytes = InputLimits::table);

  // read_text_file for a file an option names: the FileReadError's message
  // begins with what the file is to the command, e.g. role = "--against: no
  // readable members.csv".
  std::string read_option_file(const std::string &path, const std::string &role,
                               std::size_t max_bytes = InputLimits::table);
} // namespace beamslider
