// Live recording: ct_gantry.launch record:=true in real time. After ~record_s the test stops
// the recorder with SIGINT, as roslaunch and Ctrl-C do, waits for rosbag to close the bag
// (.bag.active renamed to .bag) and reads it back with rosbag::View: no sample lost, every
// topic at its rate.
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <tf2_msgs/TFMessage.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "node_pid.hpp"

namespace fs = std::filesystem;

namespace {

constexpr double kStampTolerance_s = 1e-6;  // stamps are simulated time, rounded to 1 ns

bool wait_wall(const std::function<bool()>& pred, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::WallTime::now() < end) {
    if (pred()) return true;
    ros::WallDuration(0.05).sleep();
  }
  return pred();
}

template <typename M>
std::vector<std::pair<ros::Time, typename M::ConstPtr>> read_topic(const rosbag::Bag& bag, const std::string& topic) {
  std::vector<std::pair<ros::Time, typename M::ConstPtr>> out;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic))) {
    typename M::ConstPtr msg = m.instantiate<M>();
    if (msg) out.emplace_back(m.getTime(), msg);
  }
  return out;
}

// Every interval between consecutive stamps, in seconds.
template <typename M>
std::vector<double> stamp_intervals(const std::vector<std::pair<ros::Time, typename M::ConstPtr>>& msgs) {
  std::vector<double> d;
  for (std::size_t i = 1; i < msgs.size(); ++i)
    d.push_back((msgs[i].second->header.stamp - msgs[i - 1].second->header.stamp).toSec());
  return d;
}

class LiveRecording : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle pnh("~");
    pnh.getParam("bag_path", bag_path_);
    pnh.param("record_s", record_s_, 12.0);
    const std::string active = bag_path_ + ".active";
    ASSERT_TRUE(wait_wall([&] { return fs::exists(active); }, 30.0)) << "no " << active;
    ros::WallDuration(record_s_).sleep();
    const int pid = node_test::node_pid("/bearing/recorder");
    ASSERT_GT(pid, 0) << "cannot find the recorder's PID";
    ASSERT_EQ(::kill(pid, SIGINT), 0);
    ASSERT_TRUE(wait_wall([&] { return fs::exists(bag_path_) && !fs::exists(active); }, 30.0))
        << "rosbag record did not close " << bag_path_;
    bag_.open(bag_path_, rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag_)) {
      if (first_time_.isZero()) first_time_ = m.getTime();
      last_time_ = std::max(last_time_, m.getTime());
    }
    span_s_ = (last_time_ - first_time_).toSec();
    const double mb = static_cast<double>(fs::file_size(bag_path_)) / 1e6;
    ROS_INFO("bag %s: %.1f s recorded, %.2f MB", bag_path_.c_str(), span_s_, mb);
    RecordProperty("recorded_s", std::to_string(span_s_));
    RecordProperty("bag_MB_per_minute", std::to_string(mb * 60.0 / span_s_));
  }
  static void TearDownTestSuite() {
    bag_.close();
    std::error_code ec;
    fs::remove(bag_path_, ec);
  }

  static std::string bag_path_;
  static double record_s_;
  static rosbag::Bag bag_;
  static ros::Time first_time_, last_time_;
  static double span_s_;
};
std::string LiveRecording::bag_path_;
double LiveRecording::record_s_ = 0.0;
rosbag::Bag LiveRecording::bag_;
ros::Time LiveRecording::first_time_, LiveRecording::last_time_;
double LiveRecording::span_s_ = 0.0;

TEST_F(LiveRecording, BagCoversTheRecordingTime) {
  // From the recorder's start (file created) to SIGINT, minus its subscription set-up.
  EXPECT_GT(span_s_, record_s_ - 2.0);
  EXPECT_LT(span_s_, record_s_ + 3.0);
}

