#pragma once
// Every private parameter of lcm_bridge (config/nodes/lcm_bridge.yaml documents them), read
// and checked at start-up: a bad one stops the bridge with ParameterError naming it.
#include <string>
#include <vector>

#include <xmlrpcpp/XmlRpcValue.h>

namespace bearing_sim {
namespace ros_node {

struct LcmRouteParameters {
  std::string topic;    // relative to the bridge's namespace
  bool enabled = true;  // ~bridge_<topic>
  std::string channel;  // ~<topic>_channel
};

struct LcmBridgeParameters {
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";
  double max_queue_mb = 64.0;
  double diagnostic_period_s = 1.0;
  // vibration, vibration_ideal, vibration_level, ball_loads, health (in this order).
  std::vector<LcmRouteParameters> routes;
};

// Throws ParameterError on an unknown, mistyped or out-of-range parameter, and on a
// file:// URL without mode=w (LCM would open the log for reading: every publish would fail).
LcmBridgeParameters read_lcm_bridge_parameters(const XmlRpc::XmlRpcValue& private_params, const std::string& ns);

}  // namespace ros_node
}  // namespace bearing_sim
