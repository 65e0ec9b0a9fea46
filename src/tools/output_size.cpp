#include "output_size.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <ros/serialization.h>
#include <std_msgs/String.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/ScenarioState.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "dataset_info_json.hpp"
#include "npy_file.hpp"

namespace bearing_sim::tool {
namespace {

// Decimal digits of an integer part (at least 1).
double integer_digits(double v) { return v < 10.0 ? 1.0 : std::floor(std::log10(v)) + 1.0; }

// rosbag 2.0 around each message: its record's header (op 8, conn 13, time 17 bytes, and the
// header's length, 4), the data's length (4), and its entry in the chunk's index (12).
constexpr double kBagBytesPerMessage = 4.0 + 38.0 + 4.0 + 12.0;
constexpr double kBagChunkBytes = 768.0 * 1024.0;  // rosbag closes a chunk at 768 KiB
// The version line and the 4096-byte bag header record.
constexpr double kBagHeaderBytes = 13.0 + 4096.0;

// A connection's record, written into the chunk that first uses it and again at the end:
// topic (twice), type, md5sum, message definition, and the allowance for the fields' names
// and lengths (and the dataset info's latching and caller id).
template <class M>
double connection_bytes(const std::string& topic) {
  return 2.0 * (2.0 * static_cast<double>(topic.size()) +
                static_cast<double>(std::strlen(ros::message_traits::datatype<M>())) + 32.0 +
                static_cast<double>(std::strlen(ros::message_traits::definition<M>())) + kBagConnectionAllowanceBytes);
}

template <class M>
double serialized_bytes(const M& m) {
  return static_cast<double>(ros::serialization::serializationLength(m));
}

// Messages of a SampleDivider at `rate_hz` over `samples` dynamics samples at
// `sample_rate_hz`: the first after one whole period.
double periodic_count(double samples, double rate_hz, double sample_rate_hz) {
  return std::floor(samples / std::max(1.0, std::round(sample_rate_hz / rate_hz)));
}

double spall_events(const Scenario& scenario) {
  return static_cast<double>(
      std::count_if(scenario.defect_events().begin(), scenario.defect_events().end(),
                    [](const ScenarioDefectEvent& e) { return e.kind == ScenarioDefectEvent::Kind::Spall; }));
}

std::size_t longest_phase_name(const Scenario& scenario) {
  std::size_t n = 0;
  for (const ScenarioPhase& p : scenario.phases()) n = std::max(n, p.name.size());
  return n;
}

}  // namespace

double time_series_csv_bytes(double rows, int values, double header_bytes) {
  return header_bytes + rows * (kTimeCsvFieldBytes + values * kScientificCsvFieldBytes + 1.0);
}

double npy_float_bytes(double rows, int columns) {
  return static_cast<double>(npy_header(static_cast<std::uint64_t>(rows), columns).size()) + rows * columns * 4.0;
}

double dataset_csv_bytes(double rows, double last_time_s) {
  const double header = std::strlen("sample,time_s,accel_x,accel_y,accel_z\n");
  const double sample = integer_digits(std::max(0.0, rows - 1.0));
  const double time = integer_digits(last_time_s) + 1.0 + 9.0;
  return header + rows * (sample + 1.0 + time + 3.0 * (1.0 + 15.0) + 1.0);
}

double dataset_sidecar_bytes(const runtime::DatasetInfo& info, const Scenario& scenario) {
  // The dataset info as written (indent 1) and the two channels' descriptions (~1 kB), then per
  // label (one a line, nlohmann's shortest round trip, up to 24 characters a number): time,
  // phase, speed, angle (~30 bytes each), the load's 5 numbers (~160), each spall's 9 fields
  // (~560).
  const double labels = std::floor(info.duration_s * info.label_rate_hz) + 1.0;
  const double per_label = 300.0 + static_cast<double>(longest_phase_name(scenario)) + 560.0 * spall_events(scenario);
  return static_cast<double>(dataset_info_json(info).dump(1).size()) + 2048.0 + labels * per_label;
}

double dataset_bag_bytes(const runtime::DatasetInfo& info, const runtime::GenerateSettings& settings,
                         const Scenario& scenario, int balls) {
  const double rate = info.sample_rate_hz;
  const double ideal = static_cast<double>(info.ideal_samples);
  const double measured = static_cast<double>(info.measured_samples);
  const double spalls = spall_events(scenario);
  DefectState spall;
  spall.surface = "outer_race";
  double messages = 0.0, connections = 0.0;

  // Vibration chunks: 8 float32 arrays; the sensor's chunks hold 1 / R of the dynamics' samples.
  VibrationChunk chunk;
  chunk.header.frame_id = info.frame_id;
  const double per_chunk = serialized_bytes(chunk) + kBagBytesPerMessage;
  const double ideal_chunk = static_cast<double>(settings.chunk_samples);
  const double measured_chunk = info.sensor_file.empty()
                                    ? ideal_chunk
                                    : std::max(1.0, std::floor(ideal_chunk / std::max(1, info.decimation_ratio)));
  messages += std::ceil(ideal / ideal_chunk) * per_chunk + 32.0 * ideal;
  messages += std::ceil(measured / measured_chunk) * per_chunk + 32.0 * measured;
  connections += 2.0 * connection_bytes<VibrationChunk>("/bearing/vibration_ideal");

  VibrationLevel level;
  level.header.frame_id = info.frame_id;
  messages += periodic_count(ideal, settings.level_rate_hz, rate) * (serialized_bytes(level) + kBagBytesPerMessage);
  connections += connection_bytes<VibrationLevel>("/bearing/vibration_level");

  BallLoads loads;
  loads.header.frame_id = info.bearing_frame_id;
  for (auto* v : {&loads.azimuth, &loads.load, &loads.contact_angle, &loads.deflection})
    v->assign(static_cast<std::size_t>(balls), 0.0f);
  messages +=
      periodic_count(ideal, settings.ball_loads_rate_hz, rate) * (serialized_bytes(loads) + kBagBytesPerMessage);
  connections += connection_bytes<BallLoads>("/bearing/ball_loads");

  if (settings.health_rate_hz > 0.0) {
    BearingHealth health;
    health.header.frame_id = info.frame_id;
    health.signal = info.sensor_file.empty() ? "ideal ring acceleration" : "sensor: " + info.sensor_name;
    const double per_report = serialized_bytes(health) + kHealthTextBytes + spalls * serialized_bytes(spall);
    messages += periodic_count(ideal, settings.health_rate_hz, rate) * (per_report + kBagBytesPerMessage);
    connections += connection_bytes<BearingHealth>("/bearing/health");
  }

  ScenarioState label;
  label.header.frame_id = info.bearing_frame_id;
  label.scenario = info.scenario;
  label.bearing = info.bearing_name;
  label.phase.assign(longest_phase_name(scenario), 'x');
  const double per_label = serialized_bytes(label) + spalls * serialized_bytes(spall);
  messages += (std::floor(info.duration_s * info.label_rate_hz) + 1.0) * (per_label + kBagBytesPerMessage);
  connections += connection_bytes<ScenarioState>("/bearing/scenario_state");

  std_msgs::String description;
  description.data = dataset_info_json(info).dump(2);
  messages += serialized_bytes(description) + kBagBytesPerMessage;
  connections += connection_bytes<std_msgs::String>("/bearing/dataset_info");

  return kBagHeaderBytes + connections + messages + std::ceil(messages / kBagChunkBytes) * kBagChunkAllowanceBytes;
}

double dataset_output_bytes(const runtime::DatasetInfo& info, const runtime::GenerateSettings& settings,
                            const Scenario& scenario, int balls, const std::vector<std::string>& formats) {
  double bytes = 0.0;
  for (const std::string& f : formats) {
    if (f == "bag") {
      bytes += dataset_bag_bytes(info, settings, scenario, balls);
    } else {
      const double measured = static_cast<double>(info.measured_samples);
      const double ideal = static_cast<double>(info.ideal_samples);
      bytes += dataset_sidecar_bytes(info, scenario);
      bytes += f == "npy" ? npy_float_bytes(measured, 3) + npy_float_bytes(ideal, 3)
                          : dataset_csv_bytes(measured, info.duration_s) + dataset_csv_bytes(ideal, info.duration_s);
    }
  }
  return bytes;
}

}  // namespace bearing_sim::tool
