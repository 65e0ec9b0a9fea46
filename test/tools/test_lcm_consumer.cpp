// examples/lcm_consumer.cpp on an LCM log of a known signal: x = c + A sin(2 pi f t) at
// 10 kHz, in 100-sample chunks. Per second (an integer number of periods) the RMS about
// the mean is A / sqrt(2) whatever c, and L = 20 lg(A / sqrt(2) / 9.81e-3 m/s^2). A missing
// chunk is reported as a gap and makes the exit status 2.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/ros/lcm_conversion.hpp"
#include "bearing_sim/ros/lcm_publish_queue.hpp"
#include "command_runner.hpp"

using namespace bearing_sim;
using namespace bearing_sim::ros_node;

namespace {

constexpr double kRate = 10000.0, kAmplitude = 0.05, kOffset = 0.3, kFrequency = 50.0;

// `seconds` of the signal; the chunk starting at sample `skip` (if any) is left out.
std::string write_log(const std::string& name, int seconds, std::int64_t skip) {
  const std::string path = "/tmp/bearing_sim_test_lcm_consumer_" + std::to_string(::getpid()) + "_" + name + ".lcm";
  LcmPublishQueue queue("file://" + path + "?mode=w", 64u << 20);
  for (std::uint64_t first = 0; first < static_cast<std::uint64_t>(seconds * kRate); first += 100) {
    if (static_cast<std::int64_t>(first) == skip) continue;
    VibrationChunk c;
    c.header.stamp = ros::Time(100.0 + static_cast<double>(first) / kRate);
    c.first_sample = first;
    c.sample_rate = kRate;
    for (std::uint64_t i = first; i < first + 100; ++i) {
      const double t = static_cast<double>(i) / kRate;
      c.accel_x.push_back(static_cast<float>(kOffset + kAmplitude * std::sin(2.0 * M_PI * kFrequency * t)));
    }
    for (auto* a :
         {&c.accel_y, &c.accel_z, &c.displacement_x, &c.displacement_y, &c.displacement_z, &c.tilt_x, &c.tilt_y})
      a->assign(100, 0.0f);
    queue.push("BEARING_VIBRATION", encode_lcm(to_lcm(c)));
    // Another channel in the same log must be ignored.
    queue.push("BEARING_VIBRATION_LEVEL", encode_lcm(to_lcm(VibrationLevel())));
  }
  return path;
}

// The consumer on `log`: its stdout, then its stderr, in `output`.
struct ConsumerRun {
  std::string output;
  int status = -1;
};

ConsumerRun consume(const std::string& log) {
  const std::string command = std::string(LCM_CONSUMER_PATH) + " --url 'file://" + log + "?speed=0' --idle-exit-s 1";
  const test::CommandResult r = test::run_command(command, 300);
  return {r.out + r.err, r.exit_code};
}

struct Line {
  double t, rms, level;
  int samples;
};

std::vector<Line> lines(const std::string& output) {
  static const std::regex re(
      R"(t = +([-0-9.]+) s +samples (\d+) +rms\(accel_x\) = ([-0-9.e+]+) m/s\^2 +L = +([-0-9.]+) dB)");
  std::vector<Line> out;
  for (std::sregex_iterator it(output.begin(), output.end(), re), end; it != end; ++it)
    out.push_back({std::stod((*it)[1]), std::stod((*it)[3]), std::stod((*it)[4]), std::stoi((*it)[2])});
  return out;
}

}  // namespace

TEST(LcmConsumerExample, RmsAndLevelPerSecondOfASine) {
  const std::string log = write_log("sine", 3, -1);
  const ConsumerRun run = consume(log);
  std::remove(log.c_str());
  EXPECT_EQ(run.status, 0) << run.output;
  const std::vector<Line> l = lines(run.output);
  ASSERT_EQ(l.size(), 3u) << run.output;
  const double rms = kAmplitude / std::sqrt(2.0);
  const double level = 20.0 * std::log10(rms / 9.81e-3);
  for (std::size_t i = 0; i < l.size(); ++i) {
    EXPECT_EQ(l[i].samples, 10000);
    EXPECT_NEAR(l[i].t, 100.0 + static_cast<double>(i), 1e-6);  // the second's first sample
    // float32 samples (relative error 6e-8 each), printed with 7 digits.
    EXPECT_NEAR(l[i].rms, rms, 1e-5 * rms);
    EXPECT_NEAR(l[i].level, level, 0.006);  // printed to 0.01 dB
  }
}

TEST(LcmConsumerExample, GapIsReportedAndTheSecondRestarts) {
  // Chunk 1.5 s .. 1.51 s missing: second 1 is abandoned, the next full second starts at 1.51 s.
  const std::string log = write_log("gap", 3, 15000);
  const ConsumerRun run = consume(log);
  std::remove(log.c_str());
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("gap: expected sample 15000, got 15100"), std::string::npos) << run.output;
  const std::vector<Line> l = lines(run.output);
  ASSERT_EQ(l.size(), 2u) << run.output;
  EXPECT_NEAR(l[0].t, 100.0, 1e-6);
  EXPECT_NEAR(l[1].t, 101.51, 1e-6);
  EXPECT_NEAR(l[1].rms, kAmplitude / std::sqrt(2.0), 1e-5 * kAmplitude);
}
