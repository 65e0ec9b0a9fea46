// ROS-free health units of the node: HealthMonitor (ring buffer, worker, life), the
// triaxial sensor, and the chunk's tilt fields. References are closed forms and synthetic
// signals with known content.
#include <algorithm>
#include <cmath>
#include <future>
#include <random>

#include <gtest/gtest.h>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/runtime/chunk_assembler.hpp"
#include "bearing_sim/runtime/health_monitor.hpp"
#include "bearing_sim/runtime/triaxial_sensor.hpp"

#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::runtime;

namespace {
constexpr double kFs = 10000.0;

using bearing_sim::test::ct_load;  // the CT gantry's load (test_support)

HealthSettings settings() {
  HealthSettings s;
  s.sample_rate_hz = kFs;
  s.window_s = 2.0;
  s.analysis.resonance_hz = 3000.0;  // the shipped sensor's path resonance
  return s;
}

// Gaussian noise of sigma plus, optionally, a 3 kHz ring-down (tau 1 ms, amplitude a) once
// per period of 1/impact_hz, each impact scattered about its place on the grid by 1 % of the
// period (a rolling element's slip, not accumulating): what a spall struck by every ball
// gives through the sensor path.
std::vector<float> signal(double seconds, double sigma, double impact_hz, double a, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, sigma);
  const std::size_t len = static_cast<std::size_t>(seconds * kFs);
  std::vector<double> impacts;
  if (impact_hz > 0.0) {
    std::normal_distribution<double> scatter(0.0, 0.01 / impact_hz);
    for (int k = 0; k <= static_cast<int>(seconds * impact_hz) + 1; ++k)
      impacts.push_back(k / impact_hz + scatter(rng));
  }
  std::vector<float> x(len);
  for (std::size_t i = 0; i < len; ++i) {
    const double t = static_cast<double>(i) / kFs;
    double v = n(rng);
    const auto next = std::upper_bound(impacts.begin(), impacts.end(), t);
    if (next != impacts.begin()) {
      const double since = t - *(next - 1);
      v += a * std::exp(-since / 1e-3) * std::sin(2.0 * M_PI * 3000.0 * since);
    }
    x[i] = static_cast<float>(v);
  }
  return x;
}

const FaultIndicator& fault(const HealthReport& r, FaultKind kind) {
  for (const auto& f : r.indicators.faults)
    if (f.kind == kind) return f;
  throw std::runtime_error("no such fault line");
}
}  // namespace

TEST(HealthMonitor, ImpactTrainAtTheInnerRaceFrequencyIsAWarningNoiseIsOk) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  const double bpfi = bearing_frequencies(model, test::kCtSpeedRadS).ball_pass_inner_race_hz;  // 313.2 Hz
  HealthMonitor noisy(model, ct_load(), test::kCtSpeedRadS, settings(), nullptr);
  const auto noise = signal(3.0, 1e-3, 0.0, 0.0, 1);
  noisy.push(noise.data(), noise.size());
  const HealthReport ok = noisy.analyze_now(3.0);
  ASSERT_TRUE(ok.analysed) << ok.error;
  EXPECT_EQ(ok.indicators.diagnosis.level, HealthLevel::Ok) << ok.indicators.diagnosis.reason;
  EXPECT_NEAR(ok.indicators.acceleration.rms, 1e-3, 3e-5);
  EXPECT_NEAR(ok.indicators.window_s, 2.0, 0.05);

  HealthMonitor faulty(model, ct_load(), test::kCtSpeedRadS, settings(), nullptr);
  const auto impacts = signal(3.0, 1e-3, bpfi, 5e-3, 2);
  faulty.push(impacts.data(), impacts.size());
  const HealthReport warn = faulty.analyze_now(3.0);
  ASSERT_TRUE(warn.analysed) << warn.error;
  EXPECT_GE(warn.indicators.diagnosis.level, HealthLevel::Warn);
  const FaultIndicator& f = fault(warn, FaultKind::InnerRace);
  EXPECT_TRUE(f.suspected);
  EXPECT_NEAR(f.envelope_peak.frequency_hz, bpfi, 0.01 * bpfi);
  EXPECT_GE(f.envelope_peak.snr_db, 10.0);
  EXPECT_NE(warn.indicators.diagnosis.reason.find("inner race defect suspected"), std::string::npos);
}

