// Checkpoints of a running simulation: the whole state, bit for bit.
//
// A resumed run must be bit-identical to one that was never stopped, so a
// checkpoint holds every number that influences a later step exactly as it
// is in memory (raw IEEE doubles, not text): the beam's coordinates and
// velocities, the slider's, the contact solver's warm starts, whatever the
// beam model carries between steps (BeamSystem::save_state), the per-period
// accumulators and the output cursors of AdaptationRun.
//
// File layout (checkpoint_file_bytes): a magic line, the format number, the
// program's version, the payload's length, the payload, and an FNV-1a 64-bit
// checksum of the payload. read_checkpoint_file refuses a file of another
// format or version, a truncated file and a checksum that does not match;
// the caller compares the scene's content hash stored in the payload, and
// (simulate) the run's identity and the digests of the files it continues.
#pragma once

#include <Eigen/Dense>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace beamslider
{
  // A checkpoint that cannot be used (corrupt, another version, another scene).
  class CheckpointError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  // FNV-1a, 64 bit: a checksum against corruption and a content hash of the
  // scene (not a cryptographic hash).
  std::uint64_t fnv1a(const std::string &bytes, std::uint64_t seed = 14695981039346656037ull);

  class CheckpointWriter
  {
  public:
    void put(double x);
    void put(std::uint64_t x);
    void put(bool x);
    void put(const std::string &x);
    void put(const Eigen::VectorXd &x);
    template <int R, int C>
    void put(const Eigen::Matrix<double, R, C> &x)
    {
      for (Eigen::Index i = 0; i < x.size(); ++i)
        put(x.data()[i]);
    }
    const std::string &bytes() const { return bytes_; }

  private:
    std::string bytes_;
  };

  class CheckpointReader
  {
  public:
    explicit CheckpointReader(std::string bytes);
    double get_double();
    std::uint64_t get_uint();
    bool get_bool();
    std::string get_string();
    // A count of items that take at least `bytes_per_item` bytes each,
    // refused (CheckpointError) if the rest of the checkpoint cannot hold
    // them: a corrupt count must not size an allocation.
    std::uint64_t get_count(std::size_t bytes_per_item);
    // A vector of exactly `size` entries (CheckpointError otherwise).
    Eigen::VectorXd get_vector(Eigen::Index size);
    template <int R, int C>
    void get(Eigen::Matrix<double, R, C> &x)
    {
      for (Eigen::Index i = 0; i < x.size(); ++i)
        x.data()[i] = get_double();
    }
    bool at_end() const { return position_ == bytes_.size(); }

  private:
    void take(void *out, std::size_t n);
    std::string bytes_;
    std::size_t position_ = 0;
  };

  // The format of the payload; raise it whenever what is saved changes.
  // 2: simulate's run description carries the whole model setting (θ, integrator, damped set).
  // 3: and the run's identity (command, model, scene) and digests of the files it continues.
  constexpr std::uint64_t checkpoint_format = 3;

  // The complete file around a payload, and back (throws CheckpointError).
  std::string checkpoint_file_bytes(const std::string &payload);
  std::string read_checkpoint_file(const std::string &path);
} // namespace beamslider
