// The scenario player (run here as a child process, its output and exit status read) against
// bearing_sim_node of ct_gantry.launch, with test/ros/scenario_beyond_node_limits.yaml: a load
// step to 150 kN at 3 s, which the bearing carries but the node's max_force_N (1e5 N) does not
// allow, and a spall at 1 s. Labels must say what the data has (docs/scenarios.md "Labels"):
// - with the node's limit as it runs, the player refuses the scenario before its first sample,
//   naming the key, the value and the limit; it sends nothing and publishes no label;
// - when the node nevertheless refuses an input during playback, the player stops the scenario
//   with the node's reason: a load (the player told a larger limit than the node read at its
//   start), and a spall (the node already holds the 64 it may hold), for which no label
//   listing the spall is ever published (the player learns of it from the service's reply).
// Every wait is a generous time-out; nothing here measures speed.
#include <cmath>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "bearing_sim/InjectDefect.h"
#include "bearing_sim/InputRejection.h"
#include "bearing_sim/ScenarioState.h"
#include "command_runner.hpp"
#include "service_calls.hpp"

using namespace bearing_sim;

namespace {

const char* const kMaxForceParam = "/bearing/bearing_sim_node/max_force_N";

struct PlayerRun {
  int status = -1;     // exit status (run_command's)
  std::string output;  // stdout, then stderr
};

// The player on the node's namespace with the scenario; waits for the test's scenario_state
// subscription (as for a recorder), so that every label it publishes reaches the test.
PlayerRun run_player(const std::string& name) {
  std::string file, process;
  ros::param::get("~scenario_file", file);
  ros::param::get("~node_process", process);
  const std::string command = std::string(SCENARIO_PLAYER_PATH) + " __ns:=/bearing __name:=" + name +
                              " _scenario_file:=" + file + " _node_process:=" + process +
                              " _wait_for_subscribers:=1 _wait_timeout_s:=120";
  const test::CommandResult r = test::run_command(command, 300);
  return {r.exit_code, r.out + r.err};
}

using bearing_sim::test::call_until_answered;

class ScenarioPlayerRefusals : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle nh;
    state_sub_ = nh.subscribe("scenario_state", 10000, &ScenarioPlayerRefusals::on_state);
    rejected_sub_ = nh.subscribe("rejected_inputs", 1000, &ScenarioPlayerRefusals::on_rejected);
    spinner_ = std::make_unique<ros::AsyncSpinner>(1);
    spinner_->start();
    ASSERT_TRUE(ros::service::waitForService(nh.resolveName("inject_defect"), ros::Duration(120.0)));
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(120.0);
    while (ros::WallTime::now() < end && rejected_sub_.getNumPublishers() == 0) ros::WallDuration(0.01).sleep();
    ASSERT_GT(rejected_sub_.getNumPublishers(), 0u) << "the node does not publish rejected_inputs";
    ASSERT_TRUE(ros::param::get(kMaxForceParam, node_max_force_N_));
    ASSERT_EQ(node_max_force_N_, 1e5);  // the node's, from config/nodes/bearing_sim_node.yaml
  }
  static void TearDownTestSuite() {
    spinner_->stop();
    state_sub_.shutdown();
    rejected_sub_.shutdown();
  }
  void SetUp() override {
    std::lock_guard<std::mutex> lock(mutex_);
    states_.clear();
    rejections_.clear();
    std_srvs::Trigger clear;
    ASSERT_TRUE(call_until_answered("clear_defects", clear));
  }
  void TearDown() override {
    ros::param::set(kMaxForceParam, node_max_force_N_);
    std_srvs::Trigger clear;
    call_until_answered("clear_defects", clear);
  }
  static void on_state(const ScenarioState::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    states_.push_back(*m);
  }
  static void on_rejected(const InputRejection::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    rejections_.push_back(*m);
  }
  static std::vector<ScenarioState> states() {
    std::lock_guard<std::mutex> lock(mutex_);
    return states_;
  }
  static std::vector<InputRejection> rejections() {
    std::lock_guard<std::mutex> lock(mutex_);
    return rejections_;
  }

  static double node_max_force_N_;
  static std::mutex mutex_;
  static std::vector<ScenarioState> states_;
  static std::vector<InputRejection> rejections_;
  static ros::Subscriber state_sub_, rejected_sub_;
  static std::unique_ptr<ros::AsyncSpinner> spinner_;
};
double ScenarioPlayerRefusals::node_max_force_N_ = 0.0;
std::mutex ScenarioPlayerRefusals::mutex_;
std::vector<ScenarioState> ScenarioPlayerRefusals::states_;
std::vector<InputRejection> ScenarioPlayerRefusals::rejections_;
ros::Subscriber ScenarioPlayerRefusals::state_sub_, ScenarioPlayerRefusals::rejected_sub_;
std::unique_ptr<ros::AsyncSpinner> ScenarioPlayerRefusals::spinner_;

