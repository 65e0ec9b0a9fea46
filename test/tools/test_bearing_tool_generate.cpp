// bearing_tool generate (docs/datasets.md): runs the built tool on a 2.05 s CT gantry
// scenario (speed ramp, rotating unbalance, a growing outer-race spall, the housing
// sensor) and reads back what it wrote: the bag with rosbag::View, the NPY, CSV and JSON
// files directly. Counts, contiguity and stamps are exact; labels follow the scenario's
// closed forms; the same seed gives the same bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>
#include <nlohmann/json.hpp>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/ScenarioState.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/flexible_dynamics.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "bearing_sim/core/constants.hpp"
#include "tool_runner.hpp"
#include "tool_test_files.hpp"

using bearing_sim::test::read_text;
using bearing_sim::test::run_bearing_tool;

namespace {

using bearing_sim::kPi;
using bearing_sim::test::contains;
using bearing_sim::test::kConfigDir;
using bearing_sim::test::kCtBearingYaml;
using bearing_sim::test::kCtScanYaml;

constexpr double kRpm = 2.0 * kPi / 60.0;
constexpr double kRate = 10000.0;
constexpr std::uint64_t kSamples = 20500;  // 2.05 s: the last chunk is short (100 per chunk)

using bearing_sim::test::source_file;

// 150 rpm, ramp to 180 rpm from 0.5 to 1.5 s; paper load plus 0.11 kg*m unbalance; an
// outer-race spall from 0.55 s, 0.3 mm x 5 um growing by 0.5 mm/s and 10 um/s.
std::string scenario_text(const std::string& name, int seed) {
  return "name: " + name + "\nduration_s: 2.05\nseed: " + std::to_string(seed) +
         "\nbearing_file: " + source_file("config/bearings/ct_gantry_lyc.yaml") +
         "\nsensor_file: " + source_file("config/sensors/ct_gantry_housing_accelerometer.yaml") +
         "\nphases: [{name: settle, start_s: 0}, {name: ramp, start_s: 0.5}, {name: hold, start_s: 1.5}]\n"
         "speed:\n  initial_speed_rpm: 150\n"
         "  segments: [{type: ramp, start_s: 0.5, end_s: 1.5, to_speed_rpm: 180}]\n"
         "load:\n  initial: {force_N: [6800, 0, 0], moment_Nm: [0, 2100]}\n"
         "  unbalance: {mass_kg: 0.2, radius_m: 0.55}\n"
         "defects:\n  - {at_s: 0.55, surface: outer_race, position_deg: 0, width_mm: 0.3, depth_um: 5,\n"
         "     width_growth_mm_per_s: 0.5, depth_growth_um_per_s: 10}\n";
}
double hand_speed(double t) { return (t < 0.5 ? 150.0 : t < 1.5 ? 150.0 + 30.0 * (t - 0.5) : 180.0) * kRpm; }

class Generate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    char pattern[] = "/tmp/test_generate_XXXXXX";
    dir_ = mkdtemp(pattern);
    scenario_ = dir_ + "/gen_test.yaml";
    std::ofstream(scenario_) << scenario_text("gen_test", 5);
    std::ofstream(dir_ + "/gen_test2.yaml") << scenario_text("gen_test2", 9);
    const auto a = run_bearing_tool("generate '" + scenario_ + "' --out '" + dir_ + "/a' --format bag,npy,csv");
    ASSERT_EQ(a.exit_code, 0) << a.err;
    summary_ = a.out;
  }
  static void TearDownTestSuite() { std::system(("rm -rf '" + dir_ + "'").c_str()); }

  template <class M>
  static std::vector<M> messages(const std::string& bag_path, const std::string& topic) {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    std::vector<M> out;
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic))) {
      auto p = m.instantiate<M>();
      EXPECT_TRUE(p) << topic << " holds another type";
      if (p) out.push_back(*p);
    }
    return out;
  }
  static std::string bag() { return dir_ + "/a/gen_test.bag"; }

  static std::string dir_, scenario_, summary_;
};
std::string Generate::dir_, Generate::scenario_, Generate::summary_;

