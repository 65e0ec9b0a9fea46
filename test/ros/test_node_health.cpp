// Health on the running CT node (as fast as possible, shipped sensor file): the sensor on
// `vibration`, the ideal acceleration on `vibration_ideal`, a spall injected and cleared by
// the services with `health` and /diagnostics following, and defects that do not fit.
// Reference values from the core (bearing_frequencies, solve_static) and closed forms.
#include <cmath>
#include <deque>
#include <mutex>

#include <std_srvs/Trigger.h>

#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/InjectDefect.h"
#include "bearing_sim/core/bearing_life.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "node_test_support.hpp"
#include "service_calls.hpp"

using bearing_sim::BearingHealth;
using bearing_sim::VibrationChunk;
using node_test::ct_load;
using node_test::ct_model;
using node_test::kCtSpeed;

namespace {

// One VibrationChunk stream: contiguity, and the samples of accel_x on request.
class Stream {
 public:
  void on_chunk(const VibrationChunk::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t n = msg->accel_x.size();
    sample_rate_ = msg->sample_rate;
    if (chunks_ == 0) next_ = msg->first_sample;
    if (msg->first_sample != next_) ++gaps_or_repeats_;
    next_ = msg->first_sample + n;
    ++chunks_;
    for (std::size_t i = 0; i < n; ++i) {
      non_finite_ +=
          !std::isfinite(msg->accel_x[i]) || !std::isfinite(msg->accel_y[i]) || !std::isfinite(msg->accel_z[i]);
      if (capture_.size() < capture_target_) capture_.push_back(msg->accel_x[i]);
    }
    tilt_fields_ok_ = msg->tilt_x.size() == n && msg->tilt_y.size() == n;
  }
  void start_capture(std::size_t n) {
    std::lock_guard<std::mutex> lock(mutex_);
    capture_.clear();
    capture_target_ = n;
  }
  bool captured() {
    std::lock_guard<std::mutex> lock(mutex_);
    return capture_.size() >= capture_target_;
  }
  std::vector<double> capture() {
    std::lock_guard<std::mutex> lock(mutex_);
    return capture_;
  }
  std::uint64_t next() {
    std::lock_guard<std::mutex> lock(mutex_);
    return next_;
  }
  std::uint64_t chunks() {
    std::lock_guard<std::mutex> lock(mutex_);
    return chunks_;
  }
  std::uint64_t gaps_or_repeats() {
    std::lock_guard<std::mutex> lock(mutex_);
    return gaps_or_repeats_;
  }
  std::uint64_t non_finite() {
    std::lock_guard<std::mutex> lock(mutex_);
    return non_finite_;
  }
  double sample_rate() {
    std::lock_guard<std::mutex> lock(mutex_);
    return sample_rate_;
  }
  bool tilt_fields_ok() {
    std::lock_guard<std::mutex> lock(mutex_);
    return tilt_fields_ok_;
  }

 private:
  std::mutex mutex_;
  std::uint64_t next_ = 0, chunks_ = 0, gaps_or_repeats_ = 0, non_finite_ = 0;
  double sample_rate_ = 0.0;
  bool tilt_fields_ok_ = false;
  std::vector<double> capture_;
  std::size_t capture_target_ = 0;
};

struct Fixture {
  ros::NodeHandle nh;
  Stream vibration, ideal;
  std::mutex mutex;
  std::deque<BearingHealth> health;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics;
  ros::Subscriber sub_v, sub_i, sub_h, sub_d;
  Fixture() {
    sub_v = nh.subscribe("vibration", 20000, &Stream::on_chunk, &vibration, ros::TransportHints().tcpNoDelay());
    sub_i = nh.subscribe("vibration_ideal", 20000, &Stream::on_chunk, &ideal, ros::TransportHints().tcpNoDelay());
    sub_h = nh.subscribe<BearingHealth>("health", 1000, [this](const BearingHealth::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      health.push_back(*m);
      if (health.size() > 2000) health.pop_front();
    });
    sub_d = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          for (const auto& s : m->status)
            if (s.name.find("bearing_sim_node: Health") != std::string::npos) diagnostics["Health"] = s;
        });
  }
  // The first health message stamped at or after t (simulated seconds) with an analysis.
  bool wait_health_after(double t, BearingHealth* out, double timeout_s) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
    while (ros::ok() && ros::WallTime::now() < end) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        for (const auto& h : health)
          if (h.header.stamp.toSec() >= t && h.window_s > 0.0) {
            *out = h;
            return true;
          }
      }
      ros::WallDuration(0.01).sleep();
    }
    return false;
  }
  bool health_diagnostic(diagnostic_msgs::DiagnosticStatus* out) {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = diagnostics.find("Health");
    if (it == diagnostics.end()) return false;
    *out = it->second;
    return true;
  }
  // Simulated time of the latest ideal sample received.
  double sim_time() { return static_cast<double>(ideal.next()) / 10000.0; }
};

