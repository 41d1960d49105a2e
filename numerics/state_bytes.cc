// The bytes of a state, see state_bytes.h.
#include "numerics/state_bytes.h"

#include <algorithm>
#include <cstring>
#include <sstream>

namespace beamslider
{
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
} // namespace beamslider
