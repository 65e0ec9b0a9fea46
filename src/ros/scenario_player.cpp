#include "bearing_sim/ros/scenario_player.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <geometry_msgs/WrenchStamped.h>
#include <ros/callback_queue.h>
#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>

#include "bearing_sim/DefectState.h"
#include "bearing_sim/InjectDefect.h"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/imperfections.hpp"
#include "bearing_sim/ros/message_conversion.hpp"

namespace bearing_sim {
namespace ros_node {
namespace {

Scenario load_scenario(const ros::NodeHandle& pnh, std::string* file) {
  if (!pnh.getParam("scenario_file", *file) || file->empty())
    throw std::runtime_error("parameter ~scenario_file (path of the scenario YAML) is required");
  return Scenario::load(*file);  // ConfigError names the file and the key
}

// Nodes the master lists as subscribers of a topic.
std::vector<std::string> registered_subscribers(const std::string& topic) {
  std::vector<std::string> nodes;
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, false) || payload.size() < 2) return nodes;
  XmlRpc::XmlRpcValue& subscribed = payload[1];
  for (int i = 0; i < subscribed.size(); ++i) {
    if (static_cast<std::string>(subscribed[i][0]) != topic) continue;
    for (int j = 0; j < subscribed[i][1].size(); ++j) nodes.push_back(subscribed[i][1][j]);
  }
  return nodes;
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec1, ec2;
  return std::filesystem::weakly_canonical(a, ec1) == std::filesystem::weakly_canonical(b, ec2);
}

}  // namespace

ScenarioPlayer::ScenarioPlayer(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh), pnh_(pnh), scenario_(load_scenario(pnh_, &scenario_file_)) {
  bearing_name_ = load_bearing_config(scenario_.bearing_file()).name;
  pnh_.param<std::string>("node", node_name_, "bearing_sim_node");
  pnh_.param("speed_rate_hz", settings_.speed_rate_hz, settings_.speed_rate_hz);
  pnh_.param("load_rate_hz", settings_.load_rate_hz, settings_.load_rate_hz);
  pnh_.param("state_rate_hz", settings_.state_rate_hz, settings_.state_rate_hz);
  pnh_.param("loop", settings_.loop, settings_.loop);
  pnh_.param("wait_timeout_s", wait_timeout_s_, wait_timeout_s_);
  pnh_.param("wait_for_subscribers", wait_for_subscribers_, wait_for_subscribers_);
  // A bounded wait: a recorder or node that never comes must end the player with a reason.
  if (!(std::isfinite(wait_timeout_s_) && wait_timeout_s_ > 0.0))
    throw std::runtime_error("~wait_timeout_s must be a finite number of seconds > 0, got " +
                             std::to_string(wait_timeout_s_));
  if (wait_for_subscribers_ < 0)
    throw std::runtime_error("~wait_for_subscribers must be >= 0, got " + std::to_string(wait_for_subscribers_));
  try {
    runtime::ScenarioTimeline check(scenario_, settings_);  // rates
  } catch (const InvalidInputError& e) {
    throw std::runtime_error(e.what());
  }

  speed_pub_ = nh_.advertise<std_msgs::Float64>("speed", 10);
  load_pub_ = nh_.advertise<geometry_msgs::WrenchStamped>("load", 10);
  if (scenario_.has_ring_temperature_difference())
    ring_temperature_pub_ = nh_.advertise<std_msgs::Float64>("ring_temperature_difference_K", 10, true);
  state_pub_ = nh_.advertise<ScenarioState>("scenario_state", 100);
  rejected_sub_ = nh_.subscribe("rejected_inputs", 100, &ScenarioPlayer::on_rejected, this);
  ROS_INFO("scenario_player: '%s' (%s), %.1f s, %zu defect event(s), bearing '%s'%s", scenario_.name().c_str(),
           scenario_file_.c_str(), scenario_.duration_s(), scenario_.defect_events().size(), bearing_name_.c_str(),
           settings_.loop ? ", looping" : "");
}

