#include "bearing_sim/runtime/sample_divider.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bearing_sim {
namespace runtime {
namespace {
constexpr double kMaxPeriodSamples = 9007199254740992.0;  // 2^53
}  // namespace

SampleDivider::SampleDivider(double output_rate_hz, double sample_rate_hz) {
  if (!set_rate(output_rate_hz, sample_rate_hz))
    throw std::invalid_argument("rates must be finite, positive numbers of Hz");
  next_due_ = period_ - 1;  // first output after one full period (sample period-1 closes it)
}

bool SampleDivider::valid_rates(double output_rate_hz, double sample_rate_hz) {
  if (!(output_rate_hz > 0.0) || !(sample_rate_hz > 0.0) || !std::isfinite(output_rate_hz) ||
      !std::isfinite(sample_rate_hz))
    return false;
  const double ratio = sample_rate_hz / output_rate_hz;
  // An output faster than the samples still fires once per sample (period 1).
  return std::isfinite(ratio) && ratio <= kMaxPeriodSamples;
}

bool SampleDivider::set_rate(double output_rate_hz, double sample_rate_hz) noexcept {
  if (!valid_rates(output_rate_hz, sample_rate_hz)) return false;
  period_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(sample_rate_hz / output_rate_hz)));
  if (fired_) next_due_ = last_fired_ + period_;
  else next_due_ = period_ - 1;
  return true;
}

bool SampleDivider::due(std::uint64_t sample_index) {
  if (sample_index < next_due_) return false;
  last_fired_ = sample_index;
  fired_ = true;
  // Stay on the grid of the period (no drift), skipping grid points already passed.
  while (next_due_ <= sample_index) next_due_ += period_;
  return true;
}

}  // namespace runtime
}  // namespace bearing_sim
