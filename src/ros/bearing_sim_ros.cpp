#include "bearing_sim/ros/bearing_sim_ros.hpp"

#include <pthread.h>
#include <sched.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include <rosgraph_msgs/Clock.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "bearing_sim/ros/message_conversion.hpp"
#include "bearing_sim/ros/realtime_pacer.hpp"

namespace bearing_sim {
namespace ros_node {
namespace {

template <typename T>
T param(const ros::NodeHandle& pnh, const std::string& name, const T& fallback) {
  T value;
  pnh.param(name, value, fallback);
  return value;
}

std::size_t window_samples(double window_s, double sample_rate_hz) {
  return static_cast<std::size_t>(std::max(1.0, std::round(window_s * sample_rate_hz)));
}

std::string fmt(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string describe(const Spall& s) {
  std::string what = std::string(surface_name(s.surface)) + " spall";
  if (s.surface == Surface::Ball) what += " on ball " + std::to_string(s.ball);
  return what + " at " + fmt(s.position_rad, 3) + " rad, " + fmt(s.width_m * 1e3, 2) + " mm wide, " +
         fmt(s.depth_m * 1e6, 1) + " um deep";
}

std::size_t sensor_chunk_samples(std::size_t ideal_chunk_samples, int decimation_ratio) {
  // About the same time span as the ideal chunks.
  return std::max<std::size_t>(1, ideal_chunk_samples / static_cast<std::size_t>(decimation_ratio));
}

}  // namespace

BearingSimRos::BearingSimRos(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh) {
  const std::string bearing_file = param<std::string>(pnh_, "bearing_file", "");
  if (bearing_file.empty()) throw std::runtime_error("parameter ~bearing_file is not set");
  BearingModel model(load_bearing_config(bearing_file));
  if (!model.config().has_dynamics())
    throw std::runtime_error("bearing file " + bearing_file + " has no rotating_mass_kg: no dynamics possible");

  sample_rate_hz_ = param(pnh_, "sample_rate_hz", 10000.0);
  const double load_ramp_s = param(pnh_, "load_ramp_s", 0.0);
  if (!(load_ramp_s >= 0.0) || load_ramp_s > 1.0) throw std::runtime_error("~load_ramp_s must be in [0, 1] s");
  load_ramp_ = LoadRamp(static_cast<std::uint64_t>(std::llround(load_ramp_s * sample_rate_hz_)));
  const int substeps = param(pnh_, "substeps", 0);
  const std::string integrator = param<std::string>(pnh_, "integrator", "etdrk4");
  if (integrator != "etdrk4" && integrator != "rk4") throw std::runtime_error("~integrator must be etdrk4 or rk4");
  const IntegrationMethod method = integrator == "rk4" ? IntegrationMethod::Rk4 : IntegrationMethod::ExponentialRk4;
  real_time_ = param(pnh_, "real_time", true);
  publish_clock_ = param(pnh_, "publish_clock", !real_time_);
  realtime_priority_ = param(pnh_, "realtime_priority", 0);
  const bool outer = model.config().rotating_ring == RotatingRing::Outer;
  frame_id_ = param<std::string>(pnh_, "frame_id", outer ? "bearing_outer_ring" : "bearing_inner_ring");
  bearing_frame_id_ = param<std::string>(pnh_, "bearing_frame_id", "bearing");
  limits_.max_force_N = param(pnh_, "max_force_N", limits_.max_force_N);
  limits_.max_moment_Nm = param(pnh_, "max_moment_Nm", limits_.max_moment_Nm);
  limits_.max_speed_rad_s = param(pnh_, "max_speed_rad_s", limits_.max_speed_rad_s);
  DiagnosticsSettings diag;
  diag.real_time = real_time_;
  diag.max_lag_s = param(pnh_, "max_lag_s", diag.max_lag_s);
  diag.hold_s = param(pnh_, "diagnostic_hold_s", diag.hold_s);
  const double diagnostic_period_s = param(pnh_, "diagnostic_period_s", 1.0);

  Vector5 load;
  load << param(pnh_, "initial_force_x_N", 0.0), param(pnh_, "initial_force_y_N", 0.0),
      param(pnh_, "initial_force_z_N", 0.0), param(pnh_, "initial_moment_x_Nm", 0.0),
      param(pnh_, "initial_moment_y_Nm", 0.0);
  const double speed = param(pnh_, "initial_speed_rad_s", 0.0);
  // The initial inputs obey the same rules as the topics, but a bad one stops the node.
  const InputCheck load_check = check_load(load, limits_, &model);
  if (!load_check.accepted) throw std::runtime_error("initial load: " + load_check.reason);
  const InputCheck speed_check = check_speed(speed, limits_);
  if (!speed_check.accepted) throw std::runtime_error("initial speed: " + speed_check.reason);
  accepted_load_ = load;
  accepted_speed_rad_s_ = speed;
  accepted_max_pressure_Pa_ = load_check.max_contact_pressure_Pa;

  validation_model_ = std::make_unique<BearingModel>(model);
  source_ = std::make_unique<SampleSource>(
      BearingDynamics(model, load, speed, DynamicsOptions{sample_rate_hz_, substeps, true, method}));
  substeps_ = source_->dynamics().substeps();
  assembler_ = std::make_unique<ChunkAssembler>(settings_.chunk_samples);

  // Virtual sensor: `vibration` carries what it records, at its output rate.
  const std::string sensor_file = param<std::string>(pnh_, "sensor_file", "");
  measured_rate_hz_ = sample_rate_hz_;
  sensor_description_ = "ideal ring acceleration";
  if (!sensor_file.empty()) {
    try {
      sensor_ = std::make_unique<TriaxialSensor>(load_accelerometer_config(sensor_file), sample_rate_hz_);
    } catch (const InvalidInputError& e) {
      throw std::runtime_error("sensor file " + sensor_file + " at ~sample_rate_hz " + fmt(sample_rate_hz_, 1) +
                               " Hz: " + e.what());
    }
    measured_rate_hz_ = sensor_->output_rate_hz();
    sensor_description_ = "sensor: " + sensor_->config().name;
    sensor_assembler_ = std::make_unique<ChunkAssembler>(
        sensor_chunk_samples(settings_.chunk_samples, sensor_->decimation_ratio()));
  }
  level_rms_ = std::make_unique<RunningRms>(window_samples(settings_.level_window_s, measured_rate_hz_));
  level_divider_ = std::make_unique<SampleDivider>(settings_.level_rate_hz, sample_rate_hz_);
  ball_loads_divider_ = std::make_unique<SampleDivider>(settings_.ball_loads_rate_hz, sample_rate_hz_);

  // As fast as possible, everything comes at ~15-30x its rate: deeper queues, so that a
  // subscriber descheduled for a moment (a recorder, the LCM bridge) loses nothing.
  const int depth = real_time_ ? 1 : 20;
  vibration_pub_ = nh_.advertise<VibrationChunk>("vibration", 100 * depth);
  ideal_pub_ = nh_.advertise<VibrationChunk>("vibration_ideal", 100 * depth);
  health_pub_ = nh_.advertise<BearingHealth>("health", 10 * depth);
  level_pub_ = nh_.advertise<VibrationLevel>("vibration_level", 10 * depth);
  ball_loads_pub_ = nh_.advertise<BallLoads>("ball_loads", 10 * depth);
  if (publish_clock_) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 100);

