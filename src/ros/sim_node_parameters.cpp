#include "bearing_sim/ros/sim_node_parameters.hpp"

#include <cmath>

#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/ros/parameter_reader.hpp"

namespace bearing_sim {
namespace ros_node {

SimNodeParameters read_sim_node_parameters(const XmlRpc::XmlRpcValue& private_params, const std::string& ns) {
  ParameterReader r(private_params, ns);
  SimNodeParameters p;

  p.bearing_file = r.text("bearing_file", "", true);
  if (p.bearing_file.empty()) r.fail("bearing_file", "required: the bearing YAML file (config/bearings/)");
  p.sensor_file = r.text("sensor_file", "", true);

  // Below 1 kHz the varying-compliance lines and the contact resonances are not resolved;
  // above 1 MHz no accelerometer follows and even the fast mode falls behind.
  p.sample_rate_hz = r.number("sample_rate_hz", p.sample_rate_hz, 1.0e3, 1.0e6, "Hz");
  // 0 lets the core choose from the stiffest mode; beyond 1000 a sample costs milliseconds.
  p.substeps = r.integer("substeps", p.substeps, 0, 1000);
  p.integrator = *integration_method_from_name(
      r.choice("integrator", integration_method_name(p.integrator), integration_method_names()));
  // A ramp longer than a second would hide the load steps the node is meant to show.
  p.load_ramp_s = r.number("load_ramp_s", p.load_ramp_s, 0.0, 1.0, "s");

  p.real_time = r.boolean("real_time", p.real_time);
  p.publish_clock = r.boolean("publish_clock", !p.real_time);
  // 0: as fast as the machine allows. A bound leaves CPU to the nodes that follow /clock (a
  // scenario player reacts in wall time: its inputs arrive reaction time x factor late).
  p.max_real_time_factor = r.number("max_real_time_factor", p.max_real_time_factor, 0.0, 1.0e4, "");
  // Linux SCHED_FIFO priorities are 1..99; 0: normal scheduling.
  p.realtime_priority = r.integer("realtime_priority", p.realtime_priority, 0, 99);
  p.lock_memory = r.boolean("lock_memory", p.lock_memory);
  // The lead is also the input latency: a second is the most a live input may wait.
  p.lead_s = 1e-3 * r.number("lead_ms", 1e3 * p.lead_s, 0.0, 1000.0, "ms");
  if (r.has("frame_id")) p.frame_id = r.text("frame_id", "", false);
  p.bearing_frame_id = r.text("bearing_frame_id", p.bearing_frame_id, false);

  // Limits of the inputs: positive, and below what any rolling bearing carries (the largest
  // slewing rings: ~1e7 N, ~1e7 N*m) or turns at (1e4 rad/s ~ 95000 rpm).
  p.limits.max_force_N = r.number("max_force_N", p.limits.max_force_N, 1.0, 1.0e8, "N");
  p.limits.max_moment_Nm = r.number("max_moment_Nm", p.limits.max_moment_Nm, 1.0, 1.0e8, "N*m");
  p.limits.max_speed_rad_s = r.number("max_speed_rad_s", p.limits.max_speed_rad_s, 0.1, 1.0e4, "rad/s");
  p.max_lag_s = r.number("max_lag_s", p.max_lag_s, 1.0e-5, 10.0, "s");
  p.diagnostic_hold_s = r.number("diagnostic_hold_s", p.diagnostic_hold_s, 0.0, 3600.0, "s");
  p.diagnostic_period_s = r.number("diagnostic_period_s", p.diagnostic_period_s, 0.01, 60.0, "s");

  // The initial inputs obey the topics' limits (the node checks the static solution later).
  const char* load_keys[5] = {"initial_force_x_N", "initial_force_y_N", "initial_force_z_N", "initial_moment_x_Nm",
                              "initial_moment_y_Nm"};
  for (int i = 0; i < 5; ++i) {
    const bool force = i < 3;
    const double limit = force ? p.limits.max_force_N : p.limits.max_moment_Nm;
    p.initial_load(i) =
        r.number(load_keys[i], 0.0, -limit, limit, force ? "N (+-max_force_N)" : "N*m (+-max_moment_Nm)");
  }
  if (p.initial_load.head<3>().norm() > p.limits.max_force_N)
    r.fail("initial_force_x_N", "the initial force's magnitude exceeds max_force_N");
  if (p.initial_load.tail<2>().norm() > p.limits.max_moment_Nm)
    r.fail("initial_moment_x_Nm", "the initial moment's magnitude exceeds max_moment_Nm");
  p.initial_speed_rad_s = r.number("initial_speed_rad_s", 0.0, -p.limits.max_speed_rad_s, p.limits.max_speed_rad_s,
                                   "rad/s (+-max_speed_rad_s)");

  // Health: at most 100 analyses per simulated second (each costs ~5 ms of CPU); a window of
  // 0.1 s resolves 10 Hz in the envelope spectrum, 60 s is a long ring buffer already.
  p.health_rate_hz = r.number("health_rate_hz", p.health_rate_hz, 0.01, 100.0, "Hz");
  p.health_window_s = r.number("health_window_s", p.health_window_s, 0.1, 60.0, "s");
  p.dynamic_load_rating_N = r.number("dynamic_load_rating_N", p.dynamic_load_rating_N, 0.0, 1.0e8, "N");
  const double nyquist_hz = 0.5 * p.sample_rate_hz;
  p.envelope_resonance_hz = r.optional_number("envelope_resonance_hz", 0.0, nyquist_hz, "Hz (sample_rate_hz / 2)");
  p.envelope_band_width_hz =
      r.number("envelope_band_width_hz", p.envelope_band_width_hz, 1.0, nyquist_hz, "Hz (sample_rate_hz / 2)");
  p.fault_snr_db = r.number("fault_snr_db", p.fault_snr_db, kMinFaultSnrDb, kMaxFaultSnrDb, "dB");

  // dynamic_reconfigure's parameters: the cfg's ranges (the server would clamp them silently).
  p.clearance_um =
      r.optional_number(runtime::kClearanceUm.name, runtime::kClearanceUm.min, runtime::kClearanceUm.max, "um");
  p.contact_damping_Ns_per_m =
      r.optional_number(runtime::kContactDampingNsPerM.name, runtime::kContactDampingNsPerM.min,
                        runtime::kContactDampingNsPerM.max, "N*s/m");
  if (r.has(runtime::kChunkSamples.name))
    p.chunk_samples = r.integer(runtime::kChunkSamples.name, 0, static_cast<int>(runtime::kChunkSamples.min),
                                static_cast<int>(runtime::kChunkSamples.max));
  p.level_window_s =
      r.optional_number(runtime::kLevelWindowS.name, runtime::kLevelWindowS.min, runtime::kLevelWindowS.max, "s");
  p.level_rate_hz =
      r.optional_number(runtime::kLevelRateHz.name, runtime::kLevelRateHz.min, runtime::kLevelRateHz.max, "Hz");
  p.ball_loads_rate_hz = r.optional_number(runtime::kBallLoadsRateHz.name, runtime::kBallLoadsRateHz.min,
                                           runtime::kBallLoadsRateHz.max, "Hz");

  r.reject_unknown({"diagnostic_period"});
  return p;
}

}  // namespace ros_node
}  // namespace bearing_sim
