#include "bearing_sim/ros/lcm_bridge_parameters.hpp"

#include "bearing_sim/ros/parameter_reader.hpp"

namespace bearing_sim {
namespace ros_node {

LcmBridgeParameters read_lcm_bridge_parameters(const XmlRpc::XmlRpcValue& private_params, const std::string& ns) {
  ParameterReader r(private_params, ns);
  LcmBridgeParameters p;
  p.lcm_url = r.text("lcm_url", p.lcm_url, false);
  if (p.lcm_url.rfind("file://", 0) == 0 && p.lcm_url.find("mode=w") == std::string::npos)
    r.fail("lcm_url", "a file:// URL needs mode=w to write a log, e.g. file:///tmp/run.lcm?mode=w");
  // Below 0.1 MB not even a second of ball loads fits; 4 GiB is more than any backlog worth keeping.
  p.max_queue_mb = r.number("max_queue_mb", p.max_queue_mb, 0.1, 4096.0, "MB");
  p.diagnostic_period_s = r.number("diagnostic_period_s", p.diagnostic_period_s, 0.01, 60.0, "s");
  const struct {
    const char* topic;
    const char* channel;
    bool enabled;
  } defaults[] = {{"vibration", "BEARING_VIBRATION", true},
                  {"vibration_ideal", "BEARING_VIBRATION_IDEAL", false},
                  {"vibration_level", "BEARING_VIBRATION_LEVEL", true},
                  {"ball_loads", "BEARING_BALL_LOADS", true},
                  {"health", "BEARING_HEALTH", true}};
  for (const auto& d : defaults) {
    LcmRouteParameters route;
    route.topic = d.topic;
    route.enabled = r.boolean(std::string("bridge_") + d.topic, d.enabled);
    route.channel = r.text(std::string(d.topic) + "_channel", d.channel, false);
    p.routes.push_back(route);
  }
  r.reject_unknown({"diagnostic_period"});
  return p;
}

}  // namespace ros_node
}  // namespace bearing_sim