  diagnostics_ = std::make_unique<NodeDiagnostics>(nh_, pnh_, "bearing_sim: " + model.config().name, diag);

  // Health: analysed on a worker thread (HealthMonitor), never in the simulation thread.
  HealthSettings health;
  health.sample_rate_hz = measured_rate_hz_;
  health.window_s = param(pnh_, "health_window_s", health.window_s);
  health.life.dynamic_load_rating_N = param(pnh_, "dynamic_load_rating_N", 0.0);
  // Envelope band around the sensor's transmission-path resonance, where impacts ring.
  const double default_resonance_hz = sensor_ ? sensor_->config().path_resonance_hz : 0.0;
  health.analysis.resonance_hz = param(pnh_, "envelope_resonance_hz", default_resonance_hz);
  health.analysis.envelope_band_width_hz =
      param(pnh_, "envelope_band_width_hz", health.analysis.envelope_band_width_hz);
  health.analysis.thresholds.fault_snr_db = param(pnh_, "fault_snr_db", health.analysis.thresholds.fault_snr_db);
  const double health_rate_hz = param(pnh_, "health_rate_hz", 1.0);
  if (!(health_rate_hz > 0.0) || health_rate_hz > 100.0)
    throw std::runtime_error("~health_rate_hz must be in (0, 100]");
  health_ = std::make_unique<HealthMonitor>(model, load, speed, health,
                                            [this](const HealthReport& r) { publish_health(r); });
  health_divider_ = std::make_unique<SampleDivider>(health_rate_hz, sample_rate_hz_);
  health_samples_.reserve(static_cast<std::size_t>(measured_rate_hz_ / health_rate_hz) + 10000);
  publish_model_state();
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(diagnostic_period_s),
                                           [this](const ros::WallTimerEvent&) { diagnostics_->update(); });

