#pragma once
// Every private parameter of bearing_viz_node (config/nodes/bearing_viz.yaml documents them),
// read and checked at start-up: a bad one stops the display with ParameterError naming it.
#include <string>

#include <xmlrpcpp/XmlRpcValue.h>

namespace bearing_sim {
namespace viz {

struct VizParameters {
  std::string bearing_file;  // required: the simulation's
  std::string fixed_frame = "gantry";
  std::string bearing_frame = "bearing";
  std::string rotating_ring_frame = "rotating_ring";
  std::string cage_frame = "cage";
  double update_rate_hz = 30.0;
  double initial_speed_rad_s = 0.0;
  double displacement_exaggeration = 1000.0;
  double deformation_magnification = 5000.0;  // of the flexible ring's deformation
  double colour_full_scale_N = 0.0;           // 0: the running maximum
  double ball_scale = 1.3;
  double force_arrow_length_m = 0.08;
  double polar_curve_height_m = 0.15;
};

// Throws bearing_sim::ros_node::ParameterError on a missing bearing_file or an unknown,
// mistyped or out-of-range parameter.
VizParameters read_viz_parameters(const XmlRpc::XmlRpcValue& private_params, const std::string& ns);

}  // namespace viz
}  // namespace bearing_sim
