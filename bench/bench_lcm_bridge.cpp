// Cost of lcm_bridge's work per message: a ROS chunk converted to the LCM type and encoded
// (what a ROS callback does), and the same handed to an in-process LCM (memq://, what the
// publisher thread does minus the socket or file). Chunk sizes: 100 samples (the node's
// default at 10 kHz) and 10000.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "bearing_sim/ros/lcm_conversion.hpp"

namespace {

bearing_sim::VibrationChunk chunk(std::size_t n) {
  bearing_sim::VibrationChunk c;
  c.header.stamp.sec = 12;
  c.header.frame_id = "bearing_outer_ring";
  c.sample_rate = 10000.0;
  for (auto* a : {&c.accel_x, &c.accel_y, &c.accel_z, &c.displacement_x, &c.displacement_y, &c.displacement_z,
                  &c.tilt_x, &c.tilt_y})
    for (std::size_t i = 0; i < n; ++i) a->push_back(1e-3f * static_cast<float>(i));
  return c;
}

void convert_and_encode(benchmark::State& state) {
  const bearing_sim::VibrationChunk ros = chunk(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    std::vector<std::uint8_t> bytes = bearing_sim::ros_node::encode_lcm(bearing_sim::ros_node::to_lcm(ros));
    benchmark::DoNotOptimize(bytes.data());
  }
  state.counters["chunks_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(convert_and_encode)->Arg(100)->Arg(10000);

void convert_encode_publish_memq(benchmark::State& state) {
  const bearing_sim::VibrationChunk ros = chunk(static_cast<std::size_t>(state.range(0)));
  lcm::LCM lcm("memq://");
  for (auto _ : state) {
    const std::vector<std::uint8_t> bytes = bearing_sim::ros_node::encode_lcm(bearing_sim::ros_node::to_lcm(ros));
    lcm.publish("BEARING_VIBRATION", bytes.data(), static_cast<unsigned int>(bytes.size()));
    lcm.handleTimeout(0);  // memq keeps what nobody handles
  }
  state.counters["chunks_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(convert_encode_publish_memq)->Arg(100)->Arg(10000);

}  // namespace

BENCHMARK_MAIN();