  // dynamic_reconfigure: clearance and damping start from the bearing file unless the
  // parameters were set explicitly (the server would otherwise impose the cfg defaults).
  const bool clearance_given = pnh_.hasParam("clearance_um");
  const bool damping_given = pnh_.hasParam("contact_damping_Ns_per_m");
  reconfigure_server_ =
      std::make_unique<dynamic_reconfigure::Server<BearingSimConfig>>(reconfigure_mutex_, pnh_);
  BearingSimConfig initial;
  initial.__fromServer__(pnh_);
  if (!clearance_given) initial.clearance_um = model.config().clearance_m * 1e6;
  if (!damping_given) initial.contact_damping_Ns_per_m = model.config().contact_damping_Ns_per_m;
  reconfigure_server_->updateConfig(initial);
  reconfigure_server_->setCallback(
      [this](BearingSimConfig& config, std::uint32_t level) { on_reconfigure(config, level); });

  load_sub_ = nh_.subscribe("load", 10, &BearingSimRos::on_load, this);
  inject_srv_ = nh_.advertiseService("inject_defect", &BearingSimRos::on_inject_defect, this);
  clear_srv_ = nh_.advertiseService("clear_defects", &BearingSimRos::on_clear_defects, this);
  speed_sub_ = nh_.subscribe("speed", 10, &BearingSimRos::on_speed, this);
  ROS_INFO("bearing_sim_node: '%s', %d balls, %.0f Hz dynamics, %d %s substeps per sample, %s; "
           "vibration: %s at %.0f Hz",
           model.config().name.c_str(), model.ball_count(), sample_rate_hz_, substeps_,
           source_->dynamics().method() == IntegrationMethod::Rk4 ? "RK4" : "ETDRK4",
           real_time_ ? "real time" : "as fast as possible", sensor_description_.c_str(), measured_rate_hz_);
}

BearingSimRos::~BearingSimRos() { stop(); }

void BearingSimRos::start() {
  if (sim_thread_.joinable()) return;
  stop_ = false;
  health_->start();
  sim_thread_ = std::thread([this] { run(); });
}

void BearingSimRos::stop() {
  stop_ = true;
  if (sim_thread_.joinable()) sim_thread_.join();
  if (health_) health_->stop();  // its callback publishes: stop it before the publishers go
}

// ---------------------------------------------------------------------------------------
// ROS callbacks (spinner thread)

void BearingSimRos::reject_input(const std::string& reason) {
  ROS_WARN_THROTTLE(1.0, "bearing_sim_node: input rejected, keeping the last good inputs: %s", reason.c_str());
  diagnostics_->record_rejected_input(reason);
}

void BearingSimRos::on_load(const geometry_msgs::WrenchStamped::ConstPtr& msg) {
  const Vector5 load = load_from_wrench(msg->wrench);
  const InputCheck check = check_load(load, limits_, validation_model_.get());
  if (!check.accepted) return reject_input(check.reason);
  if (check.max_contact_pressure_Pa > kPermissibleContactPressurePa)
    ROS_WARN_THROTTLE(5.0, "bearing_sim_node: static contact pressure %.0f MPa exceeds the ISO 76 limit of 4200 MPa",
                      check.max_contact_pressure_Pa * 1e-6);
  accepted_load_ = load;
  accepted_max_pressure_Pa_ = check.max_contact_pressure_Pa;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.load = load;
  }
  pending_flag_ = true;
  publish_model_state();
}

