#include "bearing_sim/ros/node_diagnostics.hpp"

#include <cmath>

#include "bearing_sim/core/quasi_static.hpp"

namespace bearing_sim {
namespace ros_node {

using diagnostic_msgs::DiagnosticStatus;

NodeDiagnostics::NodeDiagnostics(ros::NodeHandle nh, ros::NodeHandle pnh, const std::string& hardware_id,
                                 const DiagnosticsSettings& settings)
    // Named after the node's own namespace, not the process: in a nodelet manager the
    // statuses stay "<ns>/bearing_sim_node: ...".
    : settings_(settings), updater_(nh, pnh, pnh.getNamespace()), lateness_(6000) {
  unrecorded_lateness_s_.reserve(1000);  // no allocation in the real-time thread
  updater_.setHardwareID(hardware_id);
  updater_.add("Real time", this, &NodeDiagnostics::realtime_task);
  updater_.add("Inputs", this, &NodeDiagnostics::inputs_task);
  updater_.add("Model", this, &NodeDiagnostics::model_task);
  updater_.add("Health", this, &NodeDiagnostics::health_task);
}

void NodeDiagnostics::record_chunk(double lateness_s, bool overrun, std::uint64_t samples_published, double simulated_s,
                                   double wall_elapsed_s) {
  // Called by the real-time publisher thread: it must never wait for the diagnostics
  // publisher (a normal-priority thread that a busy machine can deschedule while it holds
  // the lock: priority inversion). If the lock is taken, the record waits here, touched
  // only by the calling thread, and goes in with the next chunk.
  unrecorded_lateness_s_.push_back(lateness_s);
  unrecorded_overruns_ += overrun ? 1 : 0;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  for (double l : unrecorded_lateness_s_) lateness_.add(l);
  unrecorded_lateness_s_.clear();
  last_lateness_s_ = lateness_s;
  if (unrecorded_overruns_ > 0) {
    overruns_ += unrecorded_overruns_;
    unrecorded_overruns_ = 0;
    last_overrun_ = Clock::now();
  }
  samples_published_ = samples_published;
  simulated_s_ = simulated_s;
  wall_elapsed_s_ = wall_elapsed_s;
}

void NodeDiagnostics::record_rejected_input(const std::string& reason) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++rejected_inputs_;
  last_rejection_ = reason;
  last_rejection_time_ = Clock::now();
}

void NodeDiagnostics::record_divergence(const std::string& message) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++divergences_;
  last_divergence_ = message;
  last_divergence_time_ = Clock::now();
}

void NodeDiagnostics::set_model_state(const ModelState& state) {
  std::lock_guard<std::mutex> lock(mutex_);
  model_ = state;
}

void NodeDiagnostics::set_scheduling(const std::string& description) {
  std::lock_guard<std::mutex> lock(mutex_);
  scheduling_ = description;
}

void NodeDiagnostics::set_realtime_value(const std::string& key, const std::string& value) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& kv : realtime_values_)
    if (kv.first == key) {
      kv.second = value;
      return;
    }
  realtime_values_.emplace_back(key, value);
}

void NodeDiagnostics::set_health(HealthStatus status) {
  std::lock_guard<std::mutex> lock(mutex_);
  health_ = std::move(status);
}

void NodeDiagnostics::health_task(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& kv : health_.values) status.add(kv.first, kv.second);
  status.summary(health_.level, health_.message);
}

void NodeDiagnostics::update() { updater_.force_update(); }

bool NodeDiagnostics::within_hold(Clock::time_point t, bool ever) const {
  return ever && std::chrono::duration<double>(Clock::now() - t).count() < settings_.hold_s;
}

void NodeDiagnostics::realtime_task(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  status.add("mode", settings_.real_time ? "real time" : "as fast as possible");
  status.add("simulation thread scheduling", scheduling_);
  for (const auto& kv : realtime_values_) status.add(kv.first, kv.second);
  status.add("samples published", samples_published_);
  status.addf("simulated time (s)", "%.4f", simulated_s_);
  status.addf("real-time factor", "%.3f", wall_elapsed_s_ > 0.0 ? simulated_s_ / wall_elapsed_s_ : 0.0);
  // Lag: wall time at publication minus the due time of the chunk's last sample.
  status.addf("lag (ms)", "%.3f", last_lateness_s_ * 1e3);
  status.addf("lag p50 (ms)", "%.3f", lateness_.percentile(0.50) * 1e3);
  status.addf("lag p99 (ms)", "%.3f", lateness_.percentile(0.99) * 1e3);
  status.addf("lag max (ms)", "%.3f", lateness_.max() * 1e3);
  status.add("lag statistics over chunks", lateness_.size());
  status.add("overruns", overruns_);
  if (!settings_.real_time) {
    status.summary(DiagnosticStatus::OK, "as fast as possible");
  } else if (within_hold(last_overrun_, overruns_ > 0)) {
    status.summary(DiagnosticStatus::WARN, "overrun: a chunk was published more than one chunk period late");
  } else if (last_lateness_s_ > settings_.max_lag_s) {
    status.summaryf(DiagnosticStatus::WARN, "simulated time lags wall time by %.1f ms", last_lateness_s_ * 1e3);
  } else {
    status.summary(DiagnosticStatus::OK, "in real time");
  }
}

void NodeDiagnostics::inputs_task(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  const Vector5& l = model_.load;
  status.addf("load (Fx Fy Fz N, Mx My N*m)", "%.6g %.6g %.6g %.6g %.6g", l[0], l[1], l[2], l[3], l[4]);
  status.addf("ring speed (rad/s)", "%.6g", model_.ring_speed_rad_s);
  status.add("rejected inputs", rejected_inputs_);
  status.add("last rejection", last_rejection_);
  if (within_hold(last_rejection_time_, rejected_inputs_ > 0))
    status.summary(DiagnosticStatus::WARN, "input rejected: " + last_rejection_);
  else status.summary(DiagnosticStatus::OK, "inputs accepted");
}

void NodeDiagnostics::model_task(diagnostic_updater::DiagnosticStatusWrapper& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  status.add("bearing", model_.bearing_name);
  status.addf("clearance (um)", "%.4g", model_.clearance_m * 1e6);
  status.addf("ring temperature difference (K)", "%.4g", model_.ring_temperature_difference_K);
  status.addf("operating clearance (um)", "%.4g", model_.operating_clearance_m * 1e6);
  status.addf("contact damping (N*s/m)", "%.6g", model_.contact_damping_Ns_per_m);
  status.add("integrator steps per sample", model_.substeps);
  status.addf("varying-compliance frequency (Hz)", "%.4f", model_.varying_compliance_hz);
  status.addf("static max contact pressure (MPa)", "%.1f", model_.static_max_contact_pressure_Pa * 1e-6);
  status.add("divergences", divergences_);
  status.add("last divergence", last_divergence_);
  if (within_hold(last_divergence_time_, divergences_ > 0))
    status.summary(DiagnosticStatus::ERROR, "state diverged, reset to the static equilibrium: " + last_divergence_);
  else if (model_.static_max_contact_pressure_Pa > kPermissibleContactPressurePa)
    status.summary(DiagnosticStatus::WARN, "static contact pressure beyond the ISO 76 permissible 4200 MPa");
  else status.summary(DiagnosticStatus::OK, "state finite");
}

}  // namespace ros_node
}  // namespace bearing_sim
