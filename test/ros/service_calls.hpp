#pragma once
// Service calls of the rostest gtest nodes that pass on a busy machine.
#include <string>

#include <ros/ros.h>

namespace bearing_sim::test {

// A call the transport dropped is made again, the service waited for, within `timeout_s`: the
// node's handlers and dynamic_reconfigure's answer true (a refusal is success false in the
// response), so a false is the connection's. Only for calls that may be repeated: a dropped
// answer to a call that did reach the node repeats its effect.
template <class Service>
bool call_until_answered(const std::string& name, Service& srv, double timeout_s = 120.0) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (true) {
    if (ros::service::call(name, srv)) return true;
    const double left_s = (end - ros::WallTime::now()).toSec();
    if (left_s <= 0.0) return false;
    ros::service::waitForService(ros::NodeHandle().resolveName(name), ros::Duration(left_s));
    ros::WallDuration(0.1).sleep();
  }
}

}  // namespace bearing_sim::test
