#pragma once
// The PID of a running ROS node, from its own XML-RPC server (lookupNode on the master,
// then getPid of the node's slave API); -1 if it cannot be found. For tests that measure
// or signal a node's process.
#include <cstdint>
#include <string>

#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <xmlrpcpp/XmlRpc.h>

namespace node_test {

inline int node_pid(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, payload, true)) return -1;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, pid_result;
  pid_args[0] = ros::this_node::getName();
  if (!client.execute("getPid", pid_args, pid_result) || pid_result.size() < 3) return -1;
  return static_cast<int>(pid_result[2]);
}

}  // namespace node_test
