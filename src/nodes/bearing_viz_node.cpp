// bearing_viz_node: TF and ball-load markers for rviz (see docs/visualization.md); the same
// code runs as the nodelet bearing_sim/VizNodelet (src/nodelets).
#include <exception>

#include <ros/ros.h>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/ros/parameter_reader.hpp"
#include "bearing_sim/viz/viz_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bearing_viz_node");
  try {
    bearing_sim::viz::VizNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const bearing_sim::ros_node::ParameterError& e) {  // a bad parameter or file: status 2
    ROS_FATAL("bearing_viz_node: %s", e.what());
    return 2;
  } catch (const bearing_sim::ConfigError& e) {
    ROS_FATAL("bearing_viz_node: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("bearing_viz_node: %s", e.what());
    return 1;
  }
  return 0;
}
