// bearing_sim_node as fast as possible with lcm_bridge writing an LCM log (lcm_bridge.test):
// every message this node receives on ROS must be in the log, field by field and sample by
// sample bit-exact; the log's chunks must be contiguous (the bridge lost none); the log
// must hold exactly as many level, health and ball-load messages over the same stamps.
//
// This node subscribes once the bridge has logged every channel. The node and the bridge
// keep running while the log is read, so the log is read only up to the messages received
// here: it is re-read until it holds the last of them (the bridge's stdio buffer reaches
// the file as more data follows).
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <lcm/lcm-cpp.hpp>

#include "lcm_test_support.hpp"

using lcm_test::expect_equal;

namespace {

struct RosSide {
  std::mutex mutex;
  bool frozen = false;  // stop recording: the comparison set is fixed
  std::vector<bearing_sim::VibrationChunk::ConstPtr> vibration, ideal;
  std::vector<bearing_sim::VibrationLevel::ConstPtr> levels;
  std::vector<bearing_sim::BallLoads::ConstPtr> ball_loads;
  std::vector<bearing_sim::BearingHealth::ConstPtr> health;
  std::vector<ros::Subscriber> subscribers;

  template <class M>
  void subscribe(ros::NodeHandle& nh, const std::string& topic, std::vector<typename M::ConstPtr>* out,
                 std::uint32_t queue) {
    subscribers.push_back(nh.subscribe<M>(
        topic, queue,
        [this, out](const typename M::ConstPtr& msg) {
          std::lock_guard<std::mutex> lock(mutex);
          if (!frozen) out->push_back(msg);
        },
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay()));
  }
};

struct LogSide {
  std::vector<bearing_sim_lcm::vibration_chunk_t> vibration, ideal;  // in log order
  std::vector<bearing_sim_lcm::vibration_level_t> levels;
  std::vector<bearing_sim_lcm::ball_loads_t> ball_loads;
  std::vector<bearing_sim_lcm::bearing_health_t> health;
  std::map<std::string, std::size_t> channels;
  std::size_t undecodable = 0;
};

template <class T>
void decode_into(const lcm::LogEvent& e, std::vector<T>* out, std::size_t* undecodable) {
  T msg;
  if (msg.decode(e.data, 0, e.datalen) != e.datalen) {
    ++*undecodable;
    return;
  }
  out->push_back(std::move(msg));
}

// Every complete event of the log so far (an event still being written ends the read).
LogSide read_log(const std::string& path) {
  LogSide log;
  lcm::LogFile file(path, "r");
  if (!file.good()) return log;
  for (const lcm::LogEvent* e = file.readNextEvent(); e != nullptr; e = file.readNextEvent()) {
    ++log.channels[e->channel];
    if (e->channel == "BEARING_VIBRATION") decode_into(*e, &log.vibration, &log.undecodable);
    else if (e->channel == "BEARING_VIBRATION_IDEAL") decode_into(*e, &log.ideal, &log.undecodable);
    else if (e->channel == "BEARING_VIBRATION_LEVEL") decode_into(*e, &log.levels, &log.undecodable);
    else if (e->channel == "BEARING_BALL_LOADS") decode_into(*e, &log.ball_loads, &log.undecodable);
    else if (e->channel == "BEARING_HEALTH") decode_into(*e, &log.health, &log.undecodable);
  }
  return log;
}

std::int64_t stamp_ns(const ros::Time& t) { return static_cast<std::int64_t>(t.toNSec()); }
std::int64_t stamp_ns(const bearing_sim_lcm::header_t& h) { return h.stamp_sec * 1000000000LL + h.stamp_nsec; }

// The log holds a message at least as late as the last one received on ROS.
template <class Ros, class Lcm>
bool caught_up(const std::vector<Ros>& ros, const std::vector<Lcm>& log) {
  if (ros.empty()) return true;
  const std::int64_t last = stamp_ns(ros.back()->header.stamp);
  for (auto it = log.rbegin(); it != log.rend(); ++it)
    if (stamp_ns(it->header) >= last) return true;
  return false;
}

// Every field of the ROS message in the LCM one, header.seq apart: roscpp renumbers seq in
// each serialised copy (its own count of serialised publishes), while a bridge in the
// simulation's nodelet manager gets the message itself. So seq is checked as a constant
// offset per topic (0 for a standalone bridge): none skipped, repeated or reordered.
template <class Ros, class Lcm>
void expect_equal_but_seq(const Ros& ros, const Lcm& lcm, std::set<std::int64_t>* seq_offsets) {
  Ros copy = ros;
  seq_offsets->insert(lcm.header.seq - static_cast<std::int64_t>(copy.header.seq));
  copy.header.seq = static_cast<std::uint32_t>(lcm.header.seq);
  expect_equal(copy, lcm);
}

// Chunks: the log's are contiguous, and every chunk received on ROS is in it, identical.
void compare_chunks(const char* what, const std::vector<bearing_sim::VibrationChunk::ConstPtr>& ros,
                    const std::vector<bearing_sim_lcm::vibration_chunk_t>& log) {
  SCOPED_TRACE(what);
  ASSERT_FALSE(log.empty());
  std::size_t gaps = 0;
  std::map<std::int64_t, const bearing_sim_lcm::vibration_chunk_t*> by_first_sample;
  for (std::size_t i = 0; i < log.size(); ++i) {
    if (i > 0 && log[i].first_sample != log[i - 1].first_sample + log[i - 1].num_samples) ++gaps;
    by_first_sample[log[i].first_sample] = &log[i];
  }
  EXPECT_EQ(gaps, 0u) << "the log's chunks are not contiguous";
  std::size_t missing = 0;
  std::set<std::int64_t> seq_offsets;
  for (const auto& msg : ros) {
    auto it = by_first_sample.find(static_cast<std::int64_t>(msg->first_sample));
    if (it == by_first_sample.end()) {
      ++missing;
      continue;
    }
    expect_equal_but_seq(*msg, *it->second, &seq_offsets);
    if (::testing::Test::HasFailure()) return;  // one chunk's report is enough
  }
  EXPECT_LE(seq_offsets.size(), 1u) << "header.seq not renumbered by a constant";
  EXPECT_EQ(missing, 0u) << "of " << ros.size() << " chunks received on ROS";
  std::cout << what << ": " << ros.size() << " chunks received on ROS, " << log.size() << " in the log" << std::endl;
}

// Lower-rate topics: over the stamps received on ROS, the log holds the same messages.
template <class Ros, class Lcm>
void compare_by_stamp(const char* what, const std::vector<Ros>& ros, const std::vector<Lcm>& log) {
  SCOPED_TRACE(what);
  ASSERT_FALSE(ros.empty());
  const std::int64_t first = stamp_ns(ros.front()->header.stamp), last = stamp_ns(ros.back()->header.stamp);
  std::map<std::int64_t, const Lcm*> in_range;
  std::size_t duplicates = 0;
  for (const Lcm& m : log) {
    const std::int64_t t = stamp_ns(m.header);
    if (t >= first && t <= last) duplicates += !in_range.emplace(t, &m).second;
  }
  EXPECT_EQ(duplicates, 0u);
  EXPECT_EQ(in_range.size(), ros.size()) << "messages between the first and last stamp received on ROS";
  std::set<std::int64_t> seq_offsets;
  for (const auto& msg : ros) {
    auto it = in_range.find(stamp_ns(msg->header.stamp));
    if (it == in_range.end()) {
      ADD_FAILURE() << "stamp " << msg->header.stamp << " received on ROS is not in the log";
      continue;
    }
    expect_equal_but_seq(*msg, *it->second, &seq_offsets);
  }
  EXPECT_LE(seq_offsets.size(), 1u) << "header.seq not renumbered by a constant";
  std::cout << what << ": " << ros.size() << " received on ROS, all in the log" << std::endl;
}

}  // namespace

