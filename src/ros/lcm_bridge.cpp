#include "bearing_sim/ros/lcm_bridge.hpp"

#include <stdexcept>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/ros/lcm_bridge_parameters.hpp"
#include "bearing_sim/ros/lcm_conversion.hpp"
#include "bearing_sim/ros/private_parameters.hpp"

namespace bearing_sim {
namespace ros_node {

LcmBridge::LcmBridge(ros::NodeHandle nh, ros::NodeHandle pnh)
    // Named after the node's own namespace, not the process (the same in a nodelet manager).
    : nh_(nh), pnh_(pnh), updater_(nh, pnh, pnh.getNamespace()) {
  // Every parameter checked before LCM opens: a bad one stops the bridge, naming it.
  const LcmBridgeParameters params = read_lcm_bridge_parameters(private_parameters(pnh_), pnh_.getNamespace());
  const std::string& url = params.lcm_url;
  queue_ = std::make_unique<LcmPublishQueue>(url, static_cast<std::size_t>(params.max_queue_mb * 1e6));

  // Deep ROS queues (a few seconds of simulated time): with real_time:=false the node runs
  // 20-30x real time, ~3000 chunks and ~800 ball-load messages per wall second, and a
  // shallow queue overflows whenever this process is not scheduled for a moment.
  for (const LcmRouteParameters& route : params.routes) {
    if (!route.enabled) continue;
    if (route.topic == "vibration" || route.topic == "vibration_ideal") add_route<VibrationChunk>(route, 10000);
    else if (route.topic == "vibration_level") add_route<VibrationLevel>(route, 1000);
    else if (route.topic == "ball_loads") add_route<BallLoads>(route, 3000);
    else if (route.topic == "health") add_route<BearingHealth>(route, 1000);
  }

  updater_.setHardwareID("lcm: " + url);
  updater_.add("LCM", this, &LcmBridge::diagnose);
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(params.diagnostic_period_s),
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
void LcmBridge::add_route(const LcmRouteParameters& parameters, std::uint32_t queue_size) {
  Route& route = routes_.emplace_back();
  route.topic = parameters.topic;
  route.channel = parameters.channel;
  Route* r = &route;
  // A ConstPtr callback: in a nodelet manager the simulation's message itself, not a copy.
  route.subscriber = nh_.subscribe<RosMessage>(
      route.topic, queue_size, [this, r](const typename RosMessage::ConstPtr& msg) { forward(r, *msg); },
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
    status.add(r.subscriber.getTopic() + " -> " + r.channel,
               std::to_string(r.forwarded) + " forwarded, " + std::to_string(r.rejected) + " rejected");
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
