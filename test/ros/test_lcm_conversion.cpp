// ROS -> LCM conversions and LCM transport, no ROS master: every field and every sample
// must come back bit-exact after encoding, an in-process LCM (memq://) publish + handle,
// or an LCM log written by LcmPublishQueue; bad URLs give LcmUrlError naming the URL.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include "bearing_sim/ros/lcm_conversion.hpp"
#include "bearing_sim/ros/lcm_publish_queue.hpp"
#include "lcm_test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::ros_node;
using lcm_test::bits;
using lcm_test::expect_equal;

namespace {

// Every 32-bit pattern is equally likely: NaNs with payloads, infinities, -0 and
// subnormals included, so only a bit-exact path survives.
std::vector<float> random_floats(std::size_t n, std::mt19937& rng) {
  std::vector<float> v(n);
  for (float& x : v) {
    const std::uint32_t b = static_cast<std::uint32_t>(rng());
    std::memcpy(&x, &b, sizeof x);
  }
  return v;
}

std_msgs::Header header(std::uint32_t sec, std::uint32_t nsec, std::uint32_t seq, const std::string& frame) {
  std_msgs::Header h;
  h.stamp.sec = sec;
  h.stamp.nsec = nsec;
  h.seq = seq;
  h.frame_id = frame;
  return h;
}

VibrationChunk chunk(std::size_t n, std::uint64_t first_sample, std::uint32_t seed) {
  std::mt19937 rng(seed);
  VibrationChunk c;
  c.header = header(1763900000, 123456789, 42, "bearing_outer_ring");
  c.first_sample = first_sample;
  c.sample_rate = 10000.0;
  for (auto* a : {&c.accel_x, &c.accel_y, &c.accel_z, &c.displacement_x, &c.displacement_y, &c.displacement_z,
                  &c.tilt_x, &c.tilt_y})
    *a = random_floats(n, rng);
  return c;
}

BearingHealth health(std::size_t faults, std::size_t defects) {
  BearingHealth h;
  h.header = header(12, 500000000, 7, "bearing");
  h.signal = "sensor: CT gantry housing accelerometer";
  h.sample_rate = 10000.0;
  h.window_s = 1.6384;
  h.accel_rms = 9.3e-4;
  h.accel_peak = 3.9e-3;
  h.crest_factor = 4.19;
  h.kurtosis = 3.01;
  h.level_db = -20.45;
  h.velocity_rms_mm_s = 1.1e-4;
  h.velocity_zone = "A";
  h.envelope_low_hz = 2000.0;
  h.envelope_high_hz = 4000.0;
  const char* labels[] = {"BPFO", "BPFI", "2xBSF", "FTF"};
  const char* parts[] = {"outer race", "inner race", "ball", "cage"};
  for (std::size_t i = 0; i < faults; ++i) {
    EnvelopeLine l;
    l.label = labels[i % 4];
    l.part = parts[i % 4];
    l.expected_hz = 305.1 + static_cast<double>(i);
    l.peak_hz = 305.2 + static_cast<double>(i);
    l.amplitude_m_s2 = 1e-5 * static_cast<double>(i + 1);
    l.noise_floor_m_s2 = 1e-7;
    l.snr_db = std::nan("7");  // a payload-carrying NaN must survive
    l.harmonics_found = static_cast<std::uint8_t>(i % 4);
    l.sidebands_required = i % 2 == 1;
    l.modulation_hz = 29.5;
    l.sidebands_found = static_cast<std::uint8_t>(i % 3);
    l.resolvable = i != 3;
    l.impulsiveness_required = i % 2 == 0;
    l.impulsive = i == 2;
    l.band_kurtosis = 0.25 * static_cast<double>(i) - 0.1;
    l.suspected = i % 2 == 0;
    l.note = i == 3 ? "FTF 0.50 Hz is not resolvable in a 1 s window: 10 s needed" : "";
    h.faults.push_back(l);
  }
  h.level = BearingHealth::WARN;
  h.reason = "outer race: BPFO line 24 dB above the floor";
  for (std::size_t i = 0; i < defects; ++i) {
    DefectState d;
    d.surface = i == 0 ? "outer_race" : "ball";
    d.position_rad = -0.0;
    d.ball = i == 0 ? -1 : 413;
    d.row = i == 0 ? 1 : -1;
    d.width_m = 2e-3;
    d.depth_m = 2e-5;
    d.width_growth_m_per_s = 1e-9;
    d.depth_growth_m_per_s = std::numeric_limits<double>::denorm_min();
    d.age_s = 3.25;
    h.defects.push_back(d);
  }
  h.ring_speed_rad_s = 18.84955592153876;
  h.radial_force_N = 6800.0;
  h.axial_force_N = 0.0;
  h.dynamic_load_rating_N = 3.1e5;
  h.equivalent_load_N = 6800.0;
  h.l10_million_rev = 9.5e4;
  h.l10_hours = std::numeric_limits<double>::infinity();
  h.reference_life_million_rev = 8.1e4;
  h.reference_life_hours = -std::numeric_limits<double>::infinity();
  h.miner_damage = 1.0 / 3.0;
  h.remaining_life_hours = 1.7e6;
  h.operated_s = 12.5;
  h.revolutions = 37.5;
  return h;
}

template <class T>
struct Catcher {
  std::vector<T> received;
  void on(const lcm::ReceiveBuffer*, const std::string&, const T* msg) { received.push_back(*msg); }
};

// The bridge's path: encode_lcm(to_lcm(ros)) bytes published raw on an in-process LCM,
// decoded by a typed subscriber as any LCM consumer would.
template <class LcmType, class RosMessage>
LcmType round_trip(const RosMessage& ros) {
  lcm::LCM lcm("memq://");
  EXPECT_TRUE(lcm.good());
  Catcher<LcmType> catcher;
  lcm.subscribe("BEARING_TEST", &Catcher<LcmType>::on, &catcher);
  const std::vector<std::uint8_t> bytes = encode_lcm(to_lcm(ros));
  EXPECT_EQ(lcm.publish("BEARING_TEST", bytes.data(), static_cast<unsigned int>(bytes.size())), 0);
  EXPECT_GT(lcm.handleTimeout(5000), 0);
  if (catcher.received.size() != 1) {
    ADD_FAILURE() << "received " << catcher.received.size() << " messages, expected 1";
    return LcmType();
  }
  return catcher.received.front();
}

std::string temp_log(const std::string& name) {
  return "/tmp/bearing_sim_test_lcm_" + std::to_string(::getpid()) + "_" + name + ".lcm";
}

}  // namespace

