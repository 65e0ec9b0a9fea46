// Real-time bearing vibration simulation node (see docs/node.md).
#include <exception>

#include <ros/ros.h>

#include "bearing_sim/ros/bearing_sim_ros.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bearing_sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    bearing_sim::ros_node::BearingSimRos node(nh, pnh);
    node.start();
    ros::spin();
    node.stop();
  } catch (const std::exception& e) {
    ROS_FATAL("bearing_sim_node: %s", e.what());
    return 1;
  }
  return 0;
}