Fixture& fx() {
  static Fixture f;
  return f;
}

bool wait_until(const std::function<bool()>& pred, double timeout_s) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < end) {
    if (pred()) return true;
    ros::WallDuration(0.005).sleep();
  }
  return pred();
}

double rms_about_mean(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m += v;
  m /= static_cast<double>(x.size());
  double s = 0.0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size()));
}

const BearingHealth::_faults_type::value_type* line(const BearingHealth& h, const std::string& label) {
  for (const auto& l : h.faults)
    if (l.label == label) return &l;
  return nullptr;
}

bool inject(const std::string& surface, double position_rad, int ball, double width_m, double depth_m,
            bearing_sim::InjectDefect* srv) {
  srv->request.surface = surface;
  srv->request.position_rad = position_rad;
  srv->request.ball = ball;
  srv->request.width_m = width_m;
  srv->request.depth_m = depth_m;
  return bearing_sim::test::call_until_answered("inject_defect", *srv);
}

constexpr double kWindowS = 2.0;  // ~health_window_s of ct_gantry.launch

}  // namespace

TEST(NodeHealth, VibrationCarriesTheSensorAndTheIdealStaysAvailable) {
  Fixture& f = fx();
  ASSERT_TRUE(wait_until([&] { return f.vibration.chunks() > 10 && f.ideal.chunks() > 10; }, 30.0));
  // Sensor file: 1.5 ug/sqrt(Hz), 10 kHz out, 8th-order Butterworth at 0.4 x 10 kHz. White
  // noise through it: RMS = D sqrt(B), B = the filter's noise bandwidth, ~4.0 kHz (the
  // Butterworth's is fc (pi / 2n) / sin(pi / 2n) = 1.0064 fc for n = 8).
  const double density = 1.5e-6 * bearing_sim::kStandardGravity_m_s2;
  const double bandwidth = 4000.0 * (M_PI / 16.0) / std::sin(M_PI / 16.0);
  const double noise_rms = density * std::sqrt(bandwidth);  // 9.3e-4 m/s^2
  f.vibration.start_capture(20000);
  f.ideal.start_capture(20000);
  ASSERT_TRUE(wait_until([&] { return f.vibration.captured() && f.ideal.captured(); }, 30.0));
  const double sensor_rms = rms_about_mean(f.vibration.capture());
  const double ideal_rms = rms_about_mean(f.ideal.capture());
  std::printf("[ measured ] sensor RMS %.4g m/s^2 (noise floor %.4g), ideal RMS %.4g m/s^2\n", sensor_rms, noise_rms,
              ideal_rms);
  EXPECT_NEAR(sensor_rms, noise_rms, 0.2 * noise_rms);
  EXPECT_LT(ideal_rms, 0.2 * noise_rms);  // the smooth CT bearing is below this sensor's floor
  EXPECT_DOUBLE_EQ(f.vibration.sample_rate(), 10000.0);
  EXPECT_DOUBLE_EQ(f.ideal.sample_rate(), 10000.0);
  EXPECT_TRUE(f.vibration.tilt_fields_ok());
  EXPECT_TRUE(f.ideal.tilt_fields_ok());

  BearingHealth h;
  ASSERT_TRUE(f.wait_health_after(kWindowS, &h, 30.0));
  EXPECT_EQ(h.level, BearingHealth::OK) << h.reason;
  EXPECT_TRUE(h.defects.empty());
  EXPECT_NEAR(h.accel_rms, noise_rms, 0.2 * noise_rms);
  EXPECT_EQ(h.signal.rfind("sensor: ", 0), 0u) << h.signal;
  // Life: ISO 281 with P = Fr (no axial load; the moment is not part of P) and the core's C
  // (its closed form is checked in test_bearing_life: 117.5 kN, ~5160 Mrev), Miner advancing.
  const double p_N = std::hypot(ct_load()[0], ct_load()[1]);
  const double l10_mrev = std::pow(bearing_sim::basic_dynamic_load_rating_N(ct_model().config()) / p_N, 3.0);
  EXPECT_NEAR(h.l10_million_rev, l10_mrev, 1e-6 * l10_mrev);
  EXPECT_NEAR(h.l10_hours, h.l10_million_rev * 1e6 / 180.0 / 60.0, 1e-6 * h.l10_hours);
  EXPECT_GT(h.miner_damage, 0.0);
  // Miner's sum runs on the reference life (the moment included), the life reported.
  EXPECT_NEAR(h.miner_damage, h.revolutions / (h.reference_life_million_rev * 1e6), 1e-3 * h.miner_damage);
  EXPECT_NEAR(h.reference_life_million_rev, 1063.0, 10.0);
}

