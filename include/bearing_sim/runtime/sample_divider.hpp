#pragma once
// Decides, from the sample index, when a lower-rate output is due, so those outputs
// follow simulated time in real-time and as-fast-as-possible modes alike (ROS-free).
#include <cstdint>

namespace bearing_sim {
namespace runtime {

class SampleDivider {
 public:
  // Throws std::invalid_argument for rates that valid_rates() refuses (constructed where the
  // node starts, never in its simulation thread).
  SampleDivider(double output_rate_hz, double sample_rate_hz);
  // Both rates finite and > 0, and at least one output in 2^53 samples (the period stays an
  // exact integer). An output faster than the samples fires at every sample.
  static bool valid_rates(double output_rate_hz, double sample_rate_hz);
  // New rate; the next output is due one new period after the last one. Never throws: rates
  // that valid_rates() refuses return false and leave the divider as it was.
  bool set_rate(double output_rate_hz, double sample_rate_hz) noexcept;
  // True (once) when sample_index reaches the next due index. Indices must increase.
  bool due(std::uint64_t sample_index);
  std::uint64_t period_samples() const { return period_; }

 private:
  std::uint64_t period_ = 1;
  std::uint64_t next_due_;
  std::uint64_t last_fired_ = 0;
  bool fired_ = false;
};

}  // namespace runtime
}  // namespace bearing_sim