void BearingSimRos::on_speed(const std_msgs::Float64::ConstPtr& msg) {
  const InputCheck check = check_speed(msg->data, limits_);
  if (!check.accepted) return reject_input(check.reason);
  accepted_speed_rad_s_ = msg->data;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.ring_speed_rad_s = msg->data;
  }
  pending_flag_ = true;
  publish_model_state();
}

bool BearingSimRos::on_inject_defect(InjectDefect::Request& req, InjectDefect::Response& res) {
  Spall spall;
  spall.position_rad = req.position_rad;
  spall.ball = req.ball;
  spall.width_m = req.width_m;
  spall.depth_m = req.depth_m;
  spall.width_growth_m_per_s = req.width_growth_m_per_s;
  spall.depth_growth_m_per_s = req.depth_growth_m_per_s;
  try {
    spall.surface = parse_surface(req.surface);
    // Validated here against the bearing (the core's checks), so that the caller gets the
    // reason; the sim thread then adds it from its next sample.
    validation_model_->add_spall(spall);
  } catch (const InvalidInputError& e) {
    res.success = false;
    res.message = "defect does not fit the bearing '" + validation_model_->config().name + "': " + e.what();
    res.defects_present = static_cast<std::uint32_t>(validation_model_->imperfections().spalls().size());
    ROS_WARN("bearing_sim_node: inject_defect refused: %s", res.message.c_str());
    return true;
  }
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.defect_commands.emplace_back(spall);
  }
  pending_flag_ = true;
  res.success = true;
  res.defects_present = static_cast<std::uint32_t>(validation_model_->imperfections().spalls().size());
  res.message = "injected " + describe(spall) + "; " + std::to_string(res.defects_present) + " defect(s) present";
  ROS_INFO("bearing_sim_node: %s", res.message.c_str());
  return true;
}

bool BearingSimRos::on_clear_defects(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  const std::size_t n = validation_model_->imperfections().spalls().size();
  validation_model_->clear_spalls();
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.defect_commands.emplace_back(std::nullopt);
  }
  pending_flag_ = true;
  res.success = true;
  res.message = "cleared " + std::to_string(n) + " defect(s) (spalls); waviness and roughness stay";
  ROS_INFO("bearing_sim_node: %s", res.message.c_str());
  return true;
}

void BearingSimRos::on_reconfigure(BearingSimConfig& config, std::uint32_t /*level*/) {
  const BearingConfig& old = validation_model_->config();
  const double clearance_m = config.clearance_um * 1e-6;
  std::optional<BearingModel> new_model;
  if (clearance_m != old.clearance_m || config.contact_damping_Ns_per_m != old.contact_damping_Ns_per_m) {
    BearingConfig changed = old;
    changed.clearance_m = clearance_m;
    changed.contact_damping_Ns_per_m = config.contact_damping_Ns_per_m;
    BearingModel model(changed);
    model.set_deflection_offsets(validation_model_->deflection_offsets());
    // The spalls present now, not only those of the file (the sim thread re-times them).
    model.clear_spalls();
    for (const Spall& sp : validation_model_->imperfections().spalls()) model.add_spall(sp);
    const InputCheck check = check_load(accepted_load_, limits_, &model);
    if (check.accepted) {
      accepted_max_pressure_Pa_ = check.max_contact_pressure_Pa;
      new_model = std::move(model);
    } else {
      // Refuse the change; the server publishes the reverted values.
      reject_input("clearance " + std::to_string(config.clearance_um) + " um: " + check.reason);
      config.clearance_um = old.clearance_m * 1e6;
      config.contact_damping_Ns_per_m = old.contact_damping_Ns_per_m;
    }
  }
  OutputSettings settings;
  settings.chunk_samples = static_cast<std::size_t>(std::max(1, config.chunk_samples));
  settings.level_window_s = config.level_window_s;
  settings.level_rate_hz = config.level_rate_hz;
  settings.ball_loads_rate_hz = config.ball_loads_rate_hz;
  if (new_model) *validation_model_ = *new_model;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    if (new_model) pending_.model = std::move(new_model);
    pending_.settings = settings;
  }
  pending_flag_ = true;
  publish_model_state();
}

