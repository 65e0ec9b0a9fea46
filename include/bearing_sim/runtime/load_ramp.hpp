#pragma once
// A new load reached linearly over a number of samples instead of in one step (the node's
// ~load_ramp_s). A staircase of load messages, such as a rotating unbalance sent once per
// chunk by scenario_player, would otherwise make the stiff ring ring at every step.
#include <cstdint>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {
namespace runtime {

class LoadRamp {
 public:
  explicit LoadRamp(std::uint64_t samples = 0) : samples_(samples), step_(samples) {}  // idle until start()
  // From the load applied now towards a new one; with 0 samples nothing is left to do:
  // the caller applies the target at once.
  void start(const Vector5& current, const Vector5& target) {
    from_ = current;
    to_ = target;
    step_ = 0;
  }
  bool active() const { return step_ < samples_; }
  // The load for the next sample; the target itself at the last one.
  Vector5 next() {
    if (step_ < samples_) ++step_;
    if (step_ >= samples_) return to_;
    return from_ + (to_ - from_) * (static_cast<double>(step_) / static_cast<double>(samples_));
  }

 private:
  std::uint64_t samples_ = 0;
  std::uint64_t step_ = 0;
  Vector5 from_ = Vector5::Zero(), to_ = Vector5::Zero();
};

}  // namespace runtime
}  // namespace bearing_sim
