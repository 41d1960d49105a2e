// Checkpoint files, see checkpoint.h.
#include "io/checkpoint.h"

#include "io/input_file.h"
#include "io/output_file.h"

#include <cstring>

#ifndef BEAMSLIDER_VERSION
#  define BEAMSLIDER_VERSION "unknown"
#endif

namespace beamslider
{
  namespace
  {
    const std::string magic = "beamslider checkpoint\n";
  }

  std::string checkpoint_file_bytes(const std::string &payload)
  {
    CheckpointWriter w;
    w.put(checkpoint_format);
    w.put(std::string(BEAMSLIDER_VERSION));
    w.put(std::uint64_t(payload.size()));
    CheckpointWriter tail;
    tail.put(fnv1a(payload));
    return magic + w.bytes() + payload + tail.bytes();
  }

  std::string read_checkpoint_file(const std::string &path)
  {
    std::string bytes;
    try
      {
        bytes = read_text_file(path, InputLimits::checkpoint);
      }
    catch (const FileReadError &e)
      {
        throw CheckpointError(std::string("no readable checkpoint: ") + e.what());
      }
    if (bytes.compare(0, magic.size(), magic) != 0)
      throw CheckpointError("'" + path + "' is not a beamslider checkpoint");
    CheckpointReader header(bytes.substr(magic.size()));
    const std::uint64_t format = header.get_uint();
    if (format != checkpoint_format)
      throw CheckpointError("checkpoint '" + path + "' has format " + std::to_string(format) +
                            "; this program reads format " + std::to_string(checkpoint_format));
    const std::string version = header.get_string();
    if (version != BEAMSLIDER_VERSION)
      throw CheckpointError("checkpoint '" + path + "' was written by beamslider " + version + ", this is " +
                            BEAMSLIDER_VERSION + "; a resumed run would not be the same computation");
    const std::uint64_t length = header.get_uint();
    const std::size_t start    = magic.size() + 3 * sizeof(std::uint64_t) + version.size();
    if (bytes.size() != start + length + sizeof(std::uint64_t))
      throw CheckpointError("checkpoint '" + path + "' is truncated or has trailing bytes");
    const std::string payload = bytes.substr(start, length);
    std::uint64_t stored;
    std::memcpy(&stored, bytes.data() + start + length, sizeof(stored));
    if (stored != fnv1a(payload))
      throw CheckpointError("checkpoint '" + path + "' is corrupt (checksum mismatch)");
    return payload;
  }
} // namespace beamslider