bool ScenarioPlayer::wait_for_node() {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wait_timeout_s_);
  auto remaining = [&] { return std::max(0.0, (deadline - ros::WallTime::now()).toSec()); };
  const std::string node = nh_.resolveName(node_name_);
  // The process whose subscriptions are the node's: the node, or the nodelet manager it runs in.
  std::string node_process = node_name_;
  pnh_.param<std::string>("node_process", node_process, node_process);
  node_process = nh_.resolveName(node_process);
  const std::string state_topic = nh_.resolveName("scenario_state");
  const std::string listeners_wanted = wait_for_subscribers_ > 0
                                           ? " and " + std::to_string(wait_for_subscribers_) + " subscriber(s) of " +
                                                 state_topic + " (~wait_for_subscribers: the recorder)"
                                           : "";
  ROS_INFO("scenario_player: waiting up to %.0f s (~wait_timeout_s) for %s%s", wait_timeout_s_, node.c_str(),
           listeners_wanted.c_str());
  for (const char* service : {"inject_defect", "clear_defects"}) {
    if (!ros::service::waitForService(nh_.resolveName(service), ros::Duration(remaining()))) {
      if (ros::ok())
        ROS_FATAL("scenario_player: no service %s after %.0f s: is %s running?", nh_.resolveName(service).c_str(),
                  wait_timeout_s_, node.c_str());
      return false;
    }
  }
  std::string node_bearing;
  if (nh_.getParam(node_name_ + "/bearing_file", node_bearing) && !same_file(node_bearing, scenario_.bearing_file()))
    ROS_WARN("scenario_player: %s simulates %s, the scenario is written for %s", node.c_str(), node_bearing.c_str(),
             scenario_.bearing_file().c_str());
  // The node's input limits, parameters it has read by now (unset: the defaults it uses too). An
  // input beyond them the node would refuse and run on at its last good one, while
  // scenario_state said the scenario's: refuse the scenario before its first sample instead.
  runtime::InputLimits limits;
  nh_.getParam(node_name_ + "/max_force_N", limits.max_force_N);
  nh_.getParam(node_name_ + "/max_moment_Nm", limits.max_moment_Nm);
  nh_.getParam(node_name_ + "/max_speed_rad_s", limits.max_speed_rad_s);
  const std::string refusal = runtime::scenario_limit_refusal(scenario_, limits);
  if (!refusal.empty()) {
    ROS_FATAL(
        "scenario_player: scenario %s refused: %s (parameters of %s): the node would refuse that input and run "
        "on at its last good one while scenario_state said the scenario's; the scenario does not start",
        scenario_file_.c_str(), refusal.c_str(), node.c_str());
    return false;
  }
  // The scenario runs on the node's clock: with the node as fast as possible that is its
  // /clock, which this process only follows with use_sim_time.
  bool node_real_time = true;
  nh_.getParam(node_name_ + "/real_time", node_real_time);
  if (!node_real_time && !ros::Time::isSimTime()) {
    ROS_FATAL(
        "scenario_player: %s runs as fast as possible (~real_time false) but /use_sim_time is not set: "
        "the scenario would play on wall time. Set /use_sim_time true (ct_gantry.launch does with a scenario)",
        node.c_str());
    return false;
  }
  if (!ros::Time::waitForValid(ros::WallDuration(remaining()))) {
    if (ros::ok()) ROS_FATAL("scenario_player: use_sim_time is set but no /clock after %.0f s", wait_timeout_s_);
    return false;
  }
  // Every registered subscriber of speed and load (the node among them) connected, so that
  // the inputs at t = 0 reach the node; and the recorder, if asked to wait for it.
  auto connected = [&](const ros::Publisher& pub, const std::string& topic) {
    const std::vector<std::string> subs = registered_subscribers(nh_.resolveName(topic));
    return std::find(subs.begin(), subs.end(), node_process) != subs.end() && pub.getNumSubscribers() >= subs.size();
  };
  while (ros::ok()) {
    const bool speed = connected(speed_pub_, "speed"), load = connected(load_pub_, "load");
    // The node's refusals reach the player from the first input on.
    const bool refusals = rejected_sub_.getNumPublishers() > 0;
    const std::uint32_t listeners = state_pub_.getNumSubscribers();
    const bool labels = listeners >= static_cast<std::uint32_t>(wait_for_subscribers_);
    if (speed && load && refusals && labels) return true;
    if (remaining() <= 0.0) {
      // Name what is missing: the node's inputs, or the listeners of the labels.
      std::string missing;
      if (!speed || !load)
        missing = node + " is not connected to " + (speed ? "" : nh_.resolveName("speed")) +
                  (!speed && !load ? " and " : "") + (load ? "" : nh_.resolveName("load"));
      if (!refusals)
        missing += (missing.empty() ? "" : "; ") + std::string("this player is not connected to ") +
                   nh_.resolveName("rejected_inputs") + " (published by " + node + ")";
      if (!labels)
        missing += (missing.empty() ? "" : "; ") + state_topic + " has " + std::to_string(listeners) + " of the " +
                   std::to_string(wait_for_subscribers_) +
                   " subscriber(s) asked for (~wait_for_subscribers; with record:=true the recorder, which "
                   "did not start or died: see its log)";
      ROS_FATAL("scenario_player: after %.0f s (~wait_timeout_s), %s; the scenario does not start", wait_timeout_s_,
                missing.c_str());
      return false;
    }
    ros::WallDuration(0.02).sleep();
  }
  return false;
}

