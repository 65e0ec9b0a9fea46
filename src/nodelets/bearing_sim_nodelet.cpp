// bearing_sim_node as a nodelet (bearing_sim/BearingSimNodelet, docs/node.md): the same
// BearingSimRos, in a nodelet manager next to the display and the LCM bridge, whose
// subscriptions then receive the published messages themselves (no serialisation).
#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "bearing_sim/ros/bearing_sim_ros.hpp"

namespace bearing_sim {
namespace nodelets {

class BearingSimNodelet : public nodelet::Nodelet {
 public:
  ~BearingSimNodelet() override {
    if (node_) node_->stop();
  }

 private:
  void onInit() override {
    try {
      // getNodeHandle(): the nodelet's single-threaded queue, like the node's one spinner.
      node_ = std::make_unique<ros_node::BearingSimRos>(getNodeHandle(), getPrivateNodeHandle(),
                                                        ros_node::ThreadScope::OwnThreads);
      node_->start();
    } catch (const std::exception& e) {
      NODELET_FATAL("bearing_sim_node: %s", e.what());
      throw;  // the manager refuses the load; `nodelet load` exits and a required node ends the launch
    }
  }

  std::unique_ptr<ros_node::BearingSimRos> node_;
};

}  // namespace nodelets
}  // namespace bearing_sim

PLUGINLIB_EXPORT_CLASS(bearing_sim::nodelets::BearingSimNodelet, nodelet::Nodelet)