TEST(LcmUtime, WholeMicrosecondsOfTheStamp) {
  EXPECT_EQ(lcm_utime(0, 0), 0);
  EXPECT_EQ(lcm_utime(0, 999), 0);  // below a microsecond: dropped, not rounded
  EXPECT_EQ(lcm_utime(1, 1999), 1000001);
  EXPECT_EQ(lcm_utime(1763900000, 123456789), 1763900000123456);
  // The largest ROS stamp does not overflow (sec is uint32 in ROS).
  EXPECT_EQ(lcm_utime(4294967295u, 999999999u), 4294967295999999LL);
}

TEST(LcmConversion, VibrationChunkEverySampleBitExact) {
  const VibrationChunk ros = chunk(100, 1234567890123ULL, 1);
  const auto lcm = round_trip<bearing_sim_lcm::vibration_chunk_t>(ros);
  EXPECT_EQ(lcm.num_samples, 100);
  expect_equal(ros, lcm);
  // The extremes of the ROS stamp survive exactly.
  VibrationChunk extreme = chunk(3, 0, 2);
  extreme.header = header(4294967295u, 999999999u, 4294967295u, "");
  expect_equal(extreme, round_trip<bearing_sim_lcm::vibration_chunk_t>(extreme));
}

TEST(LcmConversion, LargeChunkBitExact) {
  // 2^18 samples x 8 arrays: 8 MB, far beyond one UDP datagram; the largest first_sample an
  // int64 holds.
  const VibrationChunk ros = chunk(1u << 18, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()), 3);
  const auto lcm = round_trip<bearing_sim_lcm::vibration_chunk_t>(ros);
  EXPECT_EQ(lcm.num_samples, 1 << 18);
  expect_equal(ros, lcm);
}