void BearingSimRos::publish_model_state() {
  ModelState s;
  const BearingConfig& c = validation_model_->config();
  s.bearing_name = c.name;
  s.load = accepted_load_;
  s.ring_speed_rad_s = accepted_speed_rad_s_;
  s.clearance_m = c.clearance_m;
  s.contact_damping_Ns_per_m = c.contact_damping_Ns_per_m;
  s.substeps = substeps_;
  s.varying_compliance_hz = bearing_frequencies(*validation_model_, accepted_speed_rad_s_).varying_compliance_hz;
  s.static_max_contact_pressure_Pa = accepted_max_pressure_Pa_;
  diagnostics_->set_model_state(s);
}

// ---------------------------------------------------------------------------------------
// Simulation thread

void BearingSimRos::apply_pending() {
  Pending p;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    p = std::move(pending_);
    pending_ = Pending{};
    pending_flag_ = false;
  }
  BearingDynamics& dynamics = source_->dynamics();
  // Inputs were validated by the callbacks; the core only rejects non-finite values.
  try {
    if (p.model) {
      // Keep the spalls as they are in the running model (their creation times).
      p.model->clear_spalls();
      for (const Spall& s : dynamics.model().imperfections().spalls()) p.model->add_spall(s);
      health_->set_model(*p.model);
      dynamics.set_model(std::move(*p.model));
    }
    if (p.load) {
      load_ramp_.start(dynamics.load(), *p.load);
      if (!load_ramp_.active()) dynamics.set_load(*p.load);
    }
    if (p.ring_speed_rad_s) dynamics.set_ring_speed(*p.ring_speed_rad_s);
  } catch (const InvalidInputError& e) {
    diagnostics_->record_rejected_input(e.what());
  }
  if (!p.defect_commands.empty()) {
    for (auto& command : p.defect_commands) {
      try {
        if (command) dynamics.add_spall(*command);  // starts growing now
        else dynamics.clear_spalls();
      } catch (const InvalidInputError& e) {  // validated by the service already
        diagnostics_->record_rejected_input(e.what());
      }
    }
    health_->set_defects(dynamics.model().imperfections().spalls());
  }
  if (p.settings) apply_settings(*p.settings);
}

void BearingSimRos::apply_settings(const OutputSettings& s) {
  if (s.chunk_samples != settings_.chunk_samples) assembler_->set_chunk_samples(s.chunk_samples);
  if (s.level_window_s != settings_.level_window_s)
    level_rms_->resize(window_samples(s.level_window_s, measured_rate_hz_));
  if (sensor_ && s.chunk_samples != settings_.chunk_samples)
    sensor_assembler_->set_chunk_samples(sensor_chunk_samples(s.chunk_samples, sensor_->decimation_ratio()));
  if (s.level_rate_hz != settings_.level_rate_hz) level_divider_->set_rate(s.level_rate_hz, sample_rate_hz_);
  if (s.ball_loads_rate_hz != settings_.ball_loads_rate_hz)
    ball_loads_divider_->set_rate(s.ball_loads_rate_hz, sample_rate_hz_);
  settings_ = s;
}

ros::Time BearingSimRos::stamp_of(std::uint64_t sample_index) const {
  const long double ns = static_cast<long double>(sample_index) * 1.0e9L / sample_rate_hz_;
  ros::Duration offset;
  offset.fromNSec(static_cast<std::int64_t>(std::llround(ns)));
  return ros_start_ + offset;
}

void BearingSimRos::publish_level(const SampleSource::Sample& sample) {
  VibrationLevel msg;
  msg.header.stamp = stamp_of(sample.index);
  msg.header.frame_id = frame_id_;
  msg.accel_rms = level_rms_->rms();
  msg.level_db = vibration_level_db(msg.accel_rms);
  msg.window_s = static_cast<double>(level_rms_->size()) / measured_rate_hz_;
  level_pub_.publish(msg);
}

void BearingSimRos::publish_ball_loads(const SampleSource::Sample& sample) {
  if (ball_loads_pub_.getNumSubscribers() == 0) return;  // per-ball states cost a few microseconds per ball
  const BearingModel& model = source_->dynamics().model();
  BallLoads msg;
  msg.header.stamp = stamp_of(sample.index);
  msg.header.frame_id = bearing_frame_id_;
  fill_ball_loads(model.ball_states(sample.state->displacement, sample.state->cage_angle_rad), model.rows(),
                  model.balls_per_row(), sample.state->cage_angle_rad, &msg);
  ball_loads_pub_.publish(msg);
}

