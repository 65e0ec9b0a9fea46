#include "bearing_sim/runtime/sample_source.hpp"

#include <stdexcept>
#include <utility>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace runtime {

SampleSource::SampleSource(std::unique_ptr<RingDynamics> dynamics) : dynamics_(std::move(dynamics)) {
  if (!dynamics_) throw std::invalid_argument("SampleSource: no dynamics");
}

SampleSource::SampleSource(BearingDynamics dynamics)
    : dynamics_(std::make_unique<RigidRingDynamics>(std::move(dynamics))) {}

SampleSource::Sample SampleSource::next() {
  Sample out;
  out.index = next_index_;
  out.time_s = static_cast<double>(next_index_) / dynamics_->sample_rate_hz();
  if (next_index_ > 0) {
    try {
      dynamics_->step();
    } catch (const DivergenceError& e) {
      ++divergence_count_;
      last_divergence_ = e.what();
      out.diverged = true;
      try {
        dynamics_->reset_to_equilibrium();
      } catch (const std::exception& reset_error) {
        // No equilibrium either: the state is still the last good one (step() leaves it
        // unchanged when it throws), which is finite.
        last_divergence_ += std::string("; reset failed: ") + reset_error.what();
      }
    }
  }
  held_ = dynamics_->current();
  // Our index and time; after a reset the core's own counter lags ours.
  held_.time_s = out.time_s;
  if (!held_.displacement.allFinite() || !held_.velocity.allFinite() || !held_.acceleration.allFinite()) {
    // Never hand out NaN, whatever happened inside the core.
    held_.displacement.setZero();
    held_.velocity.setZero();
    held_.acceleration.setZero();
    out.diverged = true;
  }
  out.state = &held_;
  ++next_index_;
  return out;
}

}  // namespace runtime
}  // namespace bearing_sim
