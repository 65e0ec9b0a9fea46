// Republishes bearing_sim_node's topics on LCM (see docs/lcm.md); the same code runs as the
// nodelet bearing_sim/LcmBridgeNodelet (src/nodelets).
#include <exception>

#include <ros/ros.h>

#include "bearing_sim/ros/lcm_bridge.hpp"
#include "bearing_sim/ros/parameter_reader.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "lcm_bridge");
  ros::NodeHandle nh, pnh("~");
  try {
    bearing_sim::ros_node::LcmBridge bridge(nh, pnh);
    ros::spin();
  } catch (const bearing_sim::ros_node::ParameterError& e) {  // a bad parameter: status 2
    ROS_FATAL("lcm_bridge: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("lcm_bridge: %s", e.what());
    return 1;
  }
  return 0;
}