TEST(LcmConversion, EmptyChunk) {
  const VibrationChunk ros = chunk(0, 77, 4);
  const auto lcm = round_trip<bearing_sim_lcm::vibration_chunk_t>(ros);
  EXPECT_EQ(lcm.num_samples, 0);
  EXPECT_EQ(lcm.first_sample, 77);
  expect_equal(ros, lcm);
}

TEST(LcmConversion, ChunkThatCannotBeMirroredIsRefusedWithTheReason) {
  VibrationChunk uneven = chunk(10, 0, 5);
  uneven.tilt_y.pop_back();
  try {
    to_lcm(uneven);
    FAIL() << "no exception for arrays of unequal length";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tilt_y has 9 elements"), std::string::npos) << e.what();
  }
  VibrationChunk huge_index = chunk(1, static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) + 1, 6);
  try {
    to_lcm(huge_index);
    FAIL() << "no exception for a first_sample beyond int64";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("first_sample"), std::string::npos) << e.what();
  }
}

TEST(LcmConversion, VibrationLevel) {
  VibrationLevel ros;
  ros.header = header(3, 100000000, 30, "bearing_outer_ring");
  ros.level_db = -std::numeric_limits<double>::infinity();  // zero RMS
  ros.accel_rms = 0.0;
  ros.window_s = 0.3;
  const auto lcm = round_trip<bearing_sim_lcm::vibration_level_t>(ros);
  expect_equal(ros, lcm);
  EXPECT_TRUE(std::isinf(lcm.level_db) && lcm.level_db < 0.0);
}

TEST(LcmConversion, BallLoadsOfTheCtBearingAndEmpty) {
  std::mt19937 rng(8);
  BallLoads ros;
  ros.header = header(5, 33333333, 150, "bearing");
  ros.rows = 2;
  ros.balls_per_row = 207;
  ros.cage_angle = 1.2345678901234567;
  ros.azimuth = random_floats(414, rng);
  ros.load = random_floats(414, rng);
  ros.contact_angle = random_floats(414, rng);
  ros.deflection = random_floats(414, rng);
  const auto lcm = round_trip<bearing_sim_lcm::ball_loads_t>(ros);
  EXPECT_EQ(lcm.num_balls, 414);
  expect_equal(ros, lcm);

  // The unsigned ROS fields at their maxima, no balls.
  BallLoads empty;
  empty.rows = 255;
  empty.balls_per_row = 65535;
  const auto lcm_empty = round_trip<bearing_sim_lcm::ball_loads_t>(empty);
  EXPECT_EQ(lcm_empty.rows, 255);
  EXPECT_EQ(lcm_empty.balls_per_row, 65535);
  EXPECT_EQ(lcm_empty.num_balls, 0);
  expect_equal(empty, lcm_empty);

  BallLoads uneven = ros;
  uneven.deflection.push_back(0.0f);
  EXPECT_THROW(to_lcm(uneven), std::invalid_argument);
}

TEST(LcmConversion, HealthWithEnvelopeLinesAndDefects) {
  const BearingHealth ros = health(4, 2);
  const auto lcm = round_trip<bearing_sim_lcm::bearing_health_t>(ros);
  EXPECT_EQ(lcm.num_faults, 4);
  EXPECT_EQ(lcm.num_defects, 2);
  EXPECT_EQ(lcm.level, bearing_sim_lcm::bearing_health_t::WARN);
  expect_equal(ros, lcm);
  // The constants agree with the ROS message's.
  EXPECT_EQ(bearing_sim_lcm::bearing_health_t::OK, BearingHealth::OK);
  EXPECT_EQ(bearing_sim_lcm::bearing_health_t::WARN, BearingHealth::WARN);
  EXPECT_EQ(bearing_sim_lcm::bearing_health_t::ERROR, BearingHealth::ERROR);
}

TEST(LcmConversion, HealthBeforeTheFirstAnalysisHasNoLinesNorDefects) {
  BearingHealth ros = health(0, 0);
  ros.signal.clear();
  ros.reason.clear();
  const auto lcm = round_trip<bearing_sim_lcm::bearing_health_t>(ros);
  EXPECT_EQ(lcm.num_faults, 0);
  EXPECT_EQ(lcm.num_defects, 0);
  expect_equal(ros, lcm);
}