// float32 (samples, 3) of an .npy file, after checking its header.
std::vector<float> read_npy(const std::string& path, std::uint64_t* rows) {
  const std::string bytes = read_text(path);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header_len = static_cast<unsigned char>(bytes[8]) | (static_cast<unsigned char>(bytes[9]) << 8);
  EXPECT_EQ((10 + header_len) % 64, 0u) << "data aligned to 64 bytes";
  const std::string header = bytes.substr(10, header_len);
  std::smatch m;
  EXPECT_TRUE(
      std::regex_search(header, m, std::regex("'descr': '<f4', 'fortran_order': False, 'shape': \\((\\d+), 3\\)")))
      << header;
  *rows = std::stoull(m[1]);
  std::vector<float> data((bytes.size() - 10 - header_len) / 4);
  std::memcpy(data.data(), bytes.data() + 10 + header_len, data.size() * 4);
  return data;
}

// The bag's samples of one vibration topic, x y z interleaved, checking contiguity and
// stamps: chunk k starts where k-1 ended, header stamp = first_sample / rate to 1 ns.
std::vector<float> bag_samples(const std::vector<bearing_sim::VibrationChunk>& chunks, double rate) {
  std::vector<float> xyz;
  std::uint64_t next = 0;
  for (const auto& c : chunks) {
    EXPECT_EQ(c.first_sample, next) << "gap or overlap";
    EXPECT_EQ(c.sample_rate, rate);
    const long double expected_ns = static_cast<long double>(c.first_sample) * 1e9L / rate;
    EXPECT_LE(std::abs(static_cast<long double>(c.header.stamp.toNSec()) - expected_ns), 1.0L) << c.first_sample;
    EXPECT_EQ(c.accel_y.size(), c.accel_x.size());
    EXPECT_EQ(c.displacement_x.size(), c.accel_x.size());
    for (std::size_t i = 0; i < c.accel_x.size(); ++i) {
      xyz.push_back(c.accel_x[i]);
      xyz.push_back(c.accel_y[i]);
      xyz.push_back(c.accel_z[i]);
    }
    next = c.first_sample + c.accel_x.size();
  }
  return xyz;
}

void expect_same_bytes(const std::string& a, const std::string& b) {
  const std::string x = read_text(a), y = read_text(b);
  EXPECT_FALSE(x.empty()) << a;
  EXPECT_TRUE(x == y) << a << " and " << b << " differ";
}

}  // namespace

TEST_F(Generate, BagHoldsEverySampleContiguousWithExactStamps) {
  for (const char* topic : {"/bearing/vibration", "/bearing/vibration_ideal"}) {
    const auto chunks = messages<bearing_sim::VibrationChunk>(bag(), topic);
    const std::vector<float> xyz = bag_samples(chunks, kRate);  // the sensor runs at the dynamics' rate (R = 1)
    EXPECT_EQ(xyz.size(), 3 * kSamples) << topic;
    ASSERT_FALSE(chunks.empty());
    EXPECT_EQ(chunks.front().header.frame_id, "bearing_outer_ring");
    EXPECT_EQ(chunks.back().accel_x.size(), 100u - (205u * 100u - kSamples)) << "short last chunk";
  }
  // Lower-rate topics on the live node's grids: L at 10 Hz, ball loads at 10 Hz, health at
  // 1 Hz, each first due one period after the start.
  const auto levels = messages<bearing_sim::VibrationLevel>(bag(), "/bearing/vibration_level");
  ASSERT_EQ(levels.size(), 20u);
  for (std::size_t k = 0; k < levels.size(); ++k)
    EXPECT_EQ(levels[k].header.stamp.toNSec(), static_cast<std::uint64_t>(std::llround((1000.0 * k + 999) * 1e5)));
  const auto balls = messages<bearing_sim::BallLoads>(bag(), "/bearing/ball_loads");
  ASSERT_EQ(balls.size(), 20u);
  EXPECT_EQ(balls[0].load.size(), 414u);
  const auto health = messages<bearing_sim::BearingHealth>(bag(), "/bearing/health");
  ASSERT_EQ(health.size(), 2u);
  EXPECT_NE(health[1].signal.find("CT gantry stator"), std::string::npos);
  ASSERT_EQ(health[1].defects.size(), 1u);  // the spall, in the health report too
}