TEST_F(ScenarioPlayerRefusals, AScenarioBeyondTheNodesMaxForceIsRefusedBeforeItsFirstSample) {
  const PlayerRun run = run_player("scenario_player_beyond_max_force");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("scenario_beyond_node_limits.yaml refused: load.segments[0].force_N: |(Fx, Fy, Fz)| = "
                            "150000 N at t = 3 s exceeds the node's max_force_N = 100000 N"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("the scenario does not start"), std::string::npos) << run.output;
  // The player has exited: whatever it had sent would have arrived within this second.
  ros::WallDuration(1.0).sleep();
  EXPECT_TRUE(states().empty()) << states().size() << " labels published";
  EXPECT_TRUE(rejections().empty()) << "the node refused " << rejections().front().input << ": "
                                    << rejections().front().reason;
}

TEST_F(ScenarioPlayerRefusals, ALoadTheNodeRefusesDuringPlaybackStopsTheScenario) {
  // The player reads a limit the node does not have (the node read its parameters at its start).
  ros::param::set(kMaxForceParam, 1e6);
  const PlayerRun run = run_player("scenario_player_load_refused");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("stopped: the node refused its load (sent for t = "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("force 150000 N exceeds max_force_N = 100000"), std::string::npos) << run.output;
  ros::WallDuration(1.0).sleep();
  const std::vector<InputRejection> refused = rejections();
  ASSERT_FALSE(refused.empty());
  EXPECT_EQ(refused.front().input, "load");
  EXPECT_FALSE(refused.front().input_stamp.isZero());
  // Labels up to the load step, then none: the scenario (20 s) did not play on.
  const std::vector<ScenarioState> labels = states();
  ASSERT_FALSE(labels.empty());
  EXPECT_LT(labels.back().scenario_time_s, 20.0);
  for (const ScenarioState& s : labels) {
    if (s.scenario_time_s < 3.0) {
      EXPECT_EQ(s.load[0], 6800.0) << "t = " << s.scenario_time_s;
    }
  }
}

TEST_F(ScenarioPlayerRefusals, ASpallTheNodeRefusesStopsTheScenarioBeforeAnyLabelListsIt) {
  // The node holds the 64 spalls a bearing may hold at once: the scenario's at 1 s is the 65th.
  // Filled to the count the node reports (an answer lost on the way and its call made again
  // adds a spall twice: still spalls, and the cap is what counts here).
  bearing_sim::test::PersistentService<InjectDefect> inject("inject_defect");
  std::uint32_t present = 0;
  for (int k = 0; present < 64 && k < 128; ++k) {
    InjectDefect srv;
    srv.request.surface = "outer_race";
    srv.request.position_rad = 2.0 * M_PI * k / 64.0;
    srv.request.width_m = 1e-3;
    srv.request.depth_m = 1e-5;
    ASSERT_TRUE(inject.call(srv));
    ASSERT_TRUE(srv.response.success || srv.response.defects_present == 64) << srv.response.message;
    present = srv.response.defects_present;
  }
  ASSERT_EQ(present, 64u);
  ros::param::set(kMaxForceParam, 1e6);  // past the check before the first sample
  const PlayerRun run = run_player("scenario_player_spall_refused");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("(event at 1.000 s): the node refused the spall: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("at most 64 may be at once"), std::string::npos) << run.output;
  ros::WallDuration(1.0).sleep();
  // Labels before the event, none listing a spall; none at or after it.
  const std::vector<ScenarioState> labels = states();
  ASSERT_FALSE(labels.empty());
  for (const ScenarioState& s : labels) {
    EXPECT_LT(s.scenario_time_s, 1.0);
    EXPECT_TRUE(s.defects.empty()) << "t = " << s.scenario_time_s;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_scenario_player_refusals");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