TEST(HealthMonitor, RingBufferHoldsTheLastWindowOnly) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  HealthMonitor m(model, ct_load(), test::kCtSpeedRadS, settings(), nullptr);
  const auto loud = signal(1.0, 10.0, 0.0, 0.0, 3);
  m.push(loud.data(), loud.size());
  const HealthReport early = m.analyze_now(1.0);
  EXPECT_FALSE(early.analysed);  // 1 s of a 2 s window
  EXPECT_EQ(early.error.rfind("collecting", 0), 0u) << early.error;
  const auto quiet = signal(2.0, 0.01, 0.0, 0.0, 4);
  // In pieces of a chunk, as the node hands them over.
  for (std::size_t i = 0; i < quiet.size(); i += 100)
    m.push(quiet.data() + i, std::min<std::size_t>(100, quiet.size() - i));
  const HealthReport r = m.analyze_now(3.0);
  ASSERT_TRUE(r.analysed);
  EXPECT_NEAR(r.indicators.acceleration.rms, 0.01, 5e-4);  // none of the loud second
  EXPECT_EQ(r.end_sample, 30000u);
  EXPECT_EQ(m.samples_pushed(), 30000u);
}

TEST(HealthMonitor, MinerDamageAndLivesFollowTheOperation) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  HealthMonitor m(model, ct_load(), test::kCtSpeedRadS, settings(), nullptr);
  for (int i = 0; i < 1000; ++i) m.add_operation(ct_load(), test::kCtSpeedRadS, 0.01);  // 10 s at 180 rpm
  const HealthReport r = m.analyze_now(10.0);
  // ISO 281 for the double-row 35 deg bearing with Fa = 0: P = Fr (X = 1, Y = 0.66 Fa).
  const double c = basic_dynamic_load_rating_N(model.config());
  const double l10_rev = std::pow(c / 6800.0, 3.0) * 1e6;
  EXPECT_NEAR(r.iso281.equivalent.load_N, 6800.0, 1e-9);
  EXPECT_NEAR(r.iso281.life_million_rev * 1e6, l10_rev, 1e-9 * l10_rev);
  EXPECT_NEAR(r.revolutions, 30.0, 1e-9);
  EXPECT_NEAR(r.operated_s, 10.0, 1e-9);
  // The reference life from the ball loads (with the moment) against ISO/TS 16281's
  // closed forms is tested in test_bearing_life; here: the CT case of docs/health.md.
  const double ref_rev = r.reference_life_million_rev * 1e6;
  EXPECT_NEAR(r.reference_life_million_rev, 1063.0, 10.0);
  EXPECT_NEAR(r.reference_life_hours, ref_rev / 3.0 / 3600.0, 1e-6 * r.reference_life_hours);
  // Miner's sum uses the same life: 30 revolutions of a 1063 Mrev life.
  EXPECT_NEAR(r.miner_damage, 30.0 / ref_rev, 1e-9 * 30.0 / ref_rev);
  // Remaining life at a constant rate: the reference life less what was used.
  EXPECT_NEAR(r.remaining_life_hours, (ref_rev - 30.0) / 3.0 / 3600.0, 1e-6 * ref_rev / 3.0 / 3600.0);
  // Standstill: infinite remaining life, damage unchanged.
  m.add_operation(ct_load(), 0.0, 1.0);
  const HealthReport s = m.analyze_now(11.0);
  EXPECT_TRUE(std::isinf(s.remaining_life_hours));
  EXPECT_DOUBLE_EQ(s.miner_damage, r.miner_damage);
}