void BearingSimRos::publish_sensor_chunk() {
  SampleChunk chunk = sensor_assembler_->take();
  // Sensor sample k is the output at dynamics sample (k + 1) R - 1 (docs/sensor.md).
  const std::uint64_t r = static_cast<std::uint64_t>(sensor_->decimation_ratio());
  const ros::Time first_stamp = stamp_of((chunk.first_sample + 1) * r - 1);
  VibrationChunk msg;
  fill_vibration_chunk(std::move(chunk), first_stamp, frame_id_, measured_rate_hz_, &msg);
  vibration_pub_.publish(msg);
}

void BearingSimRos::feed_health(bool request, double time_s) {
  health_->push(health_samples_.data(), health_samples_.size());
  health_samples_.clear();
  if (request) health_->request_analysis(time_s);
}

void BearingSimRos::publish_health(const HealthReport& report) {
  BearingHealth msg;
  msg.header.stamp = ros_start_ + ros::Duration(report.end_time_s);
  msg.header.frame_id = frame_id_;
  fill_bearing_health(report, sensor_description_, measured_rate_hz_, &msg);
  health_pub_.publish(msg);

  HealthStatus status;
  status.level = msg.level;
  status.message = msg.reason;
  auto add = [&](const std::string& key, const std::string& value) { status.values.emplace_back(key, value); };
  add("signal", msg.signal);
  if (report.analysed) {
    add("window (s)", fmt(msg.window_s, 3));
    add("acceleration RMS (m/s^2)", fmt(msg.accel_rms, 6));
    add("peak (m/s^2)", fmt(msg.accel_peak, 6));
    add("crest factor", fmt(msg.crest_factor, 2));
    add("kurtosis", fmt(msg.kurtosis, 2));
    add("L (dB)", fmt(msg.level_db, 1));
    add("velocity RMS 10-1000 Hz (mm/s)", fmt(msg.velocity_rms_mm_s, 4));
    add("ISO 20816-3 zone", msg.velocity_zone);
    add("envelope band (Hz)", fmt(msg.envelope_low_hz, 0) + "-" + fmt(msg.envelope_high_hz, 0));
    for (const EnvelopeLine& l : msg.faults)
      add("envelope " + l.label + " " + fmt(l.expected_hz, 2) + " Hz",
          "peak " + fmt(l.peak_hz, 2) + " Hz, " + fmt(l.snr_db, 1) + " dB over noise" +
              (l.suspected ? " (suspected)" : ""));
  }
  std::string defects;
  for (const DefectState& d : msg.defects)
    defects += (defects.empty() ? "" : "; ") + d.surface + (d.ball >= 0 ? " ball " + std::to_string(d.ball) : "") +
               " at " + fmt(d.position_rad, 3) + " rad, " + fmt(d.width_m * 1e3, 2) + " mm x " +
               fmt(d.depth_m * 1e6, 1) + " um";
  add("defects present", defects.empty() ? "none" : defects);
  add("ISO 281 L10 (h)", fmt(msg.l10_hours, 0));
  add("reference life ISO/TS 16281 (h)", fmt(msg.reference_life_hours, 0));
  add("Miner damage", fmt(msg.miner_damage, 12));
  add("remaining life (h)", fmt(msg.remaining_life_hours, 0));
  diagnostics_->set_health(std::move(status));
}

void BearingSimRos::set_thread_scheduling() {
  // With other processes on both cores, a normal thread can wake 5-10 ms late; SCHED_FIFO
  // wakes it on time. Safe: the thread sleeps about 95 % of each chunk period, and never
  // asks for it when running as fast as possible.
  if (!real_time_ || realtime_priority_ <= 0) {
    diagnostics_->set_scheduling("normal (SCHED_OTHER)");
    return;
  }
  sched_param p{};
  p.sched_priority = std::min(realtime_priority_, sched_get_priority_max(SCHED_FIFO));
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  if (err != 0) {
    ROS_WARN("bearing_sim_node: cannot use SCHED_FIFO priority %d for the simulation thread (%s); "
             "running with normal scheduling", p.sched_priority, std::strerror(err));
    diagnostics_->set_scheduling(std::string("normal (SCHED_FIFO refused: ") + std::strerror(err) + ")");
  } else {
    diagnostics_->set_scheduling("SCHED_FIFO priority " + std::to_string(p.sched_priority));
  }
}

