#include "bearing_sim/runtime/realtime_pacer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace bearing_sim {
namespace runtime {

RealtimePacer::RealtimePacer(double sample_rate_hz, Clock::time_point start)
    : sample_rate_hz_(sample_rate_hz), start_(start) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz))
    throw std::invalid_argument("sample rate must be a positive number of Hz");
}

RealtimePacer::Clock::time_point RealtimePacer::due_time(std::uint64_t sample_index) const {
  // Computed from the index every time (long double: exact to the ns for days of samples).
  const long double ns = static_cast<long double>(sample_index) * 1.0e9L / sample_rate_hz_;
  return start_ + std::chrono::duration_cast<Clock::duration>(
                      std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(ns))));
}

bool RealtimePacer::sleep_until_due(std::uint64_t sample_index, const std::atomic<bool>& stop,
                                    Clock::duration max_slice) const {
  const Clock::time_point due = due_time(sample_index);
  while (!stop.load(std::memory_order_relaxed)) {
    const Clock::time_point now = Clock::now();
    if (now >= due) return true;
    // The last slice ends exactly at the absolute deadline.
    std::this_thread::sleep_until(std::min(due, now + max_slice));
  }
  return false;
}

double RealtimePacer::lateness_s(std::uint64_t sample_index, Clock::time_point now) const {
  return std::chrono::duration<double>(now - due_time(sample_index)).count();
}

LeadScheduler::LeadScheduler(const RealtimePacer& pacer, Clock::duration lead) : pacer_(pacer), lead_(lead) {
  if (lead < Clock::duration::zero()) throw std::invalid_argument("the lead must be >= 0");
}

std::size_t LeadScheduler::max_queued(std::size_t chunk_samples) const {
  const double lead_samples = std::chrono::duration<double>(lead_).count() * pacer_.sample_rate_hz();
  return static_cast<std::size_t>(
             std::floor(lead_samples / static_cast<double>(std::max<std::size_t>(1, chunk_samples)))) +
         1;
}

}  // namespace runtime
}  // namespace bearing_sim