TEST(HealthMonitor, MinerDamageFollowsALoadChange) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  HealthMonitor m(model, ct_load(), test::kCtSpeedRadS, settings(), nullptr);
  const double life0 = m.analyze_now(0.0).reference_life_million_rev;
  // Twice the radial load: until the next analysis the life is scaled by ISO 281's
  // (P_then / P_now)^3 = 1/8 (Fa = 0: P = Fr).
  Vector5 heavy = ct_load();
  heavy[0] *= 2.0;
  m.add_operation(heavy, test::kCtSpeedRadS, 10.0);  // 30 revolutions
  const HealthReport a = m.analyze_now(10.0);
  EXPECT_NEAR(a.miner_damage, 30.0 / (life0 / 8.0 * 1e6), 1e-9 * a.miner_damage);
  // After an analysis at the new load: its own reference life, from its ball loads.
  const double life1 = a.reference_life_million_rev;
  EXPECT_LT(life1, life0 / 4.0);  // ball loads grow with the load: (Q_c/Q_e)^3 falls ~8x
  m.add_operation(heavy, test::kCtSpeedRadS, 10.0);
  const HealthReport b = m.analyze_now(20.0);
  EXPECT_NEAR(b.miner_damage - a.miner_damage, 30.0 / (life1 * 1e6), 1e-9 * b.miner_damage);
}

TEST(HealthMonitor, DefectsAreReportedWithTheirSizeNow) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  HealthMonitor m(model, ct_load(), test::kCtSpeedRadS, settings(), nullptr);
  Spall s;
  s.surface = Surface::InnerRace;
  s.position_rad = 3.0;
  s.width_m = 1e-3;
  s.depth_m = 10e-6;
  s.width_growth_m_per_s = 1e-6;
  s.depth_growth_m_per_s = 1e-8;
  s.created_at_s = 10.0;
  m.set_defects({s});
  HealthReport r = m.analyze_now(20.0);
  ASSERT_EQ(r.defects.size(), 1u);
  EXPECT_NEAR(r.defects[0].age_s, 10.0, 1e-12);
  EXPECT_NEAR(r.defects[0].width_m, 1.01e-3, 1e-15);
  EXPECT_NEAR(r.defects[0].depth_m, 10.1e-6, 1e-15);
  m.set_defects({});
  EXPECT_TRUE(m.analyze_now(21.0).defects.empty());
}

TEST(HealthMonitor, WorkerAnalysesOnRequestAndStops) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  std::promise<HealthReport> got;
  auto future = got.get_future();
  bool once = false;
  HealthMonitor m(model, ct_load(), test::kCtSpeedRadS, settings(), [&](const HealthReport& r) {
    if (!once) got.set_value(r);
    once = true;
  });
  m.start();
  const auto x = signal(2.0, 1e-3, 0.0, 0.0, 5);
  m.push(x.data(), x.size());
  m.request_analysis(12.5);
  ASSERT_EQ(future.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  const HealthReport r = future.get();
  EXPECT_TRUE(r.analysed);
  EXPECT_DOUBLE_EQ(r.end_time_s, 12.5);
  m.stop();
  EXPECT_EQ(m.analyses(), 1u);
}

TEST(HealthMonitor, BadSettingsAreRefused) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  HealthSettings s = settings();
  s.window_s = 0.001;  // 10 samples
  EXPECT_THROW(HealthMonitor(model, ct_load(), test::kCtSpeedRadS, s, nullptr), InvalidInputError);
  s = settings();
  s.sample_rate_hz = 0.0;
  EXPECT_THROW(HealthMonitor(model, ct_load(), test::kCtSpeedRadS, s, nullptr), InvalidInputError);
}

namespace {
AccelerometerConfig quiet_sensor(double output_rate_hz) {
  AccelerometerConfig c;
  c.path_resonance_hz = 0.0;
  c.noise_density_m_s2_per_sqrt_hz = 0.0;
  c.output_rate_hz = output_rate_hz;
  c.mount_point_m = Eigen::Vector3d(0.5, 0.0, 0.0);
  return c;
}
}  // namespace

TEST(TriaxialSensor, ThreeAxesAtTheMountingPointIncludingTheTiltLever) {
  TriaxialSensor sensor(quiet_sensor(10000.0), 20000.0);
  EXPECT_EQ(sensor.decimation_ratio(), 2);
  DynamicSample s;
  // Translation (1, 2, 3) m/s^2 and tilt acceleration alpha = (0, 4, 0) rad/s^2: at r = (0.5, 0, 0)
  // the point sees a + alpha x r = (1, 2, 3 - 4 * 0.5) = (1, 2, 1).
  s.acceleration << 1.0, 2.0, 3.0, 0.0, 4.0;
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  int outputs = 0;
  for (int i = 0; i < 4000; ++i) outputs += sensor.push(s, &y);
  EXPECT_EQ(outputs, 2000);  // one per two inputs
  // After the anti-alias filter has settled (DC gain 1), up to the 24-bit quantization step.
  const double q = 2.0 * 50.0 * kStandardGravity_m_s2 / std::pow(2.0, 24);
  EXPECT_NEAR(y[0], 1.0, q);
  EXPECT_NEAR(y[1], 2.0, q);
  EXPECT_NEAR(y[2], 1.0, q);
}

