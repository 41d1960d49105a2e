// Checkpoint encoding, see checkpoint.h.
#include "contact/checkpoint.h"

#include "contact/output_file.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#ifndef BEAMSLIDER_VERSION
#  define BEAMSLIDER_VERSION "unknown"
#endif

namespace beamslider
{
  namespace
  {
    const std::string magic = "beamslider checkpoint\n";
  }

  std::uint64_t fnv1a(const std::string &bytes, std::uint64_t hash)
  {
    for (const unsigned char c : bytes)
      {
        hash ^= c;
        hash *= 1099511628211ull;
      }
    return hash;
  }

  void CheckpointWriter::put(const double x)
  {
    char raw[sizeof(double)];
    std::memcpy(raw, &x, sizeof(double));
    bytes_.append(raw, sizeof(double));
  }

  void CheckpointWriter::put(const std::uint64_t x)
  {
    char raw[sizeof(x)];
    std::memcpy(raw, &x, sizeof(x));
    bytes_.append(raw, sizeof(x));
  }

  void CheckpointWriter::put(const bool x) { put(std::uint64_t(x ? 1 : 0)); }

  void CheckpointWriter::put(const std::string &x)
  {
    put(std::uint64_t(x.size()));
    bytes_.append(x);
  }

  void CheckpointWriter::put(const Eigen::VectorXd &x)
  {
    put(std::uint64_t(x.size()));
    for (Eigen::Index i = 0; i < x.size(); ++i)
      put(x[i]);
  }

  CheckpointReader::CheckpointReader(std::string bytes)
    : bytes_(std::move(bytes))
  {}

  void CheckpointReader::take(void *out, const std::size_t n)
  {
    if (bytes_.size() - position_ < n)
      throw CheckpointError("checkpoint is shorter than its contents say (truncated)");
    std::memcpy(out, bytes_.data() + position_, n);
    position_ += n;
  }

  double CheckpointReader::get_double()
  {
    double x;
    take(&x, sizeof(x));
    return x;
  }

  std::uint64_t CheckpointReader::get_uint()
  {
    std::uint64_t x;
    take(&x, sizeof(x));
    return x;
  }

  bool CheckpointReader::get_bool() { return get_uint() != 0; }

  std::string CheckpointReader::get_string()
  {
    const std::uint64_t n = get_uint();
    if (n > bytes_.size() - position_)
      throw CheckpointError("checkpoint is shorter than its contents say (truncated)");
    std::string x = bytes_.substr(position_, n);
    position_ += n;
    return x;
  }

  std::uint64_t CheckpointReader::get_count(const std::size_t bytes_per_item)
  {
    const std::uint64_t n = get_uint();
    const std::size_t left = bytes_.size() - position_;
    if (n > left / std::max<std::size_t>(bytes_per_item, 1))
      throw CheckpointError("checkpoint records " + std::to_string(n) + " entries of at least " +
                            std::to_string(bytes_per_item) + " bytes where only " + std::to_string(left) +
                            " bytes are left (corrupt)");
    return n;
  }

  Eigen::VectorXd CheckpointReader::get_vector(const Eigen::Index size)
  {
    const std::uint64_t n = get_uint();
    if (n != static_cast<std::uint64_t>(size))
      {
        std::ostringstream m;
        m << "checkpoint holds a vector of " << n << " entries where the model has " << size
          << " (another mesh or number of modes)";
        throw CheckpointError(m.str());
      }
    Eigen::VectorXd x(size);
    for (Eigen::Index i = 0; i < size; ++i)
      x[i] = get_double();
    return x;
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
        bytes = read_text_file(path);
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