TEST(LcmPublishQueue, BadUrlsAreRefusedNamingTheUrl) {
  for (const std::string url :
       {"nosuch://x", "file:///nonexistent_dir_bearing_sim/x.lcm?mode=w", "udpm://999.1.1.1:7667", "garbage"}) {
    try {
      LcmPublishQueue q(url, 1000);
      ADD_FAILURE() << "no error for " << url;
    } catch (const LcmUrlError& e) {
      EXPECT_NE(std::string(e.what()).find("'" + url + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(LcmPublishQueue, LogFileHoldsEveryMessageInOrderBitExact) {
  const std::string path = temp_log("order");
  std::vector<std::vector<std::uint8_t>> sent;
  {
    LcmPublishQueue q("file://" + path + "?mode=w", 64u << 20);
    for (std::uint32_t i = 0; i < 2000; ++i) {
      // 100-sample chunks as the node publishes them, interleaved with levels.
      sent.push_back(i % 10 == 9 ? encode_lcm(to_lcm(VibrationLevel())) : encode_lcm(to_lcm(chunk(100, 100 * i, i))));
      std::vector<std::uint8_t> copy = sent.back();
      EXPECT_TRUE(q.push(i % 10 == 9 ? "LEVEL" : "VIB", std::move(copy)));
    }
    q.flush();
    const LcmPublishStats s = q.stats();
    EXPECT_EQ(s.published, 2000u);
    EXPECT_EQ(s.failed, 0u);
    EXPECT_EQ(s.dropped, 0u);
    EXPECT_EQ(s.queued_messages, 0u);
    EXPECT_EQ(s.queued_bytes, 0u);
  }  // closes the log
  lcm::LogFile log(path, "r");
  ASSERT_TRUE(log.good());
  std::size_t n = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent(), ++n) {
    ASSERT_LT(n, sent.size());
    EXPECT_EQ(e->channel, n % 10 == 9 ? "LEVEL" : "VIB");
    ASSERT_EQ(static_cast<std::size_t>(e->datalen), sent[n].size());
    EXPECT_EQ(std::memcmp(e->data, sent[n].data(), sent[n].size()), 0) << "event " << n;
  }
  EXPECT_EQ(n, sent.size());
  // And it decodes to the chunk that went in.
  lcm::LogFile again(path, "r");
  const lcm::LogEvent* first = again.readNextEvent();
  ASSERT_NE(first, nullptr);
  bearing_sim_lcm::vibration_chunk_t decoded;
  ASSERT_EQ(decoded.decode(first->data, 0, first->datalen), first->datalen);
  expect_equal(chunk(100, 0, 0), decoded);
  std::remove(path.c_str());
}

TEST(LcmPublishQueue, PublishFailuresAreCounted) {
  // An LCM log opened for reading accepts no publish: every one fails.
  const std::string path = temp_log("readonly");
  {
    LcmPublishQueue writer("file://" + path + "?mode=w", 1u << 20);
    writer.push("VIB", encode_lcm(to_lcm(chunk(10, 0, 9))));
  }
  LcmPublishQueue q("file://" + path, 1u << 20);
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(q.push("VIB", encode_lcm(to_lcm(chunk(10, 10 * i, 9)))));
  q.flush();
  const LcmPublishStats s = q.stats();
  EXPECT_EQ(s.failed, 5u);
  EXPECT_EQ(s.published, 0u);
  std::remove(path.c_str());
}

TEST(LcmPublishQueue, MessageLargerThanTheQueueIsDroppedAndCounted) {
  LcmPublishQueue q("memq://", 4000);
  const std::vector<std::uint8_t> small = encode_lcm(to_lcm(chunk(100, 0, 10)));  // 3.3 kB
  ASSERT_LT(small.size(), 4000u);
  EXPECT_FALSE(q.push("VIB", encode_lcm(to_lcm(chunk(200, 0, 10)))));  // 6.5 kB
  EXPECT_TRUE(q.push("VIB", std::vector<std::uint8_t>(small)));
  q.flush();
  const LcmPublishStats s = q.stats();
  EXPECT_EQ(s.dropped, 1u);
  EXPECT_EQ(s.published, 1u);
  EXPECT_EQ(s.bytes_published, small.size());
}
