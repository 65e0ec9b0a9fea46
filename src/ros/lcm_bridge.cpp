#include "bearing_sim/ros/lcm_bridge.hpp"

#include <stdexcept>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/ros/lcm_conversion.hpp"

namespace bearing_sim {
namespace ros_node {
namespace {

constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0";

template <typename T>
T param(const ros::NodeHandle& pnh, const std::string& name, const T& fallback) {
  T value;
  pnh.param(name, value, fallback);
  return value;
}

}  // namespace

LcmBridge::LcmBridge(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh), updater_(nh, pnh) {
  const std::string url = param<std::string>(pnh_, "lcm_url", kDefaultUrl);
  // LCM's file provider only reads unless told to write: every publish would fail.
  if (url.rfind("file://", 0) == 0 && url.find("mode=w") == std::string::npos)
    throw std::invalid_argument("~lcm_url '" + url +
                                "': a file:// URL needs mode=w to write a log, e.g. file:///tmp/run.lcm?mode=w");
  const double max_queue_mb = param(pnh_, "max_queue_mb", 64.0);
  if (!(max_queue_mb > 0.0))
    throw std::invalid_argument("~max_queue_mb must be positive, got " + std::to_string(max_queue_mb));
  queue_ = std::make_unique<LcmPublishQueue>(url, static_cast<std::size_t>(max_queue_mb * 1e6));

  // Deep ROS queues (a few seconds of simulated time): with real_time:=false the node runs
  // 20-30x real time, ~3000 chunks and ~800 ball-load messages per wall second, and a
  // shallow queue overflows whenever this process is not scheduled for a moment.
  add_route<VibrationChunk>("vibration", "BEARING_VIBRATION", true, 10000);
  add_route<VibrationChunk>("vibration_ideal", "BEARING_VIBRATION_IDEAL", false, 10000);
  add_route<VibrationLevel>("vibration_level", "BEARING_VIBRATION_LEVEL", true, 1000);
  add_route<BallLoads>("ball_loads", "BEARING_BALL_LOADS", true, 3000);
  add_route<BearingHealth>("health", "BEARING_HEALTH", true, 1000);

  updater_.setHardwareID("lcm: " + url);
  updater_.add("LCM", this, &LcmBridge::diagnose);
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(param(pnh_, "diagnostic_period_s", 1.0)),
                                           [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  std::string routes;
  for (const Route& r : routes_) routes += " " + r.subscriber.getTopic() + " -> " + r.channel + ";";
  ROS_INFO("lcm_bridge: publishing on %s:%s", url.c_str(), routes.c_str());
}

LcmBridge::~LcmBridge() {
  for (Route& r : routes_) r.subscriber.shutdown();
  queue_.reset();
}

template <class RosMessage>
void LcmBridge::add_route(const std::string& topic, const std::string& default_channel, bool default_enabled,
                          std::uint32_t queue_size) {
  if (!param(pnh_, "bridge_" + topic, default_enabled)) return;
  Route& route = routes_.emplace_back();
  route.topic = topic;
  route.channel = param<std::string>(pnh_, topic + "_channel", default_channel);
  if (route.channel.empty()) throw std::invalid_argument("~" + topic + "_channel is empty");
  Route* r = &route;
  route.subscriber = nh_.subscribe<RosMessage>(
      topic, queue_size, [this, r](const typename RosMessage::ConstPtr& msg) { forward(r, *msg); },
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
}

template <class RosMessage>
void LcmBridge::forward(Route* route, const RosMessage& msg) {
  std::vector<std::uint8_t> bytes;
  try {
    bytes = encode_lcm(to_lcm(msg));
  } catch (const std::exception& e) {
    ++route->rejected;
    ROS_WARN_THROTTLE(5.0, "lcm_bridge: a message on %s was not forwarded: %s", route->subscriber.getTopic().c_str(),
                      e.what());
    return;
  }
  ++route->forwarded;
  // A full queue is counted by the queue and reported on /diagnostics.
  if (!queue_->push(route->channel, std::move(bytes)))
    ROS_WARN_THROTTLE(5.0, "lcm_bridge: LCM queue full (~max_queue_mb), dropping messages on %s",
                      route->channel.c_str());
}

void LcmBridge::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const LcmPublishStats s = queue_->stats();
  std::uint64_t rejected = 0;
  for (const Route& r : routes_) {
    rejected += r.rejected;
    status.add(r.subscriber.getTopic() + " -> " + r.channel, std::to_string(r.forwarded) + " forwarded, " +
                                                                  std::to_string(r.rejected) + " rejected");
  }
  status.add("LCM URL", queue_->url());
  status.add("published", s.published);
  status.add("publish failures", s.failed);
  status.add("dropped (queue full)", s.dropped);
  status.add("rejected (not convertible)", rejected);
  status.add("MB published", s.bytes_published * 1e-6);
  status.add("queued messages", s.queued_messages);
  status.add("largest queue (MB)", s.max_queued_bytes_seen * 1e-6);

  const std::uint64_t new_failed = s.failed - last_stats_.failed, new_dropped = s.dropped - last_stats_.dropped,
                      new_rejected = rejected - last_rejected_;
  if (new_failed > 0 || new_dropped > 0 || new_rejected > 0) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "since the last report: %lu publish failures, %lu dropped (queue full), %lu not convertible",
                    static_cast<unsigned long>(new_failed), static_cast<unsigned long>(new_dropped),
                    static_cast<unsigned long>(new_rejected));
    if (new_failed > 0)
      ROS_WARN_THROTTLE(10.0, "lcm_bridge: %lu LCM publish failures on %s (%lu in total)",
                        static_cast<unsigned long>(new_failed), queue_->url().c_str(),
                        static_cast<unsigned long>(s.failed));
  } else {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::OK, "%lu messages published on LCM",
                    static_cast<unsigned long>(s.published));
  }
  last_stats_ = s;
  last_rejected_ = rejected;
}

}  // namespace ros_node
}  // namespace bearing_sim
