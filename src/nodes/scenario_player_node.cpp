// scenario_player: plays a scenario file on a running bearing_sim_node (docs/recording.md).
//   rosrun bearing_sim scenario_player __ns:=/bearing _scenario_file:=config/scenarios/ct_gantry_scan.yaml
// Without ROS, for roslaunch's <param command=...>: the node parameters for the scenario,
//   scenario_player --param initial_speed_rad_s FILE
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/ros/scenario_player.hpp"
#include "bearing_sim/runtime/scenario_timeline.hpp"

namespace {

int print_parameter(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: scenario_player --param NAME SCENARIO_FILE\n";
    return 2;
  }
  try {
    const bearing_sim::Scenario scenario = bearing_sim::Scenario::load(argv[3]);
    std::cout << bearing_sim::runtime::scenario_node_parameter(scenario, argv[2]);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "scenario_player: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "--param") == 0) return print_parameter(argc, argv);
  ros::init(argc, argv, "scenario_player");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  std::unique_ptr<bearing_sim::ros_node::ScenarioPlayer> player;
  try {
    player = std::make_unique<bearing_sim::ros_node::ScenarioPlayer>(nh, pnh);
  } catch (const bearing_sim::ConfigError& e) {
    ROS_FATAL("scenario_player: bad scenario: %s", e.what());
    return 1;
  } catch (const std::exception& e) {
    ROS_FATAL("scenario_player: %s", e.what());
    return 1;
  }
  if (!player->wait_for_node()) {
    if (!ros::ok()) return 0;
    ros::WallDuration(0.5).sleep();  // let the reason reach /rosout
    return 1;
  }
  player->start();
  ros::CallbackQueue* queue = ros::getGlobalCallbackQueue();
  while (ros::ok() && !player->finished() && !player->failed()) queue->callAvailable(ros::WallDuration(0.01));
  // Let the last messages (final inputs and labels, or the reason of a stop) leave before the
  // connections close.
  if (player->finished() || player->failed()) ros::WallDuration(0.5).sleep();
  return player->failed() ? 1 : 0;
}
