#include "bearing_sim/ros/bearing_sim_ros.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <rosgraph_msgs/Clock.h>
#include <boost/make_shared.hpp>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/InputRejection.h"
#include "bearing_sim/RingDeformation.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "bearing_sim/ros/message_conversion.hpp"
#include "bearing_sim/ros/private_parameters.hpp"
#include "bearing_sim/ros/sim_node_parameters.hpp"
#include "bearing_sim/runtime/realtime_pacer.hpp"

namespace bearing_sim {
namespace ros_node {
namespace {

std::string fmt(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Three significant digits: a spall is 1 um to some cm wide (kMinSpallSizeM up).
std::string significant(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string describe(const Spall& s) {
  std::string what = std::string(surface_name(s.surface)) + " spall";
  if (s.surface == Surface::Ball) what += " on ball " + std::to_string(s.ball);
  return what + " at " + fmt(s.position_rad, 3) + " rad, " + significant(s.width_m * 1e3) + " mm wide, " +
         significant(s.depth_m * 1e6) + " um deep";
}

// Every thread of this process (ROS I/O, spinner, timers, the health worker started
// later inherits it) at SCHED_FIFO priority 1: above every normal process, below the
// simulation and publisher threads. The publisher shares roscpp's internal locks with
// these threads; at normal priority a busy machine could deschedule one while it holds
// such a lock and stall the publisher for a time slice (priority inversion). Returns a
// description for /diagnostics.
std::string raise_process_threads_to_fifo() {
  int raised = 0, refused = 0, last_err = 0;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) {
    const pid_t tid = static_cast<pid_t>(std::stol(entry.path().filename().string()));
    sched_param p{};
    p.sched_priority = 1;
    if (sched_setscheduler(tid, SCHED_FIFO, &p) == 0) ++raised;
    else ++refused, last_err = errno;
  }
  if (refused == 0) return "SCHED_FIFO priority 1 (" + std::to_string(raised) + " threads)";
  return "normal (SCHED_FIFO refused for " + std::to_string(refused) + " threads: " + std::strerror(last_err) + ")";
}

}  // namespace

BearingSimRos::BearingSimRos(ros::NodeHandle nh, ros::NodeHandle pnh, ThreadScope thread_scope)
    : nh_(nh), pnh_(pnh), thread_scope_(thread_scope) {
  // Every parameter checked before anything starts: a bad one stops the node, naming it.
  const SimNodeParameters params = read_sim_node_parameters(private_parameters(pnh_), pnh_.getNamespace());
  const std::string& bearing_file = params.bearing_file;
  BearingModel model(load_bearing_config(bearing_file));
  if (!model.config().has_dynamics())
    throw std::runtime_error("bearing file " + bearing_file + " has no rotating_mass_kg: no dynamics possible");

  sample_rate_hz_ = params.sample_rate_hz;
  load_ramp_ = runtime::LoadRamp(static_cast<std::uint64_t>(std::llround(params.load_ramp_s * sample_rate_hz_)));
  const int substeps = params.substeps;
  const IntegrationMethod method = params.integrator;
  real_time_ = params.real_time;
  publish_clock_ = params.publish_clock;
  max_real_time_factor_ = params.max_real_time_factor;
  realtime_priority_ = params.realtime_priority;
  lock_memory_ = params.lock_memory;
  lead_s_ = params.lead_s;
  const bool outer = model.config().rotating_ring == RotatingRing::Outer;
  frame_id_ = params.frame_id.value_or(outer ? "bearing_outer_ring" : "bearing_inner_ring");
  bearing_frame_id_ = params.bearing_frame_id;
  limits_ = params.limits;
  DiagnosticsSettings diag;
  diag.real_time = real_time_;
  diag.max_lag_s = params.max_lag_s;
  diag.hold_s = params.diagnostic_hold_s;
  const double diagnostic_period_s = params.diagnostic_period_s;

  const Vector5 load = params.initial_load;
  const double speed = params.initial_speed_rad_s;
  // The initial inputs obey the same rules as the topics, but a bad one stops the node.
  const runtime::InputCheck load_check = runtime::check_load(load, limits_, &model);
  if (!load_check.accepted) throw std::runtime_error("initial load: " + load_check.reason);
  const runtime::InputCheck speed_check = runtime::check_speed(speed, limits_, &model);
  if (!speed_check.accepted) throw std::runtime_error("initial speed: " + speed_check.reason);
  // A bearing value that makes a mode no bearing has would stall the automatic step.
  if (substeps == 0) {
    const runtime::InputCheck work_check = runtime::check_integrator_work(model, load);
    if (!work_check.accepted) throw std::runtime_error("bearing file " + bearing_file + ": " + work_check.reason);
  }
  accepted_load_ = load;
  accepted_speed_rad_s_ = speed;
  accepted_max_pressure_Pa_ = load_check.max_contact_pressure_Pa;

  validation_model_ = std::make_unique<BearingModel>(model);
  // The rigid ring's dynamics, or the flexible ring's with a flexible_ring block.
  std::unique_ptr<RingDynamics> dynamics;
  try {
    dynamics = make_ring_dynamics(model, load, speed, DynamicsOptions{sample_rate_hz_, substeps, true, method});
  } catch (const InvalidInputError& e) {
    throw std::runtime_error("bearing file " + bearing_file + " with ~integrator " + integration_method_name(method) +
                             ": " + e.what());
  }
  substeps_ = dynamics->substeps();

  // Virtual sensor: `vibration` carries what it records, at its output rate.
  const std::string& sensor_file = params.sensor_file;
  std::unique_ptr<runtime::TriaxialSensor> sensor;
  measured_rate_hz_ = sample_rate_hz_;
  sensor_description_ = "ideal ring acceleration";
  if (!sensor_file.empty()) {
    try {
      sensor = std::make_unique<runtime::TriaxialSensor>(load_accelerometer_config(sensor_file), sample_rate_hz_);
    } catch (const InvalidInputError& e) {
      throw std::runtime_error("sensor file " + sensor_file + " at ~sample_rate_hz " + fmt(sample_rate_hz_, 1) +
                               " Hz: " + e.what());
    }
    measured_rate_hz_ = sensor->output_rate_hz();
    sensor_description_ = "sensor: " + sensor->config().name;
  }

  // Outgoing queues (per subscriber; memory is used only while one lags) hold about 10 s of
  // each stream in real time: a recorder or bridge descheduled for a second on a busy machine
  // loses nothing. As fast as possible everything comes at 10-30x its rate: 20 times deeper.
  const int depth = real_time_ ? 1 : 20;
  vibration_pub_ = nh_.advertise<VibrationChunk>("vibration", 1000 * depth);
  ideal_pub_ = nh_.advertise<VibrationChunk>("vibration_ideal", 1000 * depth);
  health_pub_ = nh_.advertise<BearingHealth>("health", 10 * depth);
  level_pub_ = nh_.advertise<VibrationLevel>("vibration_level", 100 * depth);
  ball_loads_pub_ = nh_.advertise<BallLoads>("ball_loads", 300 * depth);
  deformation_pub_ = nh_.advertise<RingDeformation>("ring_deformation", 300 * depth);
  if (publish_clock_) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 100);
  // Before the reconfigure server and the input subscribers, whose callbacks may refuse.
  rejected_pub_ = nh_.advertise<InputRejection>("rejected_inputs", 100);

