#pragma once
// The whole private namespace of a node from the parameter server, as one XmlRpcValue struct
// (for ParameterReader); invalid when nothing is set there.
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpcValue.h>

namespace bearing_sim {
namespace ros_node {

inline XmlRpc::XmlRpcValue private_parameters(const ros::NodeHandle& private_nh) {
  XmlRpc::XmlRpcValue tree;
  if (!ros::param::get(private_nh.getNamespace(), tree)) return XmlRpc::XmlRpcValue();
  return tree;
}

}  // namespace ros_node
}  // namespace bearing_sim
