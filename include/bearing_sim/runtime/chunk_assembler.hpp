#pragma once
// Collects consecutive samples into fixed-size chunks (ROS-free). Refuses a sample that
// is not the next in sequence, so a published chunk is always contiguous.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bearing_sim/core/bearing_dynamics.hpp"

namespace bearing_sim {
namespace runtime {

struct SampleChunk {
  std::uint64_t first_sample = 0;
  std::vector<float> accel_x, accel_y, accel_z;                       // m/s^2
  std::vector<float> displacement_x, displacement_y, displacement_z;  // m
  std::vector<float> tilt_x, tilt_y;                                  // rad
  std::size_t size() const { return accel_x.size(); }
};

class ChunkAssembler {
 public:
  explicit ChunkAssembler(std::size_t chunk_samples, std::uint64_t first_sample = 0);

  // Takes effect from the next chunk that is started (the one being filled keeps its size).
  void set_chunk_samples(std::size_t chunk_samples);
  std::size_t chunk_samples() const { return chunk_samples_; }

  // Appends the sample numbered `sample_index`; throws std::logic_error unless it is
  // next_sample(). Returns true when the chunk is full and ready for take().
  bool add(std::uint64_t sample_index, const DynamicSample& sample) {
    return add(sample_index, sample.acceleration.head<3>(), sample.displacement);
  }
  // The same with another acceleration (a sensor's x, y, z) and the ring's displacement then.
  bool add(std::uint64_t sample_index, const Eigen::Vector3d& acceleration, const Vector5& displacement);
  // The full chunk; the next one starts empty.
  SampleChunk take();

  std::uint64_t next_sample() const { return next_sample_; }
  std::size_t current_target() const { return current_target_; }

 private:
  void start_chunk();

  std::size_t chunk_samples_;
  std::size_t current_target_;
  std::uint64_t next_sample_;
  SampleChunk chunk_;
};

}  // namespace runtime
}  // namespace bearing_sim
