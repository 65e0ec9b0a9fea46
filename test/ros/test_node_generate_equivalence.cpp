// The node as fast as possible and `bearing_tool generate` run the same per-sample pipeline
// (SamplePipeline): for the same constant inputs and seed, every ideal (vibration_ideal) and
// measured (vibration, the sensor's) sample the node publishes is bit-identical to the one
// generate writes. Constant inputs, because the node's inputs are asynchronous topics that
// apply at whatever sample is being computed when they arrive; generate applies a scenario
// at exact samples. The node starts before this test subscribes, so the comparison starts
// at the first chunk received, and generate runs up to the last one received.
#include <algorithm>
#include <map>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/scenario_simulation.hpp"

using namespace bearing_sim;

namespace {

struct Received {
  std::mutex mutex;
  std::vector<VibrationChunk> chunks;
  void on(const VibrationChunk::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    chunks.push_back(*m);
  }
  std::size_t size() {
    std::lock_guard<std::mutex> lock(mutex);
    return chunks.size();
  }
};

// Collects generate's chunks, flattened by sample index.
class CollectSink : public runtime::DatasetSink {
 public:
  struct Samples {
    std::vector<float> ax, ay, az, dx, dy, dz;
    void append(const runtime::SampleChunk& c) {
      ax.insert(ax.end(), c.accel_x.begin(), c.accel_x.end());
      ay.insert(ay.end(), c.accel_y.begin(), c.accel_y.end());
      az.insert(az.end(), c.accel_z.begin(), c.accel_z.end());
      dx.insert(dx.end(), c.displacement_x.begin(), c.displacement_x.end());
      dy.insert(dy.end(), c.displacement_y.begin(), c.displacement_y.end());
      dz.insert(dz.end(), c.displacement_z.begin(), c.displacement_z.end());
    }
  };
  Samples ideal, measured;
  void begin(const runtime::DatasetInfo&) override {}
  void ideal_chunk(const runtime::SampleChunk& c) override {
    ASSERT_EQ(c.first_sample, ideal.ax.size());
    ideal.append(c);
  }
  void measured_chunk(const runtime::SampleChunk& c) override {
    ASSERT_EQ(c.first_sample, measured.ax.size());
    measured.append(c);
  }
  void label(const runtime::LabelState&) override {}
  void end() override {}
};

// Every sample of the received chunks equals generate's at the same index (bit for bit).
std::size_t compare(const std::vector<VibrationChunk>& chunks, const CollectSink::Samples& g, const char* what) {
  std::size_t compared = 0;
  for (const VibrationChunk& c : chunks) {
    for (std::size_t k = 0; k < c.accel_x.size(); ++k) {
      const std::size_t i = c.first_sample + k;
      if (i >= g.ax.size()) break;  // the short last chunk of generate's run
      const bool same = c.accel_x[k] == g.ax[i] && c.accel_y[k] == g.ay[i] && c.accel_z[k] == g.az[i] &&
                        c.displacement_x[k] == g.dx[i] && c.displacement_y[k] == g.dy[i] &&
                        c.displacement_z[k] == g.dz[i];
      if (!same) {
        ADD_FAILURE() << what << " sample " << i << " differs: node x " << c.accel_x[k] << ", generate " << g.ax[i];
        return compared;
      }
      ++compared;
    }
  }
  return compared;
}

}  // namespace

TEST(NodeGenerateEquivalence, SameSamplesForTheSameInputsAndSeed) {
  ros::NodeHandle nh;
  Received ideal, measured;
  ros::Subscriber si =
      nh.subscribe("vibration_ideal", 100000, &Received::on, &ideal, ros::TransportHints().tcpNoDelay());
  ros::Subscriber sm = nh.subscribe("vibration", 100000, &Received::on, &measured, ros::TransportHints().tcpNoDelay());
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(60.0);
  while ((ideal.size() < 30 || measured.size() < 30) && ros::WallTime::now() < deadline)
    ros::WallDuration(0.01).sleep();
  si.shutdown();
  sm.shutdown();
  ASSERT_GE(ideal.size(), 30u) << "no vibration_ideal from the node";
  ASSERT_GE(measured.size(), 30u) << "no vibration from the node";
  std::vector<VibrationChunk> ideal_chunks, measured_chunks;
  {
    std::lock_guard<std::mutex> l1(ideal.mutex), l2(measured.mutex);
    ideal_chunks = ideal.chunks;
    measured_chunks = measured.chunks;
  }
  std::uint64_t end = 0;
  for (const auto& c : ideal_chunks) end = std::max<std::uint64_t>(end, c.first_sample + c.accel_x.size());
  // Generate up to the last ideal sample received (the node's rate: 10 kHz).
  std::string scenario_file;
  ASSERT_TRUE(ros::param::get("~scenario_file", scenario_file));
  const Scenario scenario = Scenario::load(scenario_file);
  runtime::GenerateSettings settings;
  settings.duration_s = static_cast<double>(end) / scenario.sample_rate_hz();
  settings.health_rate_hz = 0.0;
  runtime::ScenarioSimulation sim(scenario, scenario_file, settings);
  ASSERT_EQ(sim.info().ideal_samples, end);
  CollectSink sink;
  sim.run({&sink});
  const std::size_t n_ideal = compare(ideal_chunks, sink.ideal, "ideal");
  const std::size_t n_measured = compare(measured_chunks, sink.measured, "measured");
  std::cout << "compared " << n_ideal << " ideal samples from index " << ideal_chunks.front().first_sample << " and "
            << n_measured << " measured ones" << std::endl;
  EXPECT_GE(n_ideal, 29u * 100u);
  EXPECT_GT(n_measured, 0u);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node_generate_equivalence");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  return result;
}
