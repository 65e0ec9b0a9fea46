#pragma once
// Every private parameter of bearing_sim_node (config/nodes/bearing_sim_node.yaml documents
// them), read and checked at start-up: a bad one stops the node with ParameterError naming it.
#include <optional>
#include <string>

#include <xmlrpcpp/XmlRpcValue.h>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/runtime/input_validator.hpp"

namespace bearing_sim {
namespace ros_node {

struct SimNodeParameters {
  std::string bearing_file;  // required
  std::string sensor_file;   // "": no sensor, `vibration` is the ideal acceleration
  double sample_rate_hz = 10000.0;
  int substeps = 0;  // 0: chosen by the core
  IntegrationMethod integrator = kDefaultIntegrationMethod;
  double load_ramp_s = 0.0;
  bool real_time = true;
  bool publish_clock = false;         // default: !real_time
  double max_real_time_factor = 0.0;  // not real time: simulated s per wall s at most; 0: unbounded
  int realtime_priority = 0;          // SCHED_FIFO of the publisher thread; 0: normal
  bool lock_memory = true;
  double lead_s = 0.03;
  std::optional<std::string> frame_id;  // unset: the rotating ring's frame
  std::string bearing_frame_id = "bearing";
  runtime::InputLimits limits;
  double max_lag_s = 0.005;
  double diagnostic_hold_s = 5.0;
  double diagnostic_period_s = 1.0;
  Vector5 initial_load = Vector5::Zero();  // Fx, Fy, Fz (N), Mx, My (N*m)
  double initial_speed_rad_s = 0.0;
  double health_rate_hz = 1.0;
  double health_window_s = 2.0;
  double dynamic_load_rating_N = 0.0;           // 0: from the geometry (ISO 281)
  std::optional<double> envelope_resonance_hz;  // unset: the sensor's path resonance, else 0 (automatic)
  double envelope_band_width_hz = 2000.0;
  double fault_snr_db = 12.0;
  // dynamic_reconfigure's start values (cfg/BearingSim.cfg); unset: the bearing file's
  // clearance and damping, the cfg's defaults for the rest.
  std::optional<double> clearance_um, contact_damping_Ns_per_m;
  std::optional<int> chunk_samples;
  std::optional<double> level_window_s, level_rate_hz, ball_loads_rate_hz;
};

// `private_params`: the node's private namespace (private_parameters()); `ns` names it in
// the messages. Throws ParameterError on a missing required, unknown, mistyped or
// out-of-range parameter.
SimNodeParameters read_sim_node_parameters(const XmlRpc::XmlRpcValue& private_params, const std::string& ns);

}  // namespace ros_node
}  // namespace bearing_sim
