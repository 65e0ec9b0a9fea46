#pragma once
// lcm_bridge: republishes bearing_sim_node's topics (in the node's namespace) on LCM
// channels (docs/lcm.md). Callbacks convert and encode (lcm_conversion) and hand the bytes
// to an LcmPublishQueue; its thread publishes. Counts and /diagnostics here.
#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "bearing_sim/ros/lcm_bridge_parameters.hpp"
#include "bearing_sim/ros/lcm_publish_queue.hpp"

namespace bearing_sim {
namespace ros_node {

class LcmBridge {
 public:
  // Reads the parameters (read_lcm_bridge_parameters) and opens ~lcm_url; throws
  // ParameterError for a bad parameter and LcmUrlError if LCM refuses the URL.
  LcmBridge(ros::NodeHandle nh, ros::NodeHandle pnh);
  // Publishes what is still queued, then closes LCM (a file:// log is complete).
  ~LcmBridge();

 private:
  struct Route {
    std::string topic, channel;
    std::uint64_t forwarded = 0;  // enqueued for LCM
    std::uint64_t rejected = 0;   // not convertible (e.g. parallel arrays of unequal length)
    ros::Subscriber subscriber;
  };
  template <class RosMessage>
  void add_route(const LcmRouteParameters& parameters, std::uint32_t queue_size);
  template <class RosMessage>
  void forward(Route* route, const RosMessage& msg);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<LcmPublishQueue> queue_;
  std::deque<Route> routes_;  // stable addresses for the callbacks
  diagnostic_updater::Updater updater_;
  ros::WallTimer diagnostics_timer_;
  LcmPublishStats last_stats_;
  std::uint64_t last_rejected_ = 0;
};

}  // namespace ros_node
}  // namespace bearing_sim
