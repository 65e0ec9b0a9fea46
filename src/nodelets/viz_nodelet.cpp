// bearing_viz_node as a nodelet (bearing_sim/VizNodelet, docs/visualization.md): in the
// simulation's nodelet manager it receives ball_loads and vibration without serialisation.
#include <exception>
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "bearing_sim/viz/viz_node.hpp"

namespace bearing_sim {
namespace nodelets {

class VizNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      node_ = std::make_unique<viz::VizNode>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL("bearing_viz_node: %s", e.what());
      throw;
    }
  }

  std::unique_ptr<viz::VizNode> node_;
};

}  // namespace nodelets
}  // namespace bearing_sim

PLUGINLIB_EXPORT_CLASS(bearing_sim::nodelets::VizNodelet, nodelet::Nodelet)