TEST_F(Generate, LabelsFollowTheScenario) {
  const auto labels = messages<bearing_sim::ScenarioState>(bag(), "/bearing/scenario_state");
  ASSERT_EQ(labels.size(), 21u);  // t = 0, 0.1, ..., 2.0 s
  for (std::size_t k = 0; k < labels.size(); ++k) {
    const auto& l = labels[k];
    const double t = 0.1 * static_cast<double>(k);
    EXPECT_EQ(l.header.stamp.toNSec(), 100000000ull * k);
    EXPECT_EQ(l.scenario, "gen_test");
    EXPECT_EQ(l.bearing, "LYC CT gantry bearing");
    EXPECT_EQ(l.seed, 5u);
    EXPECT_NEAR(l.scenario_time_s, t, 1e-12);
    EXPECT_EQ(l.phase, t < 0.5 - 1e-9 ? "settle" : t < 1.5 - 1e-9 ? "ramp" : "hold") << t;
    EXPECT_NEAR(l.ring_speed_rad_s, hand_speed(l.scenario_time_s), 1e-12) << t;
    if (t < 0.5 - 1e-9 || t > 1.5 + 1e-9) {  // holds: unbalance force m e w^2
      const double w = hand_speed(t);
      EXPECT_NEAR(std::hypot(l.load[0] - 6800.0, l.load[1]), 0.11 * w * w, 1e-9) << t;
    }
    EXPECT_EQ(l.load[4], 2100.0);
    if (l.scenario_time_s < 0.55) {
      EXPECT_TRUE(l.defects.empty()) << t;
    } else {
      ASSERT_EQ(l.defects.size(), 1u) << t;
      const double age = l.scenario_time_s - 0.55;
      EXPECT_EQ(l.defects[0].surface, "outer_race");
      EXPECT_NEAR(l.defects[0].width_m, 0.3e-3 + 0.5e-3 * age, 1e-15) << t;
      EXPECT_NEAR(l.defects[0].depth_m, 5e-6 + 10e-6 * age, 1e-16) << t;
      EXPECT_NEAR(l.defects[0].age_s, age, 1e-12);
    }
  }
  // The bag-level description.
  const auto info = messages<std_msgs::String>(bag(), "/bearing/dataset_info");
  ASSERT_EQ(info.size(), 1u);
  const nlohmann::json j = nlohmann::json::parse(info[0].data);
  EXPECT_EQ(j["scenario"]["name"], "gen_test");
  EXPECT_EQ(j["seed"], 5);
  EXPECT_EQ(j["ideal_samples"], kSamples);
  EXPECT_EQ(j["sensor"]["name"], "CT gantry stator, radial");
  // The tool runs on this CPU with this library: the same dispatcher's choice.
  EXPECT_EQ(j["simd_target"], bearing_sim::simd_target_name());
}

