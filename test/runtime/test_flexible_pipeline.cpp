// The per-sample pipeline of the node and of bearing_tool generate with a flexible ring behind
// the same interface as the rigid one (RingDynamics): the samples are FlexibleDynamics' own,
// the ball loads carry the load with the ring deformed, and a diverging state comes back to
// the flexible ring's static equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/flexible_dynamics.hpp"
#include "bearing_sim/core/ring_dynamics.hpp"
#include "bearing_sim/runtime/sample_pipeline.hpp"
#include "bearing_sim/runtime/sample_source.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::runtime;

namespace {
const std::string kFlexible = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ct_gantry_flexible.yaml";

using bearing_sim::test::ct_load;  // the CT gantry's load (test_support)

// Keeps the ideal samples and the ball loads handed out.
struct Sink : PipelineSink {
  std::vector<double> ax;  // ideal chunks' x acceleration, in order
  std::vector<std::vector<BallState>> balls;
  std::vector<std::uint64_t> ball_indices;
  void ideal_chunk(SampleChunk&& c) override {
    for (std::size_t i = 0; i < c.size(); ++i) ax.push_back(c.accel_x[i]);
  }
  void measured_chunk(SampleChunk&&) override {}
  void level(const SampleSource::Sample&, double, double) override {}
  bool wants_ball_loads() const override { return true; }
  void ball_loads(const SampleSource::Sample& s, const BearingModel&, const std::vector<BallState>& b) override {
    balls.push_back(b);
    ball_indices.push_back(s.index);
  }
};

// Sum of the balls' contact forces, Q n.
Eigen::Vector3d ball_force_sum(const std::vector<BallState>& balls) {
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  for (const BallState& b : balls) f += b.load_N * b.normal;
  return f;
}
}  // namespace

TEST(FlexiblePipeline, TheSamplesAreFlexibleDynamicsOwnAndTheBallsCarryTheLoad) {
  const BearingModel model(load_bearing_config(kFlexible));
  FlexibleDynamics reference(FlexibleBearing(model), ct_load(), test::kCtSpeedRadS);
  OutputSettings settings;
  settings.chunk_samples = 100;
  settings.ball_loads_rate_hz = 100.0;
  SamplePipeline pipeline(make_ring_dynamics(model, ct_load(), test::kCtSpeedRadS, DynamicsOptions{10000.0, 0}), nullptr,
                          settings, 0.0);
  ASSERT_NE(pipeline.source().ring().flexible(), nullptr);
  // Before the first sample: the static equilibrium. The balls' forces balance the applied
  // one there, 6800 N along x and none along y and z (the rigid-body equations; Newton stops
  // within 1e-9 N plus 1e-11 of the load, 1e-6 of it leaves room for summing 414 balls).
  const Eigen::Vector3d f = ball_force_sum(pipeline.source().ring().ball_states());
  EXPECT_NEAR(std::abs(f.x()), 6800.0, 1e-6 * 6800.0);
  EXPECT_NEAR(f.y(), 0.0, 1e-6 * 6800.0);
  EXPECT_NEAR(f.z(), 0.0, 1e-6 * 6800.0);
  // With the ring deformed, not the rigid ring's: the peak ball load differs from the rigid
  // ring's at the same rigid-body displacement by more than 1 %.
  const FlexibleStaticSolution eq = solve_flexible_static(FlexibleBearing(model), ct_load());
  const std::vector<BallState> rigid = model.ball_states(eq.coordinates.head<5>(), 0.0);
  double peak_flexible = 0.0, peak_rigid = 0.0;
  for (const BallState& b : pipeline.source().ring().ball_states()) peak_flexible = std::max(peak_flexible, b.load_N);
  for (const BallState& b : rigid) peak_rigid = std::max(peak_rigid, b.load_N);
  EXPECT_GT(std::abs(peak_flexible - peak_rigid), 0.01 * peak_rigid);

  Sink sink;
  for (int i = 0; i < 3; ++i) pipeline.run_chunk(sink);
  ASSERT_EQ(sink.ax.size(), 300u);
  ASSERT_EQ(sink.ball_indices.size(), 3u);  // at 100 Hz: samples 99, 199, 299
  // Sample 0 is the static equilibrium, then one FlexibleDynamics step per sample: the same
  // arithmetic, so the same doubles (the chunks hold floats); the ball loads handed out are
  // FlexibleBearing::ball_states at the sample.
  EXPECT_EQ(sink.ax[0], static_cast<float>(reference.current().accelerations[0]));
  std::size_t next_balls = 0;
  for (std::size_t i = 1; i < sink.ax.size(); ++i) {
    const FlexibleSample& s = reference.step();
    ASSERT_EQ(sink.ax[i], static_cast<float>(s.accelerations[0])) << "sample " << i;
    if (next_balls < sink.ball_indices.size() && sink.ball_indices[next_balls] == i) {
      const std::vector<BallState> expected = reference.bearing().ball_states(s.coordinates, s.phase);
      ASSERT_EQ(sink.balls[next_balls].size(), expected.size());
      for (std::size_t b = 0; b < expected.size(); ++b)
        ASSERT_EQ(sink.balls[next_balls][b].load_N, expected[b].load_N) << "sample " << i << " ball " << b;
      ++next_balls;
    }
  }
  EXPECT_EQ(next_balls, sink.ball_indices.size());
}

TEST(FlexiblePipeline, ADivergingFlexibleRingIsResetToItsStaticEquilibrium) {
  // One RK4 step per 2 kHz sample: the ring's modes on the balls (up to ~2 kHz) put omega h
  // far beyond RK4's stability limit of 2.8, so the state runs away; the source must hand out
  // the flexible ring's static equilibrium instead, finite, and go on.
  const BearingModel model(load_bearing_config(kFlexible));
  SampleSource source(
      make_ring_dynamics(model, ct_load(), test::kCtSpeedRadS, DynamicsOptions{2000.0, 1, true, IntegrationMethod::Rk4}));
  const FlexibleBearing bearing(model);
  int diverged = 0;
  for (int i = 0; i < 400 && diverged < 2; ++i) {
    const SampleSource::Sample s = source.next();
    ASSERT_TRUE(s.state->displacement.allFinite() && s.state->acceleration.allFinite());
    if (!s.diverged) continue;
    ++diverged;
    const FlexibleSample* full = source.ring().flexible_state();
    ASSERT_NE(full, nullptr);
    const FlexibleStaticSolution here = solve_flexible_static(bearing, ct_load(), full->phase);
    EXPECT_NEAR((full->coordinates - here.coordinates).norm(), 0.0, 1e-9 * here.coordinates.norm());
    EXPECT_EQ(s.state->velocity.norm(), 0.0);  // the rigid-body coordinates at rest
  }
  EXPECT_GE(diverged, 1);
}