void ScenarioPlayer::start() {
  // Refusals of inputs sent before the scenario (by others) are not the scenario's: handled
  // (ignored: no time line yet) before it starts.
  ros::getGlobalCallbackQueue()->callAvailable();
  timeline_ = std::make_unique<runtime::ScenarioTimeline>(scenario_, settings_);
  start_ = ros::Time::now();
  ROS_INFO("scenario_player: '%s' starts at %.3f s on the node's clock (%s)", scenario_.name().c_str(), start_.toSec(),
           ros::Time::isSimTime() ? "/clock" : "wall time");
  inject_client_ = nh_.serviceClient<InjectDefect>("inject_defect", true);
  clear_client_ = nh_.serviceClient<std_srvs::Trigger>("clear_defects", true);
  tick(start_);
  if (ros::Time::isSimTime()) {
    // Follow each /clock message as it comes (the node publishes one per chunk), not
    // roscpp's timer, which polls simulated time every millisecond of wall time.
    clock_sub_ = nh_.subscribe<rosgraph_msgs::Clock>(
        "/clock", 1, [this](const rosgraph_msgs::Clock::ConstPtr& m) { tick(m->clock); }, ros::VoidConstPtr(),
        ros::TransportHints().tcpNoDelay());
  } else {
    const double rate = std::max({settings_.speed_rate_hz, settings_.load_rate_hz, settings_.state_rate_hz});
    timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / rate),
                                 [this](const ros::WallTimerEvent&) { tick(ros::Time::now()); });
  }
}

void ScenarioPlayer::tick(const ros::Time& now) {
  if (!timeline_ || timeline_->finished() || failed_) return;
  for (const runtime::TimelineCommand& c : timeline_->advance((now - start_).toSec())) {
    execute(c);
    if (failed_) return;  // nothing after a refusal: no label claiming what the node refused
  }
}

void ScenarioPlayer::stop(const std::string& reason) {
  if (failed_) return;
  failed_ = true;
  timer_.stop();
  clock_sub_.shutdown();
  ROS_FATAL("scenario_player: '%s' stopped: %s", scenario_.name().c_str(), reason.c_str());
}

void ScenarioPlayer::on_rejected(const InputRejection::ConstPtr& m) {
  if (!timeline_ || failed_) return;  // before the scenario: not one of its inputs
  // The inputs the scenario drives; a refused dynamic_reconfigure setting changes nothing it labels.
  if (m->input != "load" && m->input != "speed" && m->input != "ring_temperature_difference_K") return;
  std::string when;
  if (!m->input_stamp.isZero()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " (sent for t = %.3f s)", (m->input_stamp - start_).toSec());
    when = buf;
  }
  stop("the node refused its " + m->input + when + ": " + m->reason + ". The node runs on at its last good " +
       m->input + " while the labels on " + state_pub_.getTopic() +
       " would say the scenario's; the labels published since that input was sent do not hold");
}

ros::Time ScenarioPlayer::stamp_of(const runtime::TimelineCommand& c) const {
  return start_ + ros::Duration(static_cast<double>(c.pass) * scenario_.duration_s() + c.scenario_time_s);
}

