// The bytes of a model's state, bit for bit: what a checkpoint holds.
//
// A resumed run must be bit-identical to one that was never stopped, so the
// state of everything that influences a later step is written exactly as it
// is in memory (raw IEEE doubles, not text): the beam's coordinates and
// velocities, the slider's, the contact solver's warm starts, whatever the
// beam model carries between steps (BeamSystem::save_state), the per-period
// accumulators and the output cursors of runs/adaptation_run.h. The models
// write and read their state here and know nothing of files; io/checkpoint.h
// puts a payload into a checked file and reads it back.
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
} // namespace beamslider
