#pragma once
// Shared by the rostest gtest nodes: records everything bearing_sim_node publishes and
// gives the reference values from the core library for the same inputs. Compiled once
// (node_test_support.cpp, library bearing_sim_test_node_support).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/core/bearing_model.hpp"
#include "test_support.hpp"

namespace node_test {

using bearing_sim::Vector5;
// The inputs of launch/ct_gantry.launch (the load: bearing_sim::test::ct_load()).
using bearing_sim::test::ct_load;
constexpr double kCtSpeed = 180.0 * 2.0 * M_PI / 60.0;

// The bearing of the test node's ~bearing_file.
bearing_sim::BearingModel ct_model();

struct ChunkArrival {
  std::uint64_t first_sample;
  std::size_t size;
  ros::Time stamp;
  ros::WallTime received;
};

// Every sample of /bearing/vibration, checked for contiguity as it arrives.
class Recorder {
 public:
  explicit Recorder(ros::NodeHandle& nh);

  // Blocks (spinning in the background) until pred() or the timeout; true if pred().
  bool wait_for(const std::function<bool()>& pred, double timeout_s);
  // Until samples up to (at least) this index have arrived.
  bool wait_for_sample(std::uint64_t index, double timeout_s);
  // Until at least n vibration levels have arrived.
  bool wait_for_levels(std::size_t n, double timeout_s);
  std::uint64_t next_index();

  // Mean of displacement component c (0..2) over samples [from, to).
  double mean_displacement(int c, std::uint64_t from, std::uint64_t to);
  std::vector<double> accel_x(std::uint64_t from, std::uint64_t to);
  double max_abs_deviation(int c, double reference, std::uint64_t from, std::uint64_t to);

  std::vector<ChunkArrival> chunks();
  std::vector<bearing_sim::VibrationLevel> levels();
  bearing_sim::BallLoads::ConstPtr last_ball_loads();
  // Latest status whose name ends with `task` ("Real time", "Inputs", "Model").
  bool diagnostic(const std::string& task, diagnostic_msgs::DiagnosticStatus* out);
  // Until n more /diagnostics messages have arrived (the node publishes one per second).
  bool wait_for_new_diagnostics(int n, double timeout_s);
  int diagnostics_received();
  static std::string value(const diagnostic_msgs::DiagnosticStatus& s, const std::string& key);
  // Worst diagnostic level of a task seen since the recorder started.
  int worst_level(const std::string& task);

  std::uint64_t gaps();
  std::uint64_t repeats();
  std::uint64_t non_finite();
  std::uint64_t first_index();

 private:
  void on_chunk(const bearing_sim::VibrationChunk::ConstPtr& msg);
  void on_level(const bearing_sim::VibrationLevel::ConstPtr& msg);
  void on_balls(const bearing_sim::BallLoads::ConstPtr& msg);
  void on_diagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& msg);

  std::mutex mutex_;
  ros::Subscriber vibration_sub_, level_sub_, ball_sub_, diag_sub_;
  bool have_samples_ = false;
  std::uint64_t first_index_ = 0, next_index_ = 0, gaps_ = 0, repeats_ = 0, non_finite_ = 0;
  std::vector<double> accel_x_, displacement_[3];
  std::vector<ChunkArrival> chunks_;
  std::vector<bearing_sim::VibrationLevel> levels_;
  bearing_sim::BallLoads::ConstPtr ball_loads_;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics_;
  std::map<std::string, int> worst_;
  int diagnostics_count_ = 0;
};

// Amplitude of the Hann-windowed DFT of x at frequency f (Hz), for sample rate fs.
double spectral_amplitude(const std::vector<double>& x, double f, double fs);

geometry_msgs::WrenchStamped wrench(const Vector5& l);
std_msgs::Float64 speed(double rad_s);

// One recorder per test process, started with the first test.
Recorder& recorder();

// Main of every rostest gtest node: background spinner for the subscriptions.
#define NODE_TEST_MAIN(node_name)         \
  int main(int argc, char** argv) {       \
    testing::InitGoogleTest(&argc, argv); \
    ros::init(argc, argv, node_name);     \
    ros::AsyncSpinner spinner(1);         \
    spinner.start();                      \
    const int result = RUN_ALL_TESTS();   \
    spinner.stop();                       \
    ros::shutdown();                      \
    return result;                        \
  }

}  // namespace node_test
