#pragma once
// Decides, from the sample index, when a lower-rate output is due, so those outputs
// follow simulated time in real-time and as-fast-as-possible modes alike (ROS-free).
#include <cstdint>

namespace bearing_sim {
namespace ros_node {

class SampleDivider {
 public:
  SampleDivider(double output_rate_hz, double sample_rate_hz);
  // New rate; the next output is due one new period after the last one.
  void set_rate(double output_rate_hz, double sample_rate_hz);
  // True (once) when sample_index reaches the next due index. Indices must increase.
  bool due(std::uint64_t sample_index);
  std::uint64_t period_samples() const { return period_; }

 private:
  std::uint64_t period_ = 1;
  std::uint64_t next_due_;
  std::uint64_t last_fired_ = 0;
  bool fired_ = false;
};

}  // namespace ros_node
}  // namespace bearing_sim
