#include "dataset_bag_writer.hpp"

#include <cmath>
#include <mutex>

#include <rosbag/bag.h>
#include <std_msgs/String.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/ScenarioState.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/core/vibration_level.hpp"
#include "bearing_sim/ros/message_conversion.hpp"
#include "dataset_info_json.hpp"

namespace bearing_sim::tool {
namespace {

// Topics of the live node (namespace /bearing) and of the scenario player.
const char* const kVibration = "/bearing/vibration";
const char* const kVibrationIdeal = "/bearing/vibration_ideal";
const char* const kLevel = "/bearing/vibration_level";
const char* const kBallLoads = "/bearing/ball_loads";
const char* const kHealth = "/bearing/health";
const char* const kScenarioState = "/bearing/scenario_state";
const char* const kDatasetInfo = "/bearing/dataset_info";

ros::Time from_ns(std::int64_t ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(ns));
  return t;
}

}  // namespace

DatasetBagWriter::DatasetBagWriter(std::string path) : path_(std::move(path)) {}
DatasetBagWriter::~DatasetBagWriter() = default;

namespace {
// Simulated time of dynamics sample `index`, to the nanosecond (as the live node).
ros::Time stamp_of(std::uint64_t index, double rate_hz) {
  return from_ns(static_cast<std::int64_t>(std::llround(static_cast<long double>(index) * 1.0e9L / rate_hz)));
}
// rosbag refuses a record time below ros::TIME_MIN (1 ns): messages of t = 0 go at 1 ns.
ros::Time record_time(const ros::Time& stamp) { return std::max(stamp, ros::TIME_MIN); }
}  // namespace

void DatasetBagWriter::begin(const runtime::DatasetInfo& info) {
  info_ = info;
  {
    // A rosbag::Bag loads its encryption plugins through pluginlib (a package crawl, ~30 ms)
    // when constructed: one thread at a time.
    static std::mutex construction;
    std::lock_guard<std::mutex> lock(construction);
    bag_ = std::make_unique<rosbag::Bag>();
    bag_->open(path_, rosbag::bagmode::Write);  // throws rosbag::BagException
  }
  std_msgs::String description;
  description.data = dataset_info_json(info).dump(2);
  // Marked latched, so that a player of the bag hands it to late subscribers.
  // rosbag stores a given connection header as it is: it must carry the type fields too.
  auto header = boost::make_shared<ros::M_string>();
  (*header)["topic"] = kDatasetInfo;
  (*header)["type"] = ros::message_traits::datatype(description);
  (*header)["md5sum"] = ros::message_traits::md5sum(description);
  (*header)["message_definition"] = ros::message_traits::definition(description);
  (*header)["latching"] = "1";
  (*header)["callerid"] = "/bearing_tool_generate";
  bag_->write(kDatasetInfo, ros::TIME_MIN, description, header);
}

void DatasetBagWriter::ideal_chunk(const runtime::SampleChunk& chunk) {
  VibrationChunk msg;
  const ros::Time stamp = stamp_of(chunk.first_sample, info_.sample_rate_hz);
  ros_node::fill_vibration_chunk(runtime::SampleChunk(chunk), stamp, info_.frame_id, info_.sample_rate_hz, &msg);
  bag_->write(kVibrationIdeal, record_time(stamp), msg);
}

void DatasetBagWriter::measured_chunk(const runtime::SampleChunk& chunk) {
  VibrationChunk msg;
  // Sensor sample k is the output at dynamics sample (k + 1) R - 1 (docs/sensor.md).
  const std::uint64_t r = static_cast<std::uint64_t>(info_.decimation_ratio);
  const ros::Time stamp = stamp_of((chunk.first_sample + 1) * r - 1, info_.sample_rate_hz);
  ros_node::fill_vibration_chunk(runtime::SampleChunk(chunk), stamp, info_.frame_id, info_.measured_rate_hz, &msg);
  bag_->write(kVibration, record_time(stamp), msg);
}

void DatasetBagWriter::level(std::uint64_t index, double accel_rms, double window_s) {
  VibrationLevel msg;
  msg.header.stamp = stamp_of(index, info_.sample_rate_hz);
  msg.header.frame_id = info_.frame_id;
  msg.accel_rms = accel_rms;
  msg.level_db = vibration_level_db(accel_rms);
  msg.window_s = window_s;
  bag_->write(kLevel, record_time(msg.header.stamp), msg);
}

void DatasetBagWriter::ball_loads(std::uint64_t index, const std::vector<BallState>& balls, int rows, int balls_per_row,
                                  double cage_angle_rad) {
  BallLoads msg;
  msg.header.stamp = stamp_of(index, info_.sample_rate_hz);
  msg.header.frame_id = info_.bearing_frame_id;
  ros_node::fill_ball_loads(balls, rows, balls_per_row, cage_angle_rad, &msg);
  bag_->write(kBallLoads, record_time(msg.header.stamp), msg);
}

void DatasetBagWriter::health(const runtime::HealthReport& report) {
  BearingHealth msg;
  msg.header.stamp = from_ns(static_cast<std::int64_t>(std::llround(report.end_time_s * 1e9)));
  msg.header.frame_id = info_.frame_id;
  const std::string signal = info_.sensor_file.empty() ? "ideal ring acceleration" : "sensor: " + info_.sensor_name;
  ros_node::fill_bearing_health(report, signal, info_.measured_rate_hz, &msg);
  bag_->write(kHealth, record_time(msg.header.stamp), msg);
}

void DatasetBagWriter::label(const runtime::LabelState& state) {
  ScenarioState msg;
  msg.header.stamp = stamp_of(state.index, info_.sample_rate_hz);
  msg.header.frame_id = info_.bearing_frame_id;
  ros_node::fill_scenario_state(info_.scenario, info_.bearing_name, info_.seed, state.time_s, state.inputs,
                                state.defects, &msg);
  bag_->write(kScenarioState, record_time(msg.header.stamp), msg);
}

void DatasetBagWriter::end() {
  if (bag_) bag_->close();
}

}  // namespace bearing_sim::tool
