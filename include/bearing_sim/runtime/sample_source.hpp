#pragma once
// The stream of output samples from the dynamics, numbered from 0 (the initial static
// equilibrium) with one dynamics step per further sample. A diverging step never
// leaves this class: the model is reset to the static equilibrium and that finite
// state is the sample (ROS-free).
#include <cstdint>
#include <memory>
#include <string>

#include "bearing_sim/core/ring_dynamics.hpp"

namespace bearing_sim {
namespace runtime {

class SampleSource {
 public:
  // The rigid or flexible ring's dynamics (make_ring_dynamics).
  explicit SampleSource(std::unique_ptr<RingDynamics> dynamics);
  explicit SampleSource(BearingDynamics dynamics);

  struct Sample {
    std::uint64_t index = 0;
    double time_s = 0.0;                   // index / sample rate
    const DynamicSample* state = nullptr;  // valid until the next call
    bool diverged = false;                 // the step diverged and the model was reset
  };
  Sample next();

  // For inputs and model changes, between samples.
  RingDynamics& ring() { return *dynamics_; }
  const RingDynamics& ring() const { return *dynamics_; }
  std::uint64_t next_index() const { return next_index_; }
  std::uint64_t divergence_count() const { return divergence_count_; }
  const std::string& last_divergence() const { return last_divergence_; }

 private:
  std::unique_ptr<RingDynamics> dynamics_;
  // Our own count: after a reset the core's sample counter does not advance, but the
  // published sequence must.
  std::uint64_t next_index_ = 0;
  std::uint64_t divergence_count_ = 0;
  std::string last_divergence_;
  DynamicSample held_;
};

}  // namespace runtime
}  // namespace bearing_sim