TEST_F(Generate, NpyCsvAndJsonEqualTheBag) {
  const std::string stem = dir_ + "/a/gen_test";
  for (const auto& [suffix, topic] : std::map<std::string, std::string>{
           {"_vibration", "/bearing/vibration"}, {"_vibration_ideal", "/bearing/vibration_ideal"}}) {
    const std::vector<float> from_bag = bag_samples(messages<bearing_sim::VibrationChunk>(bag(), topic), kRate);
    std::uint64_t rows = 0;
    const std::vector<float> npy = read_npy(stem + suffix + ".npy", &rows);
    EXPECT_EQ(rows, kSamples);
    ASSERT_EQ(npy.size(), from_bag.size());
    EXPECT_EQ(std::memcmp(npy.data(), from_bag.data(), 4 * npy.size()), 0) << suffix << ": not bit-identical";
    // CSV: sample, time, x, y, z; %.9g reads back to the same float32.
    std::ifstream csv(stem + suffix + ".csv");
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "sample,time_s,accel_x,accel_y,accel_z");
    std::size_t n = 0, mismatches = 0;
    while (std::getline(csv, line)) {
      unsigned long long k;
      double t;
      float x, y, z;
      ASSERT_EQ(std::sscanf(line.c_str(), "%llu,%lf,%f,%f,%f", &k, &t, &x, &y, &z), 5) << line;
      if (k != n || x != npy[3 * n] || y != npy[3 * n + 1] || z != npy[3 * n + 2]) ++mismatches;
      ++n;
    }
    EXPECT_EQ(n, kSamples);
    EXPECT_EQ(mismatches, 0u);
  }
  const nlohmann::json j = nlohmann::json::parse(read_text(stem + ".json"));
  EXPECT_EQ(j["scenario"]["name"], "gen_test");
  EXPECT_EQ(j["seed"], 5);
  EXPECT_EQ(j["channels"]["vibration"]["samples"], kSamples);
  EXPECT_EQ(j["channels"]["vibration"]["sample_rate_hz"], kRate);
  EXPECT_EQ(j["channels"]["vibration"]["unit"], "m_s2");
  EXPECT_EQ(j["channels"]["vibration_ideal"]["file"], "gen_test_vibration_ideal.npy");
  // The label time line equals the bag's labels.
  const auto labels = messages<bearing_sim::ScenarioState>(bag(), "/bearing/scenario_state");
  ASSERT_EQ(j["labels"]["time_s"].size(), labels.size());
  for (std::size_t k = 0; k < labels.size(); ++k) {
    EXPECT_EQ(j["labels"]["time_s"][k].get<double>(), labels[k].scenario_time_s);
    EXPECT_EQ(j["labels"]["phase"][k].get<std::string>(), labels[k].phase);
    EXPECT_EQ(j["labels"]["ring_speed_rad_s"][k].get<double>(), labels[k].ring_speed_rad_s);
    ASSERT_EQ(j["labels"]["defects"][k].size(), labels[k].defects.size());
    if (!labels[k].defects.empty()) {
      EXPECT_EQ(j["labels"]["defects"][k][0]["width_m"].get<double>(), labels[k].defects[0].width_m);
    }
  }
  EXPECT_EQ(j["phases"].size(), 3u);
}

TEST_F(Generate, SameSeedSameBytesOtherSeedDiffers) {
  const auto b = run_bearing_tool("generate '" + scenario_ + "' --out '" + dir_ + "/b' --format bag,npy --quiet");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  for (const char* f : {"gen_test.bag", "gen_test_vibration.npy", "gen_test_vibration_ideal.npy", "gen_test.json"})
    expect_same_bytes(dir_ + "/a/" + f, dir_ + "/b/" + f);
  const auto c =
      run_bearing_tool("generate '" + scenario_ + "' --out '" + dir_ + "/c' --format bag,npy --seed 6 --quiet");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  // The sensor noise follows the seed (this bearing has no random imperfections, so the
  // ideal acceleration does not depend on it).
  EXPECT_NE(read_text(dir_ + "/a/gen_test.bag"), read_text(dir_ + "/c/gen_test.bag"));
  EXPECT_NE(read_text(dir_ + "/a/gen_test_vibration.npy"), read_text(dir_ + "/c/gen_test_vibration.npy"));
  const auto labels = messages<bearing_sim::ScenarioState>(dir_ + "/c/gen_test.bag", "/bearing/scenario_state");
  ASSERT_FALSE(labels.empty());
  EXPECT_EQ(labels[0].seed, 6u);
}

TEST_F(Generate, ParallelThreadsGiveTheSameBytesAsOneByOne) {
  const std::string second = dir_ + "/gen_test2.yaml";
  const auto both = run_bearing_tool("generate '" + scenario_ + "' '" + second + "' --out '" + dir_ +
                                     "/p' --format bag,npy --threads 2 --quiet");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  const auto one =
      run_bearing_tool("generate '" + second + "' --out '" + dir_ + "/s' --format bag,npy --threads 1 --quiet");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  for (const char* f : {"gen_test.bag", "gen_test_vibration.npy", "gen_test.json"})
    expect_same_bytes(dir_ + "/a/" + f, dir_ + "/p/" + f);
  for (const char* f : {"gen_test2.bag", "gen_test2_vibration.npy", "gen_test2_vibration_ideal.npy", "gen_test2.json"})
    expect_same_bytes(dir_ + "/s/" + f, dir_ + "/p/" + f);
  // The summary gives the real-time factor of each scenario.
  EXPECT_NE(both.out.find("gen_test2"), std::string::npos);
  EXPECT_NE(both.out.find("x real time per core"), std::string::npos) << both.out;
}

