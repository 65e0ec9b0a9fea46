// The dynamics integrates only the balls near contact. Skipping the others must not
// change the result: compare with the run over every ball, through a load step and a
// speed ramp where balls enter and leave the load zone fast.
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

TEST(BallSubset, SkippingClearBallsLeavesTheTrajectoryUnchanged) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  Vector5 load;
  load << 6800.0, 0.0, 0.0, 0.0, 2100.0;
  DynamicsOptions all_balls;
  all_balls.skip_clear_balls = false;
  BearingDynamics reference(model, load, 0.0, all_balls);
  BearingDynamics subset(model, load, 0.0, DynamicsOptions{});
  const double full_speed = 180.0 * 2.0 * M_PI / 60.0;
  double max_accel_difference = 0.0, max_accel = 0.0;
  for (int i = 0; i < 3000; ++i) {
    if (i == 1000) {  // a 2x load step
      reference.set_load(2.0 * load);
      subset.set_load(2.0 * load);
    }
    const double speed = full_speed * std::min(1.0, i / 2000.0);  // ramp 0 -> 180 rpm
    reference.set_ring_speed(speed);
    subset.set_ring_speed(speed);
    const DynamicSample a = reference.step();
    const DynamicSample b = subset.step();
    max_accel_difference = std::max(max_accel_difference, (a.acceleration - b.acceleration).norm());
    max_accel = std::max(max_accel, a.acceleration.norm());
  }
  EXPECT_LT(subset.active_ball_count(), static_cast<std::size_t>(model.ball_count()))
      << "the CT load zone does not cover every ball, so some must be skipped";
  // Only the order of the force sum differs: rounding of the 1e4 N contact sum
  // (1e-16 relative) over 46 kg gives 1e-13 m/s^2; allow 1e-9 of the peak transient.
  EXPECT_LT(max_accel_difference, 1e-9 * max_accel);
}

}  // namespace
}  // namespace bearing_sim
