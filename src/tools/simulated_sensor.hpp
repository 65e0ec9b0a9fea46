#pragma once
// bearing_tool simulate --sensor: the run's samples through a virtual triaxial accelerometer
// (the node's TriaxialSensor, docs/sensor.md), with streamed statistics of its output over
// the summary's window and an optional CSV of its samples. Nothing is stored per sample,
// so a long run costs no memory.
#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/signal_statistics.hpp"
#include "bearing_sim/runtime/triaxial_sensor.hpp"

namespace bearing_sim::tool {

class SimulatedSensor {
 public:
  // sensor_file: the accelerometer file (`sensor:` mapping); rate_hz: the run's sample rate;
  // window_start: the index of the run's sample from which the statistics count (the
  // summary's window).
  SimulatedSensor(const std::string& sensor_file, double rate_hz, std::size_t window_start);
  ~SimulatedSensor();
  SimulatedSensor(const SimulatedSensor&) = delete;
  SimulatedSensor& operator=(const SimulatedSensor&) = delete;

  // Writes every sensor sample from now on to the CSV file `csv` (a header line first).
  void write_csv(const std::string& csv);
  // The CSV's size after `input_samples` of the run, at most (output_size.hpp).
  double csv_bytes(double input_samples, double rate_hz) const;
  void push(const DynamicSample& sample);
  // Closes the CSV (throws if writing it failed).
  void finish();
  nlohmann::json to_json() const;
  const std::string& unit() const { return unit_; }
  const std::array<StreamedStatistics, 3>& statistics() const { return stats_; }
  double output_rate_hz() const { return sensor_->output_rate_hz(); }

 private:
  std::string csv_header() const;

  std::string file_, csv_path_, unit_;
  std::unique_ptr<runtime::TriaxialSensor> sensor_;
  std::size_t window_start_, inputs_ = 0;
  std::array<StreamedStatistics, 3> stats_;
  std::FILE* csv_ = nullptr;
  std::size_t samples_ = 0;
};

}  // namespace bearing_sim::tool