TEST(TriaxialSensor, ChannelsFollowTheSensorsOwnAxesRightHanded) {
  // Positive up at 12 o'clock, the load down: channels along -x, -y, z.
  AccelerometerConfig c = quiet_sensor(10000.0);
  c.axis = Eigen::Vector3d(-1.0, 0.0, 0.0);
  TriaxialSensor sensor(c, 10000.0);
  DynamicSample s;
  s.acceleration << 1.0, 2.0, 3.0, 0.0, 4.0;  // the point sees (1, 2, 1), as above
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4000; ++i) sensor.push(s, &y);
  const double q = 2.0 * 50.0 * kStandardGravity_m_s2 / std::pow(2.0, 24);
  EXPECT_NEAR(y[0], -1.0, q);
  EXPECT_NEAR(y[1], -2.0, q);
  EXPECT_NEAR(y[2], 1.0, q);
  // Any axis: an orthonormal, right-handed frame with channel 0 along it.
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -3),
                                      Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(-0.3, 0.1, 0.0)}) {
    const Eigen::Matrix3d f = triaxial_frame(axis);
    EXPECT_LT((f.transpose() * f - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(f.determinant(), 1.0, 1e-12);
    EXPECT_LT((f.col(0) - axis.normalized()).norm(), 1e-15);
  }
  EXPECT_LT((triaxial_frame(Eigen::Vector3d(1, 0, 0)) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(TriaxialSensor, ChannelsHaveIndependentNoise) {
  AccelerometerConfig c = quiet_sensor(10000.0);
  c.noise_density_m_s2_per_sqrt_hz = 1e-3;
  TriaxialSensor sensor(c, 10000.0);
  EXPECT_EQ(triaxial_channel_config(c, 1).seed, c.seed + 1);
  DynamicSample s;
  Eigen::Vector3d y;
  double sxy = 0, sxx = 0, syy = 0;
  for (int i = 0; i < 20000; ++i) {
    ASSERT_TRUE(sensor.push(s, &y));
    sxy += y[0] * y[1];
    sxx += y[0] * y[0];
    syy += y[1] * y[1];
  }
  EXPECT_LT(std::abs(sxy / std::sqrt(sxx * syy)), 0.05);
  EXPECT_GT(sxx, 0.0);
}

TEST(TriaxialSensor, OutputRateThatDoesNotDivideTheDynamicsRateIsAnError) {
  EXPECT_THROW(TriaxialSensor(quiet_sensor(10000.0), 15000.0), InvalidInputError);
  EXPECT_THROW(TriaxialSensor(quiet_sensor(51200.0 * 2), 102400.0), InvalidInputError);
}

TEST(ChunkAssembler, ChunksCarryTheTilt) {
  ChunkAssembler a(2);
  DynamicSample s;
  s.displacement << 1e-6, 2e-6, 3e-6, 1e-5, -2e-5;
  s.acceleration << 0.1, 0.2, 0.3, 0.0, 0.0;
  EXPECT_FALSE(a.add(0, s));
  EXPECT_TRUE(a.add(1, Eigen::Vector3d(7.0, 8.0, 9.0), s.displacement));
  const SampleChunk c = a.take();
  ASSERT_EQ(c.tilt_x.size(), 2u);
  EXPECT_FLOAT_EQ(c.tilt_x[0], 1e-5f);
  EXPECT_FLOAT_EQ(c.tilt_y[1], -2e-5f);
  EXPECT_FLOAT_EQ(c.accel_x[0], 0.1f);
  EXPECT_FLOAT_EQ(c.accel_x[1], 7.0f);
  EXPECT_FLOAT_EQ(c.displacement_z[1], 3e-6f);
}
