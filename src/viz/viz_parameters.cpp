#include "bearing_sim/viz/viz_parameters.hpp"

#include "bearing_sim/ros/parameter_reader.hpp"

namespace bearing_sim {
namespace viz {

VizParameters read_viz_parameters(const XmlRpc::XmlRpcValue& private_params, const std::string& ns) {
  ros_node::ParameterReader r(private_params, ns);
  VizParameters p;
  p.bearing_file = r.text("bearing_file", "", true);
  if (p.bearing_file.empty()) r.fail("bearing_file", "required: the simulation's bearing YAML file");
  p.fixed_frame = r.text("fixed_frame", p.fixed_frame, false);
  p.bearing_frame = r.text("bearing_frame", p.bearing_frame, false);
  p.rotating_ring_frame = r.text("rotating_ring_frame", p.rotating_ring_frame, false);
  p.cage_frame = r.text("cage_frame", p.cage_frame, false);
  // A display: 0.1 Hz still moves, beyond 200 Hz no screen follows.
  p.update_rate_hz = r.number("update_rate_hz", p.update_rate_hz, 0.1, 200.0, "Hz");
  // The simulation's own limit on the speed input.
  p.initial_speed_rad_s = r.number("initial_speed_rad_s", p.initial_speed_rad_s, -1.0e4, 1.0e4, "rad/s");
  // Micrometre displacements of a metre-sized ring: up to 1e6 x to see them at all.
  p.displacement_exaggeration = r.number("displacement_exaggeration", p.displacement_exaggeration, 0.0, 1.0e6, "");
  // The flexible ring's bending: micrometres on a 0.6 m ring, drawn at millimetres.
  p.deformation_magnification = r.number("deformation_magnification", p.deformation_magnification, 0.0, 1.0e7, "");
  p.colour_full_scale_N = r.number("colour_full_scale_N", p.colour_full_scale_N, 0.0, 1.0e8, "N (0: running maximum)");
  // Display / true ball diameter: visible, and not larger than the bearing.
  p.ball_scale = r.number("ball_scale", p.ball_scale, 0.1, 10.0, "");
  p.force_arrow_length_m = r.number("force_arrow_length_m", p.force_arrow_length_m, 0.0, 10.0, "m");
  p.polar_curve_height_m = r.number("polar_curve_height_m", p.polar_curve_height_m, 0.0, 10.0, "m");
  r.reject_unknown();
  return p;
}

}  // namespace viz
}  // namespace bearing_sim
