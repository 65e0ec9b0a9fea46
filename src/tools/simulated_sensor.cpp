#include "simulated_sensor.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "output_size.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {

SimulatedSensor::SimulatedSensor(const std::string& sensor_file, double rate_hz, std::size_t window_start)
    : file_(sensor_file), window_start_(window_start) {
  const AccelerometerConfig config = load_accelerometer_config(sensor_file);
  try {
    sensor_ = std::make_unique<runtime::TriaxialSensor>(config, rate_hz);
  } catch (const InvalidInputError& e) {
    throw InputError("--sensor '" + sensor_file + "' at --rate " + general(rate_hz, 6) + " Hz: " + e.what());
  }
  unit_ = config.output_unit == SensorOutputUnit::Voltage_V ? "V" : "m_s2";
}

std::string SimulatedSensor::csv_header() const { return "time_s,x_" + unit_ + ",y_" + unit_ + ",z_" + unit_ + "\n"; }

void SimulatedSensor::write_csv(const std::string& csv) {
  csv_path_ = csv;
  csv_ = std::fopen(csv_path_.c_str(), "w");
  if (!csv_) throw InputError("--sensor-csv: cannot open '" + csv_path_ + "' for writing: " + std::strerror(errno));
  std::fputs(csv_header().c_str(), csv_);
}

double SimulatedSensor::csv_bytes(double input_samples, double rate_hz) const {
  const double rows = std::ceil(input_samples * sensor_->output_rate_hz() / rate_hz);
  return time_series_csv_bytes(rows, 3, static_cast<double>(csv_header().size()));
}

SimulatedSensor::~SimulatedSensor() {
  if (csv_) std::fclose(csv_);
}

void SimulatedSensor::push(const DynamicSample& sample) {
  Eigen::Vector3d measured;
  const std::size_t input = inputs_++;
  if (!sensor_->push(sample, &measured)) return;
  ++samples_;
  // A sensor sample is stamped with the dynamics sample that completed it.
  if (input >= window_start_)
    for (int axis = 0; axis < 3; ++axis) stats_[axis].add(measured[axis]);
  if (csv_) std::fprintf(csv_, "%.12g,%.10e,%.10e,%.10e\n", sample.time_s, measured[0], measured[1], measured[2]);
}

void SimulatedSensor::finish() {
  if (!csv_) return;
  const bool failed = std::ferror(csv_) != 0;
  const bool close_failed = std::fclose(csv_) != 0;
  csv_ = nullptr;
  if (failed || close_failed) throw std::runtime_error("--sensor-csv: error writing '" + csv_path_ + "'");
}

nlohmann::json SimulatedSensor::to_json() const {
  nlohmann::json rms = nlohmann::json::array(), crest = nlohmann::json::array(), kurt = nlohmann::json::array();
  for (const StreamedStatistics& axis : stats_) {
    const SignalStatistics s = axis.statistics();
    rms.push_back(s.rms);
    crest.push_back(s.crest_factor);
    kurt.push_back(s.kurtosis);
  }
  return {{"name", sensor_->config().name},
          {"file", file_},
          {"unit", unit_},
          {"output_rate_hz", sensor_->output_rate_hz()},
          {"samples", samples_},
          {"window_samples", stats_[0].samples()},
          {"rms", rms},
          {"crest_factor", crest},
          {"kurtosis", kurt},
          {"clipped_samples", sensor_->clipped_sample_count()},
          {"csv", csv_path_.empty() ? nlohmann::json(nullptr) : nlohmann::json(csv_path_)}};
}

}  // namespace bearing_sim::tool