TEST(LcmBridge, LogHoldsEveryMessageReceivedOnRosBitExact) {
  ros::NodeHandle nh, pnh("~");
  std::string path;
  ASSERT_TRUE(pnh.getParam("log_file", path));
  struct RemoveLog {
    std::string path;
    ~RemoveLog() { std::remove(path.c_str()); }  // the bridge may still write: unlinked, it vanishes when closed
  } remove_log{path};
  // Subscribe only once the bridge has logged each channel: its subscriptions are then
  // connected, so whatever this node receives, the bridge received too.
  const ros::WallTime bridge_deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (read_log(path).channels.size() < 5) {
    ASSERT_LT(ros::WallTime::now(), bridge_deadline) << "the bridge logged not all five channels in " << path;
    ros::WallDuration(0.05).sleep();
  }
  // Queues deep enough for a minute of every stream as fast as possible (10-30x real time):
  // on a busy machine this node's spinner can stall for seconds, and a message dropped
  // here is not one the bridge lost (ball_loads at 1000: 86 of 1255 dropped under load).
  RosSide ros_side;
  ros_side.subscribe<bearing_sim::VibrationChunk>(nh, "vibration", &ros_side.vibration, 100000);
  ros_side.subscribe<bearing_sim::VibrationChunk>(nh, "vibration_ideal", &ros_side.ideal, 100000);
  ros_side.subscribe<bearing_sim::VibrationLevel>(nh, "vibration_level", &ros_side.levels, 100000);
  ros_side.subscribe<bearing_sim::BallLoads>(nh, "ball_loads", &ros_side.ball_loads, 100000);
  ros_side.subscribe<bearing_sim::BearingHealth>(nh, "health", &ros_side.health, 10000);

  // 12 s of simulated time and 10 health reports (the first comes after a 2 s window).
  auto enough = [&] {
    std::lock_guard<std::mutex> lock(ros_side.mutex);
    return ros_side.vibration.size() >= 1200 && ros_side.health.size() >= 10;
  };
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(60.0);
  while (ros::ok() && !enough() && ros::WallTime::now() < give_up) ros::WallDuration(0.05).sleep();
  {
    std::lock_guard<std::mutex> lock(ros_side.mutex);
    ros_side.frozen = true;
  }
  ASSERT_TRUE(enough()) << "bearing_sim_node did not deliver 12 s of vibration and 10 health reports";
  ASSERT_FALSE(ros_side.ideal.empty());
  ASSERT_FALSE(ros_side.levels.empty());
  ASSERT_FALSE(ros_side.ball_loads.empty());

  LogSide log;
  const ros::WallTime log_deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  for (;;) {
    log = read_log(path);
    if (caught_up(ros_side.vibration, log.vibration) && caught_up(ros_side.ideal, log.ideal) &&
        caught_up(ros_side.levels, log.levels) && caught_up(ros_side.ball_loads, log.ball_loads) &&
        caught_up(ros_side.health, log.health))
      break;
    ASSERT_LT(ros::WallTime::now(), log_deadline) << "the LCM log " << path << " does not catch up with ROS";
    ros::WallDuration(0.2).sleep();
  }
  EXPECT_EQ(log.undecodable, 0u);
  EXPECT_EQ(log.channels.size(), 5u) << "channels other than the five bridged ones";

  compare_chunks("vibration", ros_side.vibration, log.vibration);
  compare_chunks("vibration_ideal", ros_side.ideal, log.ideal);
  compare_by_stamp("vibration_level", ros_side.levels, log.levels);
  compare_by_stamp("health", ros_side.health, log.health);
  compare_by_stamp("ball_loads", ros_side.ball_loads, log.ball_loads);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_lcm_bridge");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}