TEST_F(LiveRecording, VibrationHasNoGap) {
  const auto chunks = read_topic<bearing_sim::VibrationChunk>(bag_, "/bearing/vibration");
  ASSERT_GT(chunks.size(), 100u);
  const auto& first = *chunks.front().second;
  const double rate = first.sample_rate;
  EXPECT_EQ(rate, 10000.0);  // the CT sensor's output rate
  std::uint64_t next = first.first_sample;
  std::size_t gaps = 0, bad_stamps = 0, bad_sizes = 0;
  for (const auto& [t, c] : chunks) {
    if (c->first_sample != next) ++gaps;
    const double expected =
        first.header.stamp.toSec() + static_cast<double>(c->first_sample - first.first_sample) / rate;
    if (std::abs(c->header.stamp.toSec() - expected) > kStampTolerance_s) ++bad_stamps;
    const std::size_t n = c->accel_x.size();
    if (n == 0 || c->accel_y.size() != n || c->accel_z.size() != n || c->displacement_x.size() != n ||
        c->displacement_y.size() != n || c->displacement_z.size() != n || c->tilt_x.size() != n ||
        c->tilt_y.size() != n)
      ++bad_sizes;
    next = c->first_sample + n;
  }
  EXPECT_EQ(gaps, 0u) << "first_sample not contiguous";
  EXPECT_EQ(bad_stamps, 0u) << "stamp != first stamp + (first_sample - first) / rate";
  EXPECT_EQ(bad_sizes, 0u);
  // Samples against the wall-clock time the bag covers: the node runs in real time, so the
  // arrival times (bag receive time) advance like the stamps. Arrival minus stamp, as a
  // median over the first and over the last 50 chunks, drifts only by scheduling delays;
  // 0.5 s is a generous bound for those on a loaded machine, while a node that stalled,
  // ran free or lost chunks over the recording misses it by seconds.
  auto median_delay = [&](std::size_t from, std::size_t to) {
    std::vector<double> d;
    for (std::size_t i = from; i < to; ++i) d.push_back((chunks[i].first - chunks[i].second->header.stamp).toSec());
    std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
    return d[d.size() / 2];
  };
  const std::size_t n_chunks = chunks.size();
  const double drift_s = median_delay(n_chunks - 50, n_chunks) - median_delay(0, 50);
  const std::uint64_t samples = next - first.first_sample;
  const double covered_s = (chunks.back().second->header.stamp - first.header.stamp).toSec() + drift_s +
                           static_cast<double>(chunks.back().second->accel_x.size()) / rate;
  constexpr double kGenerousDriftS = 0.5;
  EXPECT_NEAR(static_cast<double>(samples), covered_s * rate, kGenerousDriftS * rate)
      << samples << " samples in " << covered_s << " s of wall-clock time";
  RecordProperty("drift_ms", std::to_string(drift_s * 1e3));
  EXPECT_GT(static_cast<double>(samples), (record_s_ - 2.0) * rate);
  RecordProperty("samples", std::to_string(samples));
  RecordProperty("covered_s", std::to_string(covered_s));
}

TEST_F(LiveRecording, LevelEveryTenthOfASecond) {
  const auto msgs = read_topic<bearing_sim::VibrationLevel>(bag_, "/bearing/vibration_level");
  ASSERT_GT(msgs.size(), 2u);
  for (double d : stamp_intervals<bearing_sim::VibrationLevel>(msgs)) EXPECT_NEAR(d, 0.1, kStampTolerance_s);
  EXPECT_NEAR(static_cast<double>(msgs.size()), 10.0 * span_s_, 3.0);
  for (const auto& [t, m] : msgs) EXPECT_TRUE(std::isfinite(m->level_db));
}

TEST_F(LiveRecording, BallLoadsAtThirtyHertz) {
  const auto msgs = read_topic<bearing_sim::BallLoads>(bag_, "/bearing/ball_loads");
  ASSERT_GT(msgs.size(), 2u);
  // Produced when the sample index crosses k * 10000 / 30: 333 or 334 samples apart.
  for (double d : stamp_intervals<bearing_sim::BallLoads>(msgs)) {
    EXPECT_GT(d, 0.0333 - kStampTolerance_s);
    EXPECT_LT(d, 0.0334 + kStampTolerance_s);
  }
  EXPECT_NEAR(static_cast<double>(msgs.size()), 30.0 * span_s_, 3.0);
  for (const auto& [t, m] : msgs) {
    EXPECT_EQ(m->load.size(), 414u);
    EXPECT_EQ(m->azimuth.size(), 414u);
  }
}

TEST_F(LiveRecording, HealthEverySecond) {
  const auto msgs = read_topic<bearing_sim::BearingHealth>(bag_, "/bearing/health");
  ASSERT_GT(msgs.size(), 2u);
  for (double d : stamp_intervals<bearing_sim::BearingHealth>(msgs)) EXPECT_NEAR(d, 1.0, kStampTolerance_s);
  // The first analysis needs a full 2 s window, possibly before the recorder started.
  EXPECT_GE(static_cast<double>(msgs.size()), span_s_ - 3.0);
  EXPECT_LE(static_cast<double>(msgs.size()), span_s_ + 1.0);
}

TEST_F(LiveRecording, DiagnosticsAndTransforms) {
  const auto diag = read_topic<diagnostic_msgs::DiagnosticArray>(bag_, "/diagnostics");
  EXPECT_GE(static_cast<double>(diag.size()), span_s_ - 2.0);  // 1 Hz
  std::set<std::string> statuses;
  for (const auto& [t, m] : diag)
    for (const auto& s : m->status) statuses.insert(s.name);
  EXPECT_TRUE(std::any_of(statuses.begin(), statuses.end(),
                          [](const std::string& n) { return n.find("Real time") != std::string::npos; }));

  // bearing_viz_node: rotating_ring and cage at 30 Hz (wall timer), gantry -> bearing latched.
  std::map<std::string, int> children;
  for (const auto& [t, m] : read_topic<tf2_msgs::TFMessage>(bag_, "/tf"))
    for (const auto& tr : m->transforms) ++children[tr.child_frame_id];
  EXPECT_GE(children["rotating_ring"], static_cast<int>(0.8 * 30.0 * span_s_));
  EXPECT_GE(children["cage"], static_cast<int>(0.8 * 30.0 * span_s_));
  bool static_bearing = false;
  for (const auto& [t, m] : read_topic<tf2_msgs::TFMessage>(bag_, "/tf_static"))
    for (const auto& tr : m->transforms)
      static_bearing |= tr.header.frame_id == "gantry" && tr.child_frame_id == "bearing";
  EXPECT_TRUE(static_bearing);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_live_recording");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
