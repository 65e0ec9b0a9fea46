#pragma once
// Paces the simulation against a steady clock with absolute deadlines: sample n is due
// at start + n / sample_rate. Deadlines never accumulate sleep errors, and a chunk size
// change needs no re-anchoring because the deadline depends only on the sample index.
#include <atomic>
#include <chrono>
#include <cstdint>

namespace bearing_sim {
namespace ros_node {

class RealtimePacer {
 public:
  using Clock = std::chrono::steady_clock;

  RealtimePacer(double sample_rate_hz, Clock::time_point start);

  // Wall time at which the sample with this index (simulated time index / rate) is due.
  Clock::time_point due_time(std::uint64_t sample_index) const;
  // Sleeps until due_time(sample_index) with std::this_thread::sleep_until, in slices of
  // at most max_slice so that `stop` is noticed promptly. Returns false if stopped.
  bool sleep_until_due(std::uint64_t sample_index, const std::atomic<bool>& stop,
                       Clock::duration max_slice = std::chrono::milliseconds(50)) const;
  // now - due_time(sample_index), s: positive when the simulation is behind wall time.
  double lateness_s(std::uint64_t sample_index, Clock::time_point now) const;

  Clock::time_point start() const { return start_; }
  double sample_rate_hz() const { return sample_rate_hz_; }

 private:
  double sample_rate_hz_;
  Clock::time_point start_;
};

}  // namespace ros_node
}  // namespace bearing_sim
