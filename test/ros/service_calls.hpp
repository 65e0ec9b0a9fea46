#pragma once
// Service calls of the rostest gtest nodes that pass on a busy machine.
#include <string>
#include <utility>

#include <ros/ros.h>

namespace bearing_sim::test {

// A service over one persistent connection, not one per call (a fresh connection per call lost
// an answer the node had sent, once in 64 quick calls, on the CI machine). A call the transport
// dropped is made again on a new connection, the service waited for, within `timeout_s`: the
// node's handlers and dynamic_reconfigure's answer true (a refusal is success false in the
// response), so a false is the connection's. A dropped answer to a call that did reach the
// node repeats its effect.
template <class Service>
class PersistentService {
 public:
  explicit PersistentService(std::string name) : name_(std::move(name)), client_(connect()) {}
  bool call(Service& srv, double timeout_s = 120.0) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
    while (true) {
      if (client_.isValid() && client_.call(srv)) return true;
      const double left_s = (end - ros::WallTime::now()).toSec();
      if (left_s <= 0.0) return false;
      ros::service::waitForService(ros::NodeHandle().resolveName(name_), ros::Duration(left_s));
      client_ = connect();
      ros::WallDuration(0.1).sleep();
    }
  }

 private:
  ros::ServiceClient connect() const { return ros::NodeHandle().serviceClient<Service>(name_, true); }
  std::string name_;
  ros::ServiceClient client_;
};

// One call that may be repeated (clear, reconfigure), made as PersistentService makes it.
template <class Service>
bool call_until_answered(const std::string& name, Service& srv, double timeout_s = 120.0) {
  return PersistentService<Service>(name).call(srv, timeout_s);
}

}  // namespace bearing_sim::test
