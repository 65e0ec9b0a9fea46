#pragma once
// What `bearing_tool generate` produces for one scenario run, handed to the writers of
// the output formats (rosbag, NPY/CSV + JSON). ROS-free: the bag writer converts.
#include <cstdint>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/chunk_assembler.hpp"
#include "bearing_sim/runtime/health_monitor.hpp"

namespace bearing_sim::runtime {

// Fixed facts of a run (the bag's dataset_info, the JSON sidecar's header).
struct DatasetInfo {
  std::string scenario, description, scenario_file;
  std::string bearing_name, bearing_file;
  std::string sensor_name, sensor_file;  // empty: no sensor, `vibration` is the ideal acceleration
  std::string sensor_unit;               // m_s2 or V (of `vibration`)
  std::uint64_t seed = 0;
  double duration_s = 0.0;
  double sample_rate_hz = 0.0;      // dynamics: vibration_ideal
  double measured_rate_hz = 0.0;    // vibration: the sensor's output rate (or the dynamics')
  int decimation_ratio = 1;         // sensor sample k is dynamics sample (k + 1) R - 1
  std::uint64_t ideal_samples = 0;  // duration_s * sample_rate_hz
  std::uint64_t measured_samples = 0;
  double label_rate_hz = 0.0;  // scenario_state / the sidecar's label time line
  std::string frame_id, bearing_frame_id;
  std::vector<ScenarioPhase> phases;
  // The SIMD target the kernels ran on: the same scenario and seed give the same bytes on
  // CPUs that run the same target; across targets the samples differ in their rounding.
  std::string simd_target;
};

// The labels of one instant (dynamics sample `index`).
struct LabelState {
  std::uint64_t index = 0;
  double time_s = 0.0;
  ScenarioInputs inputs;
  std::vector<runtime::DefectNow> defects;  // sized by the scenario's growth law at time_s
};

class DatasetSink {
 public:
  virtual ~DatasetSink() = default;
  virtual void begin(const DatasetInfo& info) = 0;
  // Dynamics-rate chunk (`vibration_ideal`), numbered in dynamics samples.
  virtual void ideal_chunk(const runtime::SampleChunk& chunk) = 0;
  // Measured chunk (`vibration`), numbered in measured samples; without a sensor the
  // same chunk as ideal_chunk.
  virtual void measured_chunk(const runtime::SampleChunk& chunk) = 0;
  virtual void level(std::uint64_t index, double accel_rms, double window_s) {
    (void)index, (void)accel_rms, (void)window_s;
  }
  virtual bool wants_ball_loads() const { return false; }
  virtual void ball_loads(std::uint64_t index, const std::vector<BallState>& balls, int rows, int balls_per_row,
                          double cage_angle_rad) {
    (void)index, (void)balls, (void)rows, (void)balls_per_row, (void)cage_angle_rad;
  }
  virtual bool wants_health() const { return false; }
  virtual void health(const runtime::HealthReport& report) { (void)report; }
  virtual void label(const LabelState& state) = 0;
  // Flushes and closes; throws on an I/O error.
  virtual void end() = 0;
};

}  // namespace bearing_sim::runtime