void BearingSimRos::run() {
  using Clock = RealtimePacer::Clock;
  set_thread_scheduling();
  apply_pending();  // the initial dynamic_reconfigure settings
  const Clock::time_point start = Clock::now();
  // Real time: stamps on the ROS clock, sample 0 at start. Otherwise simulated time itself
  // is the clock (published on /clock).
  ros_start_ = real_time_ ? ros::Time::now() : ros::Time(0, 0);
  const RealtimePacer pacer(sample_rate_hz_, start);
  while (!stop_ && ros::ok()) {
    if (pending_flag_.load(std::memory_order_acquire)) apply_pending();
    const std::uint64_t last_index = assembler_->next_sample() + assembler_->current_target() - 1;
    // Compute a chunk only once its last sample is due, so inputs received up to then apply.
    if (real_time_ && !pacer.sleep_until_due(last_index, stop_)) break;
    bool full = false;
    while (!full) {
      // New inputs take effect from the next sample.
      if (pending_flag_.load(std::memory_order_acquire)) apply_pending();
      if (load_ramp_.active()) source_->dynamics().set_load(load_ramp_.next());
      const SampleSource::Sample sample = source_->next();
      if (sample.diverged) {
        ROS_ERROR_THROTTLE(1.0, "bearing_sim_node: %s; reset to the static equilibrium",
                           source_->last_divergence().c_str());
        diagnostics_->record_divergence(source_->last_divergence());
      }
      full = assembler_->add(sample.index, *sample.state);
      // The measured signal (sensor, or the ideal x without one): L and health.
      bool measured = true;
      double measured_x = sample.state->acceleration[0];
      if (sensor_) {
        Eigen::Vector3d y;
        measured = sensor_->push(*sample.state, &y);
        if (measured) {
          measured_x = y[0];
          if (sensor_assembler_->add(sensor_assembler_->next_sample(), y, sample.state->displacement))
            publish_sensor_chunk();
        }
      }
      if (measured) {
        level_rms_->add(measured_x);
        health_samples_.push_back(static_cast<float>(measured_x));
      }
      if (level_divider_->due(sample.index)) publish_level(sample);
      if (ball_loads_divider_->due(sample.index)) publish_ball_loads(sample);
      if (health_divider_->due(sample.index)) feed_health(true, sample.time_s);
    }
    SampleChunk chunk = assembler_->take();
    const std::uint64_t chunk_size = chunk.size();
    const ros::Time first_stamp = stamp_of(chunk.first_sample);
    VibrationChunk msg;
    fill_vibration_chunk(std::move(chunk), first_stamp, frame_id_, sample_rate_hz_, &msg);
    if (!sensor_) vibration_pub_.publish(msg);  // without a sensor `vibration` is the ideal acceleration
    ideal_pub_.publish(msg);
    // Hand the measured samples over once per chunk; Miner damage for the chunk's inputs.
    feed_health(false, 0.0);
    health_->add_operation(source_->dynamics().load(), source_->dynamics().ring_speed_rad_s(),
                           static_cast<double>(chunk_size) / sample_rate_hz_);
    if (publish_clock_) {
      rosgraph_msgs::Clock clock;
      clock.clock = stamp_of(last_index);
      clock_pub_.publish(clock);
    }
    const Clock::time_point now = Clock::now();
    const double lateness_s = pacer.lateness_s(last_index, now);
    const double chunk_period_s = static_cast<double>(chunk_size) / sample_rate_hz_;
    diagnostics_->record_chunk(lateness_s, real_time_ && lateness_s > chunk_period_s, last_index + 1,
                               static_cast<double>(last_index + 1) / sample_rate_hz_,
                               std::chrono::duration<double>(now - start).count());
  }
}

}  // namespace ros_node
}  // namespace bearing_sim