  diagnostics_ = std::make_unique<NodeDiagnostics>(nh_, pnh_, "bearing_sim: " + model.config().name, diag);

  // Health: analysed on a worker thread (HealthMonitor), never in the simulation thread.
  runtime::HealthSettings health;
  health.sample_rate_hz = measured_rate_hz_;
  health.window_s = params.health_window_s;
  health.life.dynamic_load_rating_N = params.dynamic_load_rating_N;
  // Envelope band around the sensor's transmission-path resonance, where impacts ring.
  const double default_resonance_hz = sensor ? sensor->config().path_resonance_hz : 0.0;
  health.analysis.resonance_hz = params.envelope_resonance_hz.value_or(default_resonance_hz);
  health.analysis.envelope_band_width_hz = params.envelope_band_width_hz;
  health.analysis.thresholds.fault_snr_db = params.fault_snr_db;
  const double health_rate_hz = params.health_rate_hz;
  health_ = std::make_unique<runtime::HealthMonitor>(model, load, speed, health,
                                                     [this](const runtime::HealthReport& r) { publish_health(r); });
  pipeline_ = std::make_unique<runtime::SamplePipeline>(std::move(dynamics), std::move(sensor),
                                                        runtime::OutputSettings{}, health_rate_hz);
  publish_model_state();
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(diagnostic_period_s),
                                           [this](const ros::WallTimerEvent&) { diagnostics_->update(); });