void ScenarioPlayer::execute(const runtime::TimelineCommand& c) {
  using Kind = runtime::TimelineCommand::Kind;
  switch (c.kind) {
    case Kind::ClearDefects:
      ROS_INFO("scenario_player: pass %llu of '%s' begins", static_cast<unsigned long long>(c.pass + 1),
               scenario_.name().c_str());
      clear(c);
      break;
    case Kind::DefectEvent:
      if (c.event.kind == ScenarioDefectEvent::Kind::Clear) clear(c);
      else inject(c);
      break;
    case Kind::Speed: {
      std_msgs::Float64 m;
      m.data = c.speed_rad_s;
      speed_pub_.publish(m);
      break;
    }
    case Kind::Load: {
      geometry_msgs::WrenchStamped m;
      m.header.stamp = stamp_of(c);
      m.header.frame_id = "bearing";
      m.wrench.force.x = c.load[0];
      m.wrench.force.y = c.load[1];
      m.wrench.force.z = c.load[2];
      m.wrench.torque.x = c.load[3];
      m.wrench.torque.y = c.load[4];
      load_pub_.publish(m);
      break;
    }
    case Kind::RingTemperature: {
      std_msgs::Float64 m;
      m.data = c.ring_temperature_difference_K;
      ring_temperature_pub_.publish(m);
      break;
    }
    case Kind::State:
      publish_state(c);
      break;
    case Kind::End:
      ROS_INFO("scenario_player: '%s' finished at %.3f s; the node keeps the last speed and load",
               scenario_.name().c_str(), c.scenario_time_s);
      break;
  }
}

void ScenarioPlayer::inject(const runtime::TimelineCommand& c) {
  const Spall& s = c.event.spall;
  InjectDefect srv;
  srv.request.surface = surface_name(s.surface);
  srv.request.position_rad = s.position_rad;
  srv.request.ball = s.ball;
  srv.request.row = s.row;
  srv.request.width_m = s.width_m;
  srv.request.depth_m = s.depth_m;
  srv.request.width_growth_m_per_s = s.width_growth_m_per_s;
  srv.request.depth_growth_m_per_s = s.depth_growth_m_per_s;
  if (!inject_client_.isValid()) inject_client_ = nh_.serviceClient<InjectDefect>("inject_defect", true);
  char when[96];
  std::snprintf(when, sizeof when, "t = %.3f s (event at %.3f s)", c.scenario_time_s, c.event.time_s);
  // The labels from now on would list the spall: the scenario stops unless the node has it.
  if (!inject_client_.call(srv))
    stop(std::string(when) + ": inject_defect failed (node gone?); the labels would list a spall the simulation " +
         "may not have");
  else if (!srv.response.success)
    stop(std::string(when) + ": the node refused the spall: " + srv.response.message +
         "; the labels would list a spall the simulation does not have");
  else
    ROS_INFO("scenario_player: t = %.3f s (event at %.3f s): %s", c.scenario_time_s, c.event.time_s,
             srv.response.message.c_str());
}

void ScenarioPlayer::clear(const runtime::TimelineCommand& c) {
  std_srvs::Trigger srv;
  if (!clear_client_.isValid()) clear_client_ = nh_.serviceClient<std_srvs::Trigger>("clear_defects", true);
  if (!clear_client_.call(srv)) {
    char when[64];
    std::snprintf(when, sizeof when, "t = %.3f s", c.scenario_time_s);
    stop(std::string(when) + ": clear_defects failed (node gone?); the labels would leave out spalls the " +
         "simulation may still have");
  } else ROS_INFO("scenario_player: t = %.3f s: %s", c.scenario_time_s, srv.response.message.c_str());
}

void ScenarioPlayer::publish_state(const runtime::TimelineCommand& c) {
  const double t = c.scenario_time_s;
  const ScenarioInputs in = scenario_.inputs_at(t);
  ScenarioState m;
  m.header.stamp = stamp_of(c);
  m.header.frame_id = "bearing";
  fill_scenario_state(scenario_.name(), bearing_name_, scenario_.seed(), t, in,
                      runtime::scenario_defects_at(scenario_, t), &m);
  state_pub_.publish(m);
}

}  // namespace ros_node
}  // namespace bearing_sim
