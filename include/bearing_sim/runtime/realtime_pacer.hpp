#pragma once
// Paces the simulation against a steady clock with absolute deadlines: sample n is due
// at start + n / sample_rate. Deadlines never accumulate sleep errors, and a chunk size
// change needs no re-anchoring because the deadline depends only on the sample index.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace bearing_sim {
namespace runtime {

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

// Computing ahead of wall time by a bounded lead (the node's ~lead_ms). Two threads: the
// simulation thread may compute chunk k (last sample L) from due(L) - lead, with at most
// max_queued() chunks computed and not yet published; the publisher thread publishes it at
// due(L), never earlier, or at once when it comes late (catching up: every chunk once, in
// order). A delay of the simulation thread shorter than the lead thus costs no lateness,
// and inputs apply at the first chunk not yet computed (input latency <= the lead).
// lead 0: computed when its last sample is due, published at once (just in time).
class LeadScheduler {
 public:
  using Clock = RealtimePacer::Clock;

  LeadScheduler(const RealtimePacer& pacer, Clock::duration lead);

  Clock::time_point compute_start(std::uint64_t last_index) const { return pacer_.due_time(last_index) - lead_; }
  Clock::time_point publish_time(std::uint64_t last_index) const { return pacer_.due_time(last_index); }
  // Most chunks computed and not yet published for this chunk size: what the lead spans, + 1.
  std::size_t max_queued(std::size_t chunk_samples) const;
  // Whether the simulation thread may compute the chunk ending at next_last now, with
  // `queued` chunks waiting for the publisher.
  bool may_compute(Clock::time_point now, std::size_t queued, std::uint64_t next_last,
                   std::size_t chunk_samples) const {
    return queued < max_queued(chunk_samples) && now >= compute_start(next_last);
  }
  Clock::duration lead() const { return lead_; }
  const RealtimePacer& pacer() const { return pacer_; }

 private:
  RealtimePacer pacer_;
  Clock::duration lead_;
};

}  // namespace runtime
}  // namespace bearing_sim