  // dynamic_reconfigure: clearance and damping start from the bearing file unless the
  // parameters were set explicitly (the server would otherwise impose the cfg defaults);
  // the other settings from the parameters, else the cfg defaults.
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<BearingSimConfig>>(reconfigure_mutex_, pnh_);
  BearingSimConfig initial = BearingSimConfig::__getDefault__();
  initial.clearance_um = params.clearance_um.value_or(model.config().clearance_m * 1e6);
  initial.contact_damping_Ns_per_m = params.contact_damping_Ns_per_m.value_or(model.config().contact_damping_Ns_per_m);
  if (params.chunk_samples) initial.chunk_samples = *params.chunk_samples;
  if (params.level_window_s) initial.level_window_s = *params.level_window_s;
  if (params.level_rate_hz) initial.level_rate_hz = *params.level_rate_hz;
  if (params.ball_loads_rate_hz) initial.ball_loads_rate_hz = *params.ball_loads_rate_hz;
  reconfigure_server_->updateConfig(initial);
  reconfigure_server_->setCallback(
      [this](BearingSimConfig& config, std::uint32_t level) { on_reconfigure(config, level); });

  load_sub_ = nh_.subscribe("load", 10, &BearingSimRos::on_load, this);
  inject_srv_ = nh_.advertiseService("inject_defect", &BearingSimRos::on_inject_defect, this);
  clear_srv_ = nh_.advertiseService("clear_defects", &BearingSimRos::on_clear_defects, this);
  speed_sub_ = nh_.subscribe("speed", 10, &BearingSimRos::on_speed, this);
  ring_temperature_sub_ = nh_.subscribe("ring_temperature_difference_K", 10, &BearingSimRos::on_ring_temperature, this);
  ROS_INFO(
      "bearing_sim_node: '%s', %d balls, %.0f Hz dynamics, %g %s steps per sample, %s; "
      "vibration: %s at %.0f Hz",
      model.config().name.c_str(), model.ball_count(), sample_rate_hz_, substeps_, integration_method_name(method),
      real_time_ ? "real time" : "as fast as possible", sensor_description_.c_str(), measured_rate_hz_);
}

BearingSimRos::~BearingSimRos() { stop(); }

void BearingSimRos::start() {
  if (sim_thread_.joinable()) return;
  stop_ = false;
  lock_memory();
  // Its own process: every thread of it at SCHED_FIFO 1. A guest in a nodelet manager: the
  // manager's and the other nodelets' threads are not the node's to change (docs/node.md).
  if (real_time_ && realtime_priority_ > 1 && thread_scope_ == ThreadScope::Process)
    diagnostics_->set_realtime_value("other threads scheduling", raise_process_threads_to_fifo());
  start_health_worker();
  // Real time: stamps on the ROS clock, sample 0 at start. Otherwise simulated time itself
  // is the clock (published on /clock).
  wall_start_ = runtime::RealtimePacer::Clock::now();
  ros_start_ = real_time_ ? ros::Time::now() : ros::Time(0, 0);
  const auto lead =
      std::chrono::duration_cast<runtime::RealtimePacer::Clock::duration>(std::chrono::duration<double>(lead_s_));
  scheduler_.emplace(runtime::RealtimePacer(sample_rate_hz_, wall_start_), lead);
  if (!real_time_ && max_real_time_factor_ > 0.0)
    bounded_pacer_.emplace(sample_rate_hz_ * max_real_time_factor_, wall_start_);
  // Speed figures mean little without the CPU and the SIMD code path that produced them.
  diagnostics_->set_realtime_value("CPU", cpu_model_name());
  diagnostics_->set_realtime_value("SIMD target", simd_target_name());
  if (real_time_) {
    diagnostics_->set_realtime_value("lead (ms)", fmt(lead_s_ * 1e3, 1));
    publisher_thread_ = std::thread([this] { run_publisher(); });
  }
  sim_thread_ = std::thread([this] { run(); });
}

void BearingSimRos::start_health_worker() {
  if (thread_scope_ == ThreadScope::Process || !real_time_ || realtime_priority_ <= 1) {
    health_->start();  // in its own process at the scheduling just given to every thread
    return;
  }
  // A new thread inherits its creator's scheduling: the worker is created by a short-lived
  // thread at SCHED_FIFO 1, so that no thread of the manager changes.
  std::string scheduling;
  std::thread([this, &scheduling] {
    sched_param p{};
    p.sched_priority = 1;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
    scheduling = err == 0 ? "health worker SCHED_FIFO priority 1; nodelet manager's threads unchanged"
                          : std::string("normal (SCHED_FIFO refused for the health worker: ") + std::strerror(err) +
                                "); nodelet manager's threads unchanged";
    health_->start();
  }).join();
  diagnostics_->set_realtime_value("other threads scheduling", scheduling);
}

void BearingSimRos::stop() {
  stop_ = true;
  queue_cv_.notify_all();
  if (sim_thread_.joinable()) sim_thread_.join();
  if (publisher_thread_.joinable()) publisher_thread_.join();
  if (health_) health_->stop();  // its callback publishes: stop it before the publishers go
}

// ---------------------------------------------------------------------------------------
// ROS callbacks (spinner thread)

void BearingSimRos::reject_input(const std::string& input, const std::string& reason, const ros::Time& input_stamp) {
  ROS_WARN_THROTTLE(1.0, "bearing_sim_node: input rejected, keeping the last good inputs: %s", reason.c_str());
  diagnostics_->record_rejected_input(reason);
  // Whoever sent it learns that the simulation does not have it (the scenario player stops).
  InputRejection m;
  m.header.stamp = ros::Time::now();
  m.input = input;
  m.reason = reason;
  m.input_stamp = input_stamp;
  rejected_pub_.publish(m);
}

void BearingSimRos::on_load(const geometry_msgs::WrenchStamped::ConstPtr& msg) {
  const Vector5 load = load_from_wrench(msg->wrench);
  const runtime::InputCheck check = runtime::check_load(load, limits_, validation_model_.get());
  if (!check.accepted) return reject_input("load", check.reason, msg->header.stamp);
  if (check.max_contact_pressure_Pa > kPermissibleContactPressurePa)
    ROS_WARN_THROTTLE(5.0, "bearing_sim_node: static contact pressure %.0f MPa exceeds the ISO 76 limit of 4200 MPa",
                      check.max_contact_pressure_Pa * 1e-6);
  accepted_load_ = load;
  accepted_max_pressure_Pa_ = check.max_contact_pressure_Pa;
  {
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
    pending_.load = load;
  }
  pending_flag_ = true;
  publish_model_state();
}

void BearingSimRos::on_speed(const std_msgs::Float64::ConstPtr& msg) {
  const runtime::InputCheck check = runtime::check_speed(msg->data, limits_, validation_model_.get());
  if (!check.accepted) return reject_input("speed", check.reason);
  accepted_speed_rad_s_ = msg->data;
  {
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
    pending_.ring_speed_rad_s = msg->data;
  }
  pending_flag_ = true;
  publish_model_state();
}

bool BearingSimRos::on_inject_defect(InjectDefect::Request& req, InjectDefect::Response& res) {
  Spall spall;
  spall.position_rad = req.position_rad;
  spall.ball = req.ball;
  spall.row = req.row;
  spall.width_m = req.width_m;
  spall.depth_m = req.depth_m;
  spall.width_growth_m_per_s = req.width_growth_m_per_s;
  spall.depth_growth_m_per_s = req.depth_growth_m_per_s;
  try {
    spall.surface = parse_surface(req.surface);
    // Validated here against the bearing (the core's checks), so that the caller gets the
    // reason; the sim thread then adds it from its next sample.
    validation_model_->add_spall(spall);
  } catch (const std::exception& e) {  // InvalidInputError, or anything else: never leaves the callback
    res.success = false;
    res.message = "defect does not fit the bearing '" + validation_model_->config().name + "': " + e.what();
    res.defects_present = static_cast<std::uint32_t>(validation_model_->imperfections().spalls().size());
    ROS_WARN("bearing_sim_node: inject_defect refused: %s", res.message.c_str());
    return true;
  }
  {
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
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
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
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
  // Every value checked here (the server's clamp lets NaN through) so that the sim thread never
  // sees a bad one; a refused value reverts to the last good one, which the server publishes back.
  const auto refuse = [this](const runtime::InputCheck& c) {
    if (!c.accepted) reject_input("dynamic_reconfigure", c.reason);
    return !c.accepted;
  };
  if (refuse(runtime::check_setting(config.clearance_um, runtime::kClearanceUm)))
    config.clearance_um = old.clearance_m * 1e6;
  if (refuse(runtime::check_setting(config.contact_damping_Ns_per_m, runtime::kContactDampingNsPerM)))
    config.contact_damping_Ns_per_m = old.contact_damping_Ns_per_m;
  const runtime::OutputSettings good = accepted_settings_.value_or(runtime::OutputSettings{});
  if (refuse(runtime::check_setting(config.chunk_samples, runtime::kChunkSamples)))
    config.chunk_samples = static_cast<int>(good.chunk_samples);
  if (refuse(runtime::check_setting(config.level_window_s, runtime::kLevelWindowS)))
    config.level_window_s = good.level_window_s;
  if (refuse(runtime::check_setting(config.level_rate_hz, runtime::kLevelRateHz)))
    config.level_rate_hz = good.level_rate_hz;
  if (refuse(runtime::check_setting(config.ball_loads_rate_hz, runtime::kBallLoadsRateHz)))
    config.ball_loads_rate_hz = good.ball_loads_rate_hz;

  const double clearance_m = config.clearance_um * 1e-6;
  std::optional<BearingModel> new_model;
  if (clearance_m != old.clearance_m || config.contact_damping_Ns_per_m != old.contact_damping_Ns_per_m) {
    BearingConfig changed = old;
    changed.clearance_m = clearance_m;
    changed.contact_damping_Ns_per_m = config.contact_damping_Ns_per_m;
    new_model = validated_model(changed, "dynamic_reconfigure",
                                "clearance " + std::to_string(config.clearance_um) + " um, contact damping " +
                                    std::to_string(config.contact_damping_Ns_per_m) + " N*s/m");
    if (!new_model) {
      config.clearance_um = old.clearance_m * 1e6;
      config.contact_damping_Ns_per_m = old.contact_damping_Ns_per_m;
    }
  }
  runtime::OutputSettings settings;
  settings.chunk_samples = static_cast<std::size_t>(config.chunk_samples);
  settings.level_window_s = config.level_window_s;
  settings.level_rate_hz = config.level_rate_hz;
  settings.ball_loads_rate_hz = config.ball_loads_rate_hz;
  accepted_settings_ = settings;
  if (new_model) *validation_model_ = *new_model;
  {
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
    if (new_model) pending_.model = std::move(new_model);
    pending_.settings = settings;
  }
  pending_flag_ = true;
  publish_model_state();
}

std::optional<BearingModel> BearingSimRos::validated_model(const BearingConfig& changed, const std::string& input,
                                                           const std::string& what) {
  try {
    BearingModel model(changed);  // throws for a clearance the ring temperatures take out of range
    model.set_deflection_offsets(validation_model_->deflection_offsets());
    // The spalls present now, not only those of the file (the sim thread re-times them).
    model.clear_spalls();
    for (const Spall& sp : validation_model_->imperfections().spalls()) model.add_spall(sp);
    runtime::InputCheck check = runtime::check_load(accepted_load_, limits_, &model);
    if (check.accepted) {
      const runtime::InputCheck work = runtime::check_integrator_work(model, accepted_load_);  // would stall the step
      if (!work.accepted) check = work;
    }
    if (!check.accepted) {
      reject_input(input, what + ": " + check.reason);
      return std::nullopt;
    }
    accepted_max_pressure_Pa_ = check.max_contact_pressure_Pa;
    return model;
  } catch (const std::exception& e) {  // a model the core refuses: no exception leaves the callback
    reject_input(input, what + " refused: " + e.what());
    return std::nullopt;
  }
}

void BearingSimRos::on_ring_temperature(const std_msgs::Float64::ConstPtr& msg) {
  const double dT = msg->data;
  const std::string what = "ring_temperature_difference_K " + std::to_string(dT);
  if (!std::isfinite(dT)) return reject_input("ring_temperature_difference_K", what + " refused: not a finite number");
  const BearingConfig& old = validation_model_->config();
  if (dT == old.ring_temperature_difference_K) return;
  BearingConfig changed = old;
  changed.ring_temperature_difference_K = dT;
  std::optional<BearingModel> model = validated_model(changed, "ring_temperature_difference_K", what);
  if (!model) return;
  *validation_model_ = *model;
  {
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
    pending_.model = std::move(model);
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
  s.ring_temperature_difference_K = c.ring_temperature_difference_K;
  s.operating_clearance_m = validation_model_->clearance_m();
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
    std::lock_guard<runtime::PriorityInheritanceMutex> lock(pending_mutex_);
    p = std::move(pending_);
    pending_ = Pending{};
    pending_flag_ = false;
  }
  RingDynamics& dynamics = pipeline_->source().ring();
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
  if (p.settings) pipeline_->apply_settings(*p.settings);
}

ros::Time BearingSimRos::stamp_of(std::uint64_t sample_index) const {
  const long double ns = static_cast<long double>(sample_index) * 1.0e9L / sample_rate_hz_;
  ros::Duration offset;
  offset.fromNSec(static_cast<std::int64_t>(std::llround(ns)));
  return ros_start_ + offset;
}

void BearingSimRos::level(const runtime::SampleSource::Sample& sample, double accel_rms, double window_s) {
  auto msg = boost::make_shared<VibrationLevel>();
  msg->header.stamp = stamp_of(sample.index);
  msg->header.frame_id = frame_id_;
  msg->accel_rms = accel_rms;
  msg->level_db = vibration_level_db(accel_rms);
  msg->window_s = window_s;
  bundle_->actions.emplace_back([this, msg] {
    msg->header.seq = level_seq_++;
    level_pub_.publish(msg);
  });
}

bool BearingSimRos::wants_ball_loads() const {
  return ball_loads_pub_.getNumSubscribers() > 0;  // per-ball states cost a few microseconds per ball
}

void BearingSimRos::ball_loads(const runtime::SampleSource::Sample& sample, const BearingModel& model,
                               const std::vector<BallState>& balls) {
  auto msg = boost::make_shared<BallLoads>();
  msg->header.stamp = stamp_of(sample.index);
  msg->header.frame_id = bearing_frame_id_;
  fill_ball_loads(balls, model.rows(), model.balls_per_row(), sample.state->cage_angle_rad, msg.get());
  bundle_->actions.emplace_back([this, msg] {
    msg->header.seq = ball_loads_seq_++;
    ball_loads_pub_.publish(msg);
  });
}

bool BearingSimRos::wants_ring_deformation() const { return deformation_pub_.getNumSubscribers() > 0; }

void BearingSimRos::ring_deformation(const runtime::SampleSource::Sample& sample,
                                     const FlexibleBearing::Deformation& deformation) {
  auto msg = boost::make_shared<RingDeformation>();
  msg->header.stamp = stamp_of(sample.index);
  msg->header.frame_id = bearing_frame_id_;
  msg->ring_angle = std::remainder(deformation.ring_angle_rad, 2.0 * kPi);
  msg->azimuth.assign(deformation.azimuth_rad.begin(), deformation.azimuth_rad.end());
  msg->radial.assign(deformation.radial_m.begin(), deformation.radial_m.end());
  msg->axial.assign(deformation.axial_m.begin(), deformation.axial_m.end());
  bundle_->actions.emplace_back([this, msg] {
    msg->header.seq = deformation_seq_++;
    deformation_pub_.publish(msg);
  });
}

void BearingSimRos::measured_chunk(runtime::SampleChunk&& chunk) {
  // Sensor sample k is the output at dynamics sample (k + 1) R - 1 (docs/sensor.md).
  const std::uint64_t r = static_cast<std::uint64_t>(pipeline_->sensor()->decimation_ratio());
  const ros::Time first_stamp = stamp_of((chunk.first_sample + 1) * r - 1);
  auto msg = boost::make_shared<VibrationChunk>();
  fill_vibration_chunk(std::move(chunk), first_stamp, frame_id_, measured_rate_hz_, msg.get());
  bundle_->actions.emplace_back([this, msg] {
    msg->header.seq = vibration_seq_++;
    vibration_pub_.publish(msg);
  });
}

void BearingSimRos::ideal_chunk(runtime::SampleChunk&& chunk) {
  bundle_->samples = chunk.size();
  bundle_->last_index = chunk.first_sample + chunk.size() - 1;
  const ros::Time first_stamp = stamp_of(chunk.first_sample);
  auto msg = boost::make_shared<VibrationChunk>();
  fill_vibration_chunk(std::move(chunk), first_stamp, frame_id_, sample_rate_hz_, msg.get());
  const bool ideal_is_vibration = pipeline_->sensor() == nullptr;
  bundle_->actions.emplace_back([this, msg, ideal_is_vibration] {
    msg->header.seq = ideal_seq_++;                       // both topics publish every ideal chunk then: the same count
    if (ideal_is_vibration) vibration_pub_.publish(msg);  // without a sensor `vibration` is the ideal acceleration
    ideal_pub_.publish(msg);
  });
}

void BearingSimRos::health_samples(std::vector<float>&& x, std::optional<double> analysis_time_s) {
  // At the samples' time, with the chunk: the monitor never sees the future.
  bundle_->actions.emplace_back([this, x = std::move(x), analysis_time_s] {
    health_->push(x.data(), x.size());
    if (analysis_time_s) health_->request_analysis(*analysis_time_s);
  });
}

void BearingSimRos::chunk_end(std::uint64_t last_index, std::size_t samples, const Vector5& load,
                              double ring_speed_rad_s) {
  const double chunk_s = static_cast<double>(samples) / sample_rate_hz_;
  bundle_->actions.emplace_back([this, load, ring_speed_rad_s, chunk_s] {
    health_->add_operation(load, ring_speed_rad_s, chunk_s);  // Miner damage for the chunk's inputs
  });
  if (publish_clock_) {
    auto clock = boost::make_shared<rosgraph_msgs::Clock>();
    clock->clock = stamp_of(last_index);
    bundle_->actions.emplace_back([this, clock] { clock_pub_.publish(clock); });
  }
}

void BearingSimRos::divergence(const std::string& message) {
  ROS_ERROR_THROTTLE(1.0, "bearing_sim_node: %s; reset to the static equilibrium", message.c_str());
  diagnostics_->record_divergence(message);
}

void BearingSimRos::publish_health(const runtime::HealthReport& report) {
  const auto shared = boost::make_shared<BearingHealth>();
  BearingHealth& msg = *shared;
  msg.header.stamp = ros_start_ + ros::Duration(report.end_time_s);
  msg.header.frame_id = frame_id_;
  fill_bearing_health(report, sensor_description_, measured_rate_hz_, &msg);
  msg.header.seq = health_seq_++;
  health_pub_.publish(shared);  // not changed after this: read below only

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
    add("velocity RMS, ISO 20816-3 band (mm/s)", fmt(msg.velocity_rms_mm_s, 4));
    add("ISO 20816-3 zone", msg.velocity_zone);
    add("envelope band (Hz)", fmt(msg.envelope_low_hz, 0) + "-" + fmt(msg.envelope_high_hz, 0));
    for (const EnvelopeLine& l : msg.faults)
      add("envelope " + l.label + " " + fmt(l.expected_hz, 2) + " Hz",
          "peak " + fmt(l.peak_hz, 2) + " Hz, " + fmt(l.snr_db, 1) + " dB over noise" + ", " +
              std::to_string(l.harmonics_found) + " harmonics" +
              (l.sidebands_required ? ", " + std::to_string(l.sidebands_found) + "/2 sidebands" : std::string()) +
              (l.suspected ? " (suspected)" : "") + (l.note.empty() ? std::string() : "; " + l.note));
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

std::string BearingSimRos::set_thread_scheduling(int priority) {
  // With other processes on both cores, a normal thread can wake 5-10 ms late; SCHED_FIFO
  // wakes it on time. Safe: both threads sleep most of each chunk period, and never ask
  // for it when running as fast as possible.
  if (!real_time_ || priority <= 0) return "normal (SCHED_OTHER)";
  sched_param p{};
  p.sched_priority = std::min(priority, sched_get_priority_max(SCHED_FIFO));
  const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  if (err != 0) {
    ROS_WARN("bearing_sim_node: cannot use SCHED_FIFO priority %d (%s); running with normal scheduling",
             p.sched_priority, std::strerror(err));
    return std::string("normal (SCHED_FIFO refused: ") + std::strerror(err) + ")";
  }
  return "SCHED_FIFO priority " + std::to_string(p.sched_priority);
}

void BearingSimRos::lock_memory() {
  // No page fault in the real-time path (the queue, messages, the dynamics' buffers).
  if (!real_time_ || !lock_memory_) {
    diagnostics_->set_realtime_value("memory locked", real_time_ ? "no (~lock_memory false)" : "no (not real time)");
    return;
  }
  // With MCL_FUTURE every later allocation counts against RLIMIT_MEMLOCK and fails beyond
  // it: lock only when the limit cannot bite (root, unlimited or >= 1 GiB; the node needs
  // ~100 MB).
  rlimit limit{};
  const bool roomy = geteuid() == 0 || (getrlimit(RLIMIT_MEMLOCK, &limit) == 0 &&
                                        (limit.rlim_cur == RLIM_INFINITY || limit.rlim_cur >= (rlim_t(1) << 30)));
  if (!roomy) {
    const std::string why = "RLIMIT_MEMLOCK " + std::to_string(limit.rlim_cur / 1024) + " kB";
    ROS_WARN("bearing_sim_node: memory not locked (%s; raise it, e.g. ulimit -l unlimited)", why.c_str());
    diagnostics_->set_realtime_value("memory locked", "no (" + why + ")");
    return;
  }
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    const int err = errno;
    ROS_WARN("bearing_sim_node: mlockall refused (%s); memory not locked", std::strerror(err));
    diagnostics_->set_realtime_value("memory locked", std::string("no (mlockall refused: ") + std::strerror(err) + ")");
  } else {
    diagnostics_->set_realtime_value("memory locked", "yes (mlockall)");
  }
}

BearingSimRos::ChunkBundle BearingSimRos::compute_chunk() {
  ChunkBundle bundle;
  bundle_ = &bundle;
  runtime::SampleSource& source = pipeline_->source();
  bool full = false;
  while (!full) {
    // New inputs take effect from the next sample not yet computed.
    if (pending_flag_.load(std::memory_order_acquire)) apply_pending();
    if (load_ramp_.active()) source.ring().set_load(load_ramp_.next());
    full = pipeline_->step(*this);
  }
  bundle_ = nullptr;
  return bundle;
}

void BearingSimRos::publish_bundle(ChunkBundle& bundle) {
  for (auto& action : bundle.actions) action();
  const runtime::RealtimePacer::Clock::time_point now = runtime::RealtimePacer::Clock::now();
  const double lateness_s = scheduler_->pacer().lateness_s(bundle.last_index, now);
  const double chunk_period_s = static_cast<double>(bundle.samples) / sample_rate_hz_;
  diagnostics_->record_chunk(lateness_s, real_time_ && lateness_s > chunk_period_s, bundle.last_index + 1,
                             static_cast<double>(bundle.last_index + 1) / sample_rate_hz_,
                             std::chrono::duration<double>(now - wall_start_).count());
}

void BearingSimRos::run() {
  using Clock = runtime::RealtimePacer::Clock;
  // Below the publisher: publishing on time matters more than computing ahead.
  diagnostics_->set_scheduling(set_thread_scheduling(realtime_priority_ > 0 ? std::max(1, realtime_priority_ - 1) : 0));
  apply_pending();  // the initial dynamic_reconfigure settings
  const runtime::LeadScheduler& scheduler = *scheduler_;
  while (!stop_ && ros::ok()) {
    if (pending_flag_.load(std::memory_order_acquire)) apply_pending();
    if (!real_time_) {  // as fast as possible: publish each chunk as soon as computed
      ChunkBundle bundle = compute_chunk();
      publish_bundle(bundle);
      // A bounded factor: the chunk's end is due at that multiple of real time.
      if (bounded_pacer_ && !bounded_pacer_->sleep_until_due(bundle.last_index + 1, stop_)) break;
      continue;
    }
    const std::size_t target = pipeline_->current_chunk_samples();
    const std::uint64_t last_index = pipeline_->current_chunk_last_index();
    {
      // Wait until the chunk may be computed (its start within the lead, room in the queue);
      // in slices, so that stop and new inputs are noticed.
      std::unique_lock<std::mutex> lock(queue_mutex_);
      const Clock::time_point now = Clock::now();
      if (!scheduler.may_compute(now, ready_.size(), last_index, target)) {
        Clock::time_point wake = now + std::chrono::milliseconds(50);
        if (ready_.size() < scheduler.max_queued(target)) wake = std::min(wake, scheduler.compute_start(last_index));
        queue_cv_.wait_until(lock, wake);
        continue;
      }
    }
    ChunkBundle bundle = compute_chunk();
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      ready_.push_back(std::move(bundle));
    }
    queue_cv_.notify_all();
  }
}

void BearingSimRos::run_publisher() {
  diagnostics_->set_realtime_value("publisher thread scheduling", set_thread_scheduling(realtime_priority_));
  const runtime::RealtimePacer& pacer = scheduler_->pacer();
  while (!stop_ && ros::ok()) {
    std::uint64_t last_index = 0;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      if (ready_.empty()) {
        queue_cv_.wait_for(lock, std::chrono::milliseconds(50));
        continue;
      }
      last_index = ready_.front().last_index;  // only this thread pops: the head stays
    }
    // Never before its time; at once when late (catching up, every chunk once, in order).
    if (!pacer.sleep_until_due(last_index, stop_)) break;
    ChunkBundle bundle;
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      bundle = std::move(ready_.front());
      ready_.pop_front();
    }
    queue_cv_.notify_all();  // room for the sim thread
    publish_bundle(bundle);
  }
}

}  // namespace ros_node
}  // namespace bearing_sim