TEST_F(Generate, BadInputExitsTwoNamingTheProblem) {
  auto expect_bad = [&](const std::string& args, const std::string& what) {
    const auto r = run_bearing_tool("generate " + args + " --quiet");
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
  };
  expect_bad("'" + dir_ + "/missing.yaml' --out '" + dir_ + "/x'", "missing.yaml");
  std::ofstream(dir_ + "/bad.yaml") << scenario_text("bad", 1) << "speeed: 3\n";
  expect_bad("'" + dir_ + "/bad.yaml' --out '" + dir_ + "/x'", "'speeed'");
  std::ofstream(dir_ + "/not_a_dir") << "x";
  expect_bad("'" + scenario_ + "' --out '" + dir_ + "/not_a_dir/sub'", "not_a_dir/sub");
  expect_bad("'" + scenario_ + "' --out '" + dir_ + "/x' --format hdf5", "hdf5");
  expect_bad("'" + scenario_ + "' '" + scenario_ + "' --out '" + dir_ + "/x'", "gen_test");  // same name twice
  expect_bad("'" + scenario_ + "' --out '" + dir_ + "/x' --duration-s -1", "duration");
}

TEST_F(Generate, AFlexibleRingScenarioIsFlexibleDynamicsDrivenByIt) {
  // The CT bearing with its flexible ring through a speed ramp, a load step and a spall: the
  // ideal stream is FlexibleDynamics' rigid-body x acceleration driven as the scenario says
  // (speed at each sample's middle, the load's line through it, defects before the sample
  // after their time), to the float.
  const std::string file = dir_ + "/flexible.yaml";
  std::ofstream(file)
      << "name: flexible\nduration_s: 0.12\nseed: 3\nbearing_file: "
      << source_file("config/bearings/ct_gantry_flexible.yaml")
      << "\nspeed:\n  initial_speed_rpm: 150\n"
         "  segments: [{type: ramp, start_s: 0.02, end_s: 0.1, to_speed_rpm: 180}]\n"
         "load:\n  initial: {force_N: [6800, 0, 0], moment_Nm: [0, 2100]}\n"
         "  segments: [{type: step, start_s: 0.05, force_N: [9000, 0, 0], moment_Nm: [0, 2100]}]\n"
         "defects:\n  - {type: spall, at_s: 0.03, surface: outer_race, position_deg: 0, width_mm: 1, depth_um: 20}\n";
  const auto r = run_bearing_tool("generate '" + file + "' --out '" + dir_ + "/f' --format npy --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::uint64_t rows = 0;
  const std::vector<float> ideal = read_npy(dir_ + "/f/flexible_vibration_ideal.npy", &rows);
  ASSERT_EQ(rows, 1200u);

  const bearing_sim::Scenario sc = bearing_sim::Scenario::load(file);
  bearing_sim::BearingConfig config = bearing_sim::load_bearing_config(sc.bearing_file());
  config.imperfections.seed = 3;
  const double rate = sc.sample_rate_hz();
  bearing_sim::FlexibleDynamics d(bearing_sim::FlexibleBearing(bearing_sim::BearingModel(config)), sc.load_at(0.0),
                                  sc.ring_speed_at(0.0), rate);
  EXPECT_EQ(ideal[0], static_cast<float>(d.current().accelerations[0]));
  std::size_t next_event = 0;
  const auto& events = sc.defect_events();
  for (std::uint64_t i = 1; i < rows; ++i) {
    for (; next_event < events.size() && events[next_event].time_s <= (i - 1) / rate; ++next_event)
      d.add_spall(events[next_event].spall);
    const double mid = (i - 0.5) / rate;
    if (sc.ring_speed_at(mid) != d.ring_speed_rad_s()) d.set_ring_speed(sc.ring_speed_at(mid));
    const bearing_sim::Vector5 load = sc.load_at(mid), load_end = sc.load_at(i / rate);
    if (load != d.load() || load_end != load) d.set_load(load, load_end);
    ASSERT_EQ(ideal[3 * i], static_cast<float>(d.step().accelerations[0])) << "sample " << i;
  }
  EXPECT_EQ(next_event, events.size());
}
