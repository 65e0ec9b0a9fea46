#pragma once
// /diagnostics of bearing_sim_node: real-time lag and overruns, rejected inputs, model
// state. Recorders are thread-safe (sim thread and ROS callbacks); update() publishes.
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/runtime/timing_stats.hpp"

namespace bearing_sim {
namespace ros_node {

struct DiagnosticsSettings {
  bool real_time = true;
  double max_lag_s = 0.005;  // WARN above this lag of simulated behind wall time
  double hold_s = 5.0;       // a rejected input (WARN) or divergence (ERROR) stays reported this long
};

struct ModelState {
  std::string bearing_name;
  Vector5 load = Vector5::Zero();
  double ring_speed_rad_s = 0.0;
  double clearance_m = 0.0;  // at equal ring temperatures (file / clearance_um)
  double ring_temperature_difference_K = 0.0;
  double operating_clearance_m = 0.0;  // what the model uses
  double contact_damping_Ns_per_m = 0.0;
  double substeps = 0.0;  // internal steps per sample
  double varying_compliance_hz = 0.0;
  double static_max_contact_pressure_Pa = 0.0;
};

// The latest health analysis, as shown on /diagnostics (filled by the health worker).
struct HealthStatus {
  std::uint8_t level = 0;  // diagnostic_msgs::DiagnosticStatus OK / WARN / ERROR
  std::string message = "collecting the first window";
  std::vector<std::pair<std::string, std::string>> values;
};

class NodeDiagnostics {
 public:
  NodeDiagnostics(ros::NodeHandle nh, ros::NodeHandle pnh, const std::string& hardware_id,
                  const DiagnosticsSettings& settings);

  // After each published chunk, from one thread only (the publisher, or the sim thread as
  // fast as possible); never blocks. lateness_s: wall time minus the due time of
  // the chunk's last sample; overrun: later than one chunk period.
  void record_chunk(double lateness_s, bool overrun, std::uint64_t samples_published, double simulated_s,
                    double wall_elapsed_s);
  void record_rejected_input(const std::string& reason);
  void record_divergence(const std::string& message);
  void set_model_state(const ModelState& state);
  void set_scheduling(const std::string& description);
  // Further facts of the real-time setup shown in the status (e.g. "memory locked", "lead (ms)").
  void set_realtime_value(const std::string& key, const std::string& value);
  void set_health(HealthStatus status);
  void update();  // publish now

 private:
  using Clock = std::chrono::steady_clock;
  void realtime_task(diagnostic_updater::DiagnosticStatusWrapper& status);
  void inputs_task(diagnostic_updater::DiagnosticStatusWrapper& status);
  void model_task(diagnostic_updater::DiagnosticStatusWrapper& status);
  void health_task(diagnostic_updater::DiagnosticStatusWrapper& status);
  bool within_hold(Clock::time_point t, bool ever) const;

  DiagnosticsSettings settings_;
  diagnostic_updater::Updater updater_;
  std::mutex mutex_;
  runtime::TimingStats lateness_;  // last minute of chunks at 100 Hz
  // record_chunk's records not yet under mutex_ (only the recording thread touches them).
  std::vector<double> unrecorded_lateness_s_;
  std::uint64_t unrecorded_overruns_ = 0;
  double last_lateness_s_ = 0.0;
  std::uint64_t overruns_ = 0, samples_published_ = 0;
  double simulated_s_ = 0.0, wall_elapsed_s_ = 0.0;
  Clock::time_point last_overrun_;
  std::uint64_t rejected_inputs_ = 0;
  std::string last_rejection_;
  Clock::time_point last_rejection_time_;
  std::uint64_t divergences_ = 0;
  std::string last_divergence_;
  Clock::time_point last_divergence_time_;
  ModelState model_;
  std::string scheduling_;
  std::vector<std::pair<std::string, std::string>> realtime_values_;
  HealthStatus health_;
};

}  // namespace ros_node
}  // namespace bearing_sim
