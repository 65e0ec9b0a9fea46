// bearing_viz_node: TF and ball-load markers for rviz (see docs/visualization.md).
#include <exception>

#include <ros/ros.h>

#include "bearing_sim/viz/viz_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bearing_viz_node");
  try {
    bearing_sim::viz::VizNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("bearing_viz_node: %s", e.what());
    return 1;
  }
  return 0;
}
