#pragma once
// One scenario run (`bearing_tool generate`, the Python module): drives the dynamics from the scenario
// (speed, load, defect events) through the live node's per-sample pipeline
// (SamplePipeline: chunks, sensor, level, dividers, health hand-over) and hands
// everything to the dataset sinks. Faster than real time, no ROS, deterministic for a
// seed: every random source (imperfections, cage slip, sensor noise) is seeded from it.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "bearing_sim/runtime/dataset_sink.hpp"

namespace bearing_sim::runtime {

struct GenerateSettings {
  std::optional<std::uint64_t> seed;                    // overrides the scenario's
  std::optional<double> duration_s;                     // overrides the scenario's
  std::optional<double> ring_temperature_difference_K;  // a constant instead of the scenario's time line
  std::size_t chunk_samples = 100;                      // per vibration_ideal chunk, as the live node
  double level_rate_hz = 10.0;
  double level_window_s = 1.0;
  double ball_loads_rate_hz = 10.0;
  double label_rate_hz = 10.0;
  double health_rate_hz = 1.0;  // 0: no health
  double health_window_s = 2.0;
};

struct RunStats {
  double simulated_s = 0.0;
  double cpu_s = 0.0;         // CPU time of the running thread, all of the run
  double sink_cpu_s = 0.0;    // of that, in the sinks (message conversion, writing, ball loads)
  double health_cpu_s = 0.0;  // of that, in the health analysis (condition indicators, lives)
  std::uint64_t ideal_samples = 0, measured_samples = 0, divergences = 0;
  double realtime_factor_per_core() const { return cpu_s > 0.0 ? simulated_s / cpu_s : 0.0; }
};

class ScenarioSimulation {
 public:
  // Loads the bearing and sensor of the scenario; throws ConfigError / InvalidInputError.
  ScenarioSimulation(Scenario scenario, const std::string& scenario_file, GenerateSettings settings);

  const DatasetInfo& info() const { return info_; }
  const Scenario& scenario() const { return scenario_; }

  // Runs to the end. `progress` is called after every chunk with the simulated time.
  RunStats run(const std::vector<DatasetSink*>& sinks, const std::function<void(double)>& progress = {});

 private:
  Scenario scenario_;
  GenerateSettings settings_;
  DatasetInfo info_;
  std::unique_ptr<BearingModel> model_;
  std::optional<AccelerometerConfig> sensor_config_;
  std::uint64_t label_period_ = 1;  // dynamics samples between labels
};

// The labels of a scenario at dynamics sample `index` (time index / rate).
LabelState scenario_label(const Scenario& scenario, std::uint64_t index, double sample_rate_hz);

}  // namespace bearing_sim::runtime
