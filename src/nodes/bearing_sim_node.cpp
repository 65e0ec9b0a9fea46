// Real-time bearing vibration simulation node (see docs/node.md); the same code runs as the
// nodelet bearing_sim/BearingSimNodelet (src/nodelets).
#include <exception>

#include <ros/ros.h>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/ros/bearing_sim_ros.hpp"
#include "bearing_sim/ros/parameter_reader.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bearing_sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    bearing_sim::ros_node::BearingSimRos node(nh, pnh, bearing_sim::ros_node::ThreadScope::Process);
    node.start();
    ros::spin();
    node.stop();
  } catch (const bearing_sim::ros_node::ParameterError& e) {  // a bad parameter or file: status 2
    ROS_FATAL("bearing_sim_node: %s", e.what());
    return 2;
  } catch (const bearing_sim::ConfigError& e) {
    ROS_FATAL("bearing_sim_node: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("bearing_sim_node: %s", e.what());
    return 1;
  }
  return 0;
}
