// lcm_bridge as a nodelet (bearing_sim/LcmBridgeNodelet, docs/lcm.md): in the simulation's
// nodelet manager it converts the published messages themselves, with no ROS serialisation
// in between.
#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "bearing_sim/ros/lcm_bridge.hpp"

namespace bearing_sim {
namespace nodelets {

class LcmBridgeNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      bridge_ = std::make_unique<ros_node::LcmBridge>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL("lcm_bridge: %s", e.what());
      throw;
    }
  }

  std::unique_ptr<ros_node::LcmBridge> bridge_;
};

}  // namespace nodelets
}  // namespace bearing_sim

PLUGINLIB_EXPORT_CLASS(bearing_sim::nodelets::LcmBridgeNodelet, nodelet::Nodelet)
