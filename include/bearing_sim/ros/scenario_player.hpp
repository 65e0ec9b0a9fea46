#pragma once
// scenario_player: drives a running bearing_sim_node from a scenario file (docs/recording.md).
// Publishes `speed` and `load`, calls `inject_defect` / `clear_defects` at the defect
// events and publishes the labels on `scenario_state`, all in the node's namespace, on the
// node's clock: ros::Time, which is wall time when the node runs in real time (its stamps
// are wall time at its start + n / rate) and the node's /clock with use_sim_time when it
// runs as fast as possible. The time line itself is ScenarioTimeline (ROS-free).
// The labels say what the data has (docs/scenarios.md "Labels"): a scenario with an input
// beyond the node's max_force_N / max_moment_Nm / max_speed_rad_s is refused before its first
// sample (scenario_limit_refusal), and an input the node refuses during playback (a spall in
// the reply of inject_defect, a load, speed or ring temperature on its rejected_inputs) stops
// the scenario with the reason.
#include <memory>
#include <string>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "bearing_sim/InputRejection.h"
#include "bearing_sim/ScenarioState.h"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/scenario_timeline.hpp"

namespace bearing_sim {
namespace ros_node {

class ScenarioPlayer {
 public:
  // Reads ~scenario_file and the rates; throws ConfigError (file and key) for a bad scenario,
  // std::runtime_error for a bad parameter.
  ScenarioPlayer(ros::NodeHandle nh, ros::NodeHandle pnh);

  // Until the node's services, its subscriptions to speed and load, a valid clock and
  // ~wait_for_subscribers listeners of scenario_state are there, for ~wait_timeout_s at most.
  // False (logged, naming what is missing) on timeout or a mode mismatch; also false if ROS
  // shut down meanwhile. Also false (logged, naming the key, the value and the limit) for a
  // scenario with an input beyond the node's input limits (its parameters max_force_N,
  // max_moment_Nm, max_speed_rad_s, read once the node is there).
  bool wait_for_node();
  // Scenario time 0 = now on the node's clock; sends the inputs at 0 at once.
  void start();
  bool finished() const { return timeline_ && timeline_->finished(); }
  // The node refused an input of the scenario (or a service call failed): the scenario was
  // stopped, logged with the reason; nothing more is sent or labelled.
  bool failed() const { return failed_; }
  const Scenario& scenario() const { return scenario_; }

 private:
  void tick(const ros::Time& now);
  void execute(const runtime::TimelineCommand& c);
  ros::Time stamp_of(const runtime::TimelineCommand& c) const;  // on the node's clock
  void publish_state(const runtime::TimelineCommand& c);
  void inject(const runtime::TimelineCommand& c);
  void clear(const runtime::TimelineCommand& c);
  void on_rejected(const InputRejection::ConstPtr& m);
  void stop(const std::string& reason);

  ros::NodeHandle nh_, pnh_;
  std::string scenario_file_;
  Scenario scenario_;
  std::string bearing_name_;
  std::string node_name_;
  runtime::TimelineSettings settings_;
  double wait_timeout_s_ = 60.0;
  int wait_for_subscribers_ = 0;
  std::unique_ptr<runtime::ScenarioTimeline> timeline_;
  ros::Time start_;

  ros::Publisher speed_pub_, load_pub_, state_pub_;
  ros::Publisher ring_temperature_pub_;  // only for a scenario with ring_temperature_difference
  ros::ServiceClient inject_client_, clear_client_;
  ros::Subscriber clock_sub_;
  ros::Subscriber rejected_sub_;  // the node's rejected_inputs
  bool failed_ = false;
  ros::WallTimer timer_;
};

}  // namespace ros_node
}  // namespace bearing_sim