TEST(NodeHealth, InjectedInnerRaceSpallIsDiagnosedAndClearingReturnsToOk) {
  Fixture& f = fx();
  ASSERT_TRUE(wait_until([&] { return f.ideal.chunks() > 10; }, 30.0));
  // CT: the inner ring is fixed and the load zone is fixed in the bearing frame, so a spall on
  // the inner race in the load zone is struck by every loaded ball: an impact train at BPFI
  // without modulation (an outer-race spall would cross the load zone once per 3 s turn).
  // Load zone: the azimuth of the most loaded ball at the static equilibrium.
  const bearing_sim::BearingModel model = ct_model();
  const bearing_sim::StaticSolution st = bearing_sim::solve_static(model, ct_load());
  double max_load = 0.0, zone_rad = 0.0;
  for (const auto& b : st.balls)
    if (b.load_N > max_load) max_load = b.load_N, zone_rad = b.azimuth_rad;
  const double bpfi = bearing_sim::bearing_frequencies(model, kCtSpeed).ball_pass_inner_race_hz;  // 313.2 Hz

  bearing_sim::InjectDefect srv;
  ASSERT_TRUE(inject("inner_race", zone_rad, 0, 1.0e-3, 10.0e-6, &srv));
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  EXPECT_EQ(srv.response.defects_present, 1u);
  const double injected_at = f.sim_time();

  BearingHealth h;
  // Two windows: the test's view of simulated time may trail the node's by a little.
  ASSERT_TRUE(f.wait_health_after(injected_at + 2.0 * kWindowS + 0.5, &h, 30.0));
  const auto* l = line(h, "BPFI");
  ASSERT_NE(l, nullptr);
  std::printf(
      "[ measured ] spall: level %d, BPFI expected %.3f Hz, peak %.3f Hz, %.1f dB; RMS %.3g, kurtosis %.2f\n"
      "             %s\n",
      h.level, bpfi, l->peak_hz, l->snr_db, h.accel_rms, h.kurtosis, h.reason.c_str());
  EXPECT_GE(h.level, BearingHealth::WARN);
  EXPECT_NE(h.reason.find("inner race defect suspected"), std::string::npos) << h.reason;
  EXPECT_NEAR(l->expected_hz, bpfi, 1e-9 * bpfi);
  EXPECT_NEAR(l->peak_hz, bpfi, 0.01 * bpfi);
  EXPECT_GE(l->snr_db, 10.0);
  EXPECT_TRUE(l->suspected);
  // The evidence beside it: BPFI of the CT bearing (~308 Hz) is resolvable in the window.
  EXPECT_TRUE(l->resolvable);
  EXPECT_TRUE(!l->impulsiveness_required || l->impulsive);
  EXPECT_TRUE(std::isfinite(l->band_kurtosis));
  ASSERT_EQ(h.defects.size(), 1u);
  EXPECT_EQ(h.defects[0].surface, "inner_race");
  EXPECT_NEAR(h.defects[0].position_rad, zone_rad, 1e-12);
  EXPECT_NEAR(h.defects[0].width_m, 1.0e-3, 1e-12);
  EXPECT_NEAR(h.defects[0].depth_m, 10.0e-6, 1e-15);
  EXPECT_EQ(h.defects[0].ball, -1);

  // The same on /diagnostics (published once per wall second).
  ros::WallDuration(1.5).sleep();
  diagnostic_msgs::DiagnosticStatus d;
  ASSERT_TRUE(f.health_diagnostic(&d));
  EXPECT_GE(d.level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NE(d.message.find("inner race defect suspected: envelope peak at"), std::string::npos) << d.message;

  std_srvs::Trigger clear;
  ASSERT_TRUE(bearing_sim::test::call_until_answered("clear_defects", clear));
  EXPECT_TRUE(clear.response.success);
  const double cleared_at = f.sim_time();
  // Within two windows the analysed signal no longer contains the spall.
  ASSERT_TRUE(f.wait_health_after(cleared_at + 2.0 * kWindowS + 0.5, &h, 30.0));
  std::printf("[ measured ] cleared: level %d, BPFI %.1f dB: %s\n", h.level,
              line(h, "BPFI") ? line(h, "BPFI")->snr_db : 0.0, h.reason.c_str());
  EXPECT_EQ(h.level, BearingHealth::OK) << h.reason;
  EXPECT_TRUE(h.defects.empty());
  EXPECT_EQ(f.vibration.gaps_or_repeats(), 0u);
  EXPECT_EQ(f.ideal.gaps_or_repeats(), 0u);
  EXPECT_EQ(f.vibration.non_finite(), 0u);
  EXPECT_EQ(f.ideal.non_finite(), 0u);
}

TEST(NodeHealth, DefectsThatDoNotFitAreRefusedWithTheReason) {
  Fixture& f = fx();
  ASSERT_TRUE(wait_until([&] { return f.ideal.chunks() > 10; }, 30.0));
  const double d = ct_model().config().ball_diameter_m;  // 12 mm: depth at most 3 mm
  struct Case {
    std::string surface;
    int ball;
    double width_m, depth_m;
    std::string expected;  // in the message
  };
  const Case cases[] = {
      {"inner_race", 0, 1e-3, 0.26 * d, "depth must be > 0 and at most a quarter of the ball diameter"},
      {"cup", 0, 1e-3, 10e-6, "surface must be outer_race, inner_race or ball, got 'cup'"},
      {"ball", 414, 1e-3, 10e-6, "ball index 414 is not in [0, 414)"},
      {"outer_race", 0, 2.0, 10e-6, "a race spall must be wider than 0 and at most a quarter of the raceway"},
  };
  for (const Case& c : cases) {
    bearing_sim::InjectDefect srv;
    ASSERT_TRUE(inject(c.surface, 0.0, c.ball, c.width_m, c.depth_m, &srv));
    EXPECT_FALSE(srv.response.success) << c.surface;
    EXPECT_NE(srv.response.message.find(c.expected), std::string::npos) << srv.response.message;
    EXPECT_NE(srv.response.message.find("does not fit the bearing"), std::string::npos) << srv.response.message;
    EXPECT_EQ(srv.response.defects_present, 0u);
  }
  // The node keeps publishing.
  const std::uint64_t before = f.vibration.next();
  EXPECT_TRUE(wait_until([&] { return f.vibration.next() > before + 10000; }, 20.0));
  BearingHealth h;
  ASSERT_TRUE(f.wait_health_after(f.sim_time(), &h, 30.0));
  EXPECT_TRUE(h.defects.empty());
}

NODE_TEST_MAIN("test_node_health")
