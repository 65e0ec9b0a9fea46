// bearing_sim_node's inputs: a 2x load step, a speed change and a speed ramp from rest,
// bad inputs, and dynamic_reconfigure, each checked against the core library.
#include <cmath>
#include <limits>

#include <dynamic_reconfigure/Reconfigure.h>
#include <std_srvs/Trigger.h>

#include "bearing_sim/InjectDefect.h"
#include "bearing_sim/InputRejection.h"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "node_test_support.hpp"
#include "service_calls.hpp"

using namespace node_test;

namespace {
constexpr double kRate = 10000.0;

struct Inputs {
  ros::Publisher load, speed, ring_temperature;
};
Inputs& inputs() {
  static ros::NodeHandle nh;
  static Inputs in{nh.advertise<geometry_msgs::WrenchStamped>("load", 10, true),
                   nh.advertise<std_msgs::Float64>("speed", 10, true),
                   nh.advertise<std_msgs::Float64>("ring_temperature_difference_K", 10, true)};
  return in;
}

// Publishes and returns the index of a sample the node had certainly not computed yet
// when the message left (the latest received plus the 10 ms real-time lead of a chunk,
// with margin): the input applies from a sample at or before that index + 0.1 s.
std::uint64_t send_load(const Vector5& l) {
  const std::uint64_t before = recorder().next_index();
  inputs().load.publish(wrench(l));
  return before;
}
std::uint64_t send_speed(double w) {
  const std::uint64_t before = recorder().next_index();
  inputs().speed.publish(speed(w));
  return before;
}

void expect_mean_at_static(const Vector5& load, std::uint64_t from, std::uint64_t to, const std::string& what,
                           const bearing_sim::BearingModel& model) {
  const bearing_sim::StaticSolution s = bearing_sim::solve_static(model, load);
  const double scale = s.displacement.head<3>().norm();
  // 0.5 %: see test_node_steady_state (vibration < 1e-10 m, damped transients gone in ~10 ms).
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(recorder().mean_displacement(c, from, to), s.displacement[c], 0.005 * scale) << what << ", axis " << c;
}

bool reconfigure(const std::string& name, double value, bool is_int = false,
                 dynamic_reconfigure::Config* applied = nullptr) {
  dynamic_reconfigure::Reconfigure srv;
  if (is_int) {
    dynamic_reconfigure::IntParameter p;
    p.name = name;
    p.value = static_cast<int>(value);
    srv.request.config.ints.push_back(p);
  } else {
    dynamic_reconfigure::DoubleParameter p;
    p.name = name;
    p.value = value;
    srv.request.config.doubles.push_back(p);
  }
  const bool ok = bearing_sim::test::call_until_answered("bearing_sim_node/set_parameters", srv);
  if (applied) *applied = srv.response.config;
  return ok;
}

std_msgs::Float64 kelvin(double dT) {
  std_msgs::Float64 m;
  m.data = dT;
  return m;
}

double applied_value(const dynamic_reconfigure::Config& c, const std::string& name) {
  for (const auto& p : c.doubles)
    if (p.name == name) return p.value;
  for (const auto& p : c.ints)
    if (p.name == name) return p.value;
  return std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

class NodeInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    inputs();
    ASSERT_TRUE(recorder().wait_for_sample(0, 20.0)) << "no vibration samples";
  }
  void TearDown() override {
    // Whatever happened, the stream stayed whole and finite.
    EXPECT_EQ(recorder().gaps(), 0u);
    EXPECT_EQ(recorder().repeats(), 0u);
    EXPECT_EQ(recorder().non_finite(), 0u);
  }
  // Waits for `seconds` of simulated time after sample `from`.
  void settle(std::uint64_t from, double seconds) {
    ASSERT_TRUE(recorder().wait_for_sample(from + static_cast<std::uint64_t>(seconds * kRate), 10.0 + 2 * seconds));
  }
  // The "Inputs" diagnostic from a message composed after `new_messages` more arrive, and the
  // node's count of rejected inputs in it.
  static int inputs_diagnostic(int new_messages, diagnostic_msgs::DiagnosticStatus* in) {
    EXPECT_TRUE(recorder().wait_for_new_diagnostics(new_messages, 5.0));
    EXPECT_TRUE(recorder().diagnostic("Inputs", in));
    return std::stoi(Recorder::value(*in, "rejected inputs"));
  }
};

TEST_F(NodeInputs, LoadStepOf2xReachesTheNewEquilibrium) {
  const bearing_sim::BearingModel model = ct_model();
  const Vector5 doubled = 2.0 * ct_load();
  const std::uint64_t sent = send_load(doubled);
  settle(sent, 1.0);
  // The old and new equilibria differ by about 45 %: far beyond the 0.5 % tolerance.
  expect_mean_at_static(doubled, sent + 5000, sent + 10000, "after the 2x load step", model);
  // No blow-up on the way: every sample within 2x the largest static displacement.
  const double x_new = bearing_sim::solve_static(model, doubled).displacement[0];
  EXPECT_LT(recorder().max_abs_deviation(0, 0.0, sent, sent + 10000), 2.0 * x_new);
  send_load(ct_load());
}

TEST_F(NodeInputs, SpeedChangeMovesTheVaryingCompliancePeak) {
  const bearing_sim::BearingModel model = ct_model();
  const double old_speed = kCtSpeed, new_speed = 120.0 * 2.0 * M_PI / 60.0;                       // 180 -> 120 rpm
  const double f_old = bearing_sim::bearing_frequencies(model, old_speed).varying_compliance_hz;  // 313 Hz
  const double f_new = bearing_sim::bearing_frequencies(model, new_speed).varying_compliance_hz;  // 209 Hz
  send_speed(old_speed);
  const std::uint64_t start = recorder().next_index();
  settle(start, 0.7);
  const std::uint64_t sent = send_speed(new_speed);
  settle(sent, 0.9);
  // 0.5 s windows, before the change and 0.3 s after it (the change applies within 0.1 s).
  const auto before = recorder().accel_x(sent - 5000, sent);
  const auto after = recorder().accel_x(sent + 3000, sent + 8000);
  // Offline the line at the ball-pass frequency stands 1e3..1e4 above the other one and
  // above the spectral floor; 100x is a clear peak with margin.
  EXPECT_GT(spectral_amplitude(before, f_old, kRate), 100.0 * spectral_amplitude(before, f_new, kRate));
  EXPECT_GT(spectral_amplitude(after, f_new, kRate), 100.0 * spectral_amplitude(after, f_old, kRate));
  EXPECT_GT(spectral_amplitude(after, f_new, kRate), 100.0 * spectral_amplitude(after, 0.5 * (f_old + f_new), kRate));
  send_speed(kCtSpeed);
}

TEST_F(NodeInputs, SpeedRampFromRestTo180RpmStaysAtTheEquilibrium) {
  const bearing_sim::BearingModel model = ct_model();
  send_speed(0.0);
  settle(recorder().next_index(), 0.3);
  const std::uint64_t ramp_start = recorder().next_index();
  // 0 -> 180 rpm in 1 s of 50 Hz steps.
  for (int i = 0; i <= 50; ++i) {
    inputs().speed.publish(speed(kCtSpeed * i / 50.0));
    ros::WallDuration(0.02).sleep();
  }
  settle(recorder().next_index(), 0.5);
  const std::uint64_t end = recorder().next_index();
  const double x_static = bearing_sim::solve_static(model, ct_load()).displacement[0];
  // Offline the ramp moves x by 1e-11 m (ball passing); 1 % of x (66 nm) means "no blow-up".
  EXPECT_LT(recorder().max_abs_deviation(0, x_static, ramp_start, end), 0.01 * x_static);
  diagnostic_msgs::DiagnosticStatus model_status;
  ASSERT_TRUE(recorder().diagnostic("Model", &model_status));
  EXPECT_EQ(Recorder::value(model_status, "divergences"), "0");
  EXPECT_LT(recorder().worst_level("Model"), diagnostic_msgs::DiagnosticStatus::ERROR);
  // The speed reached is in the diagnostics.
  diagnostic_msgs::DiagnosticStatus in;
  // Two diagnostics messages, so one was composed after the last speed message.
  ASSERT_TRUE(recorder().wait_for_new_diagnostics(2, 5.0));
  ASSERT_TRUE(recorder().diagnostic("Inputs", &in));
  EXPECT_NEAR(std::stod(Recorder::value(in, "ring speed (rad/s)")), kCtSpeed, 1e-3);
}

TEST_F(NodeInputs, BadInputsAreRejectedAndTheNodeKeepsItsLastGoodInputs) {
  const bearing_sim::BearingModel model = ct_model();
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  diagnostic_msgs::DiagnosticStatus in;
  const int rejected_before = inputs_diagnostic(1, &in);
  // Each refusal is also published on rejected_inputs (the scenario player stops on one).
  std::mutex refused_mutex;
  std::vector<bearing_sim::InputRejection> refused;
  ros::NodeHandle nh;
  ros::Subscriber refused_sub = nh.subscribe<bearing_sim::InputRejection>(
      "rejected_inputs", 100, [&](const bearing_sim::InputRejection::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(refused_mutex);
        refused.push_back(*m);
      });
  ASSERT_TRUE(recorder().wait_for([&] { return refused_sub.getNumPublishers() > 0; }, 60.0));
  Vector5 bad = ct_load();
  bad[0] = nan;
  send_load(bad);
  bad = ct_load();
  bad[4] = inf;
  send_load(bad);
  bad = ct_load();
  bad[2] = 2.0e5;  // max_force_N = 1e5 in ct_gantry.launch
  send_load(bad);
  bad = ct_load();
  bad[3] = 6.0e4;  // max_moment_Nm = 5e4
  send_load(bad);
  const std::uint64_t sent = send_speed(inf);
  ros::WallDuration(0.05).sleep();
  inputs().speed.publish(speed(200.0));  // max_speed_rad_s = 100
  settle(sent, 1.0);
  // Still publishing, at the equilibrium of the last good load.
  expect_mean_at_static(ct_load(), sent, sent + 10000, "after bad inputs", model);
  EXPECT_EQ(inputs_diagnostic(2, &in) - rejected_before, 6);  // composed after the inputs
  EXPECT_EQ(in.level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_NEAR(std::stod(Recorder::value(in, "ring speed (rad/s)")), kCtSpeed, 1e-3);
  ASSERT_TRUE(recorder().wait_for(
      [&] {
        std::lock_guard<std::mutex> lock(refused_mutex);
        return refused.size() >= 6;
      },
      60.0));
  std::lock_guard<std::mutex> lock(refused_mutex);
  ASSERT_EQ(refused.size(), 6u);
  int loads = 0, speeds = 0, over_force = 0;
  for (const bearing_sim::InputRejection& r : refused) {
    if (r.input == "load") {
      ++loads;
      EXPECT_FALSE(r.input_stamp.isZero()) << r.reason;  // the refused message's stamp
      // |(6800, 0, 2e5)| N
      if (r.reason == "force 200116 N exceeds max_force_N = 100000") ++over_force;
    } else {
      EXPECT_EQ(r.input, "speed") << r.reason;
      EXPECT_TRUE(r.input_stamp.isZero());
      ++speeds;
    }
  }
  EXPECT_EQ(loads, 4);
  EXPECT_EQ(speeds, 2);
  EXPECT_EQ(over_force, 1);
}

TEST_F(NodeInputs, ReconfigureClearanceAndChunkSizeLive) {
  bearing_sim::BearingModel model = ct_model();
  auto config = model.config();
  config.clearance_m = 20e-6;
  const bearing_sim::BearingModel loose(config);
  ASSERT_TRUE(reconfigure("clearance_um", 20.0));
  ASSERT_TRUE(reconfigure("chunk_samples", 50, true));
  const std::uint64_t sent = recorder().next_index();
  settle(sent, 1.0);
  // 20 um clearance moves the equilibrium by about 20 um, so the 0.5 % check tells them apart.
  expect_mean_at_static(ct_load(), sent + 5000, sent + 10000, "clearance 20 um", loose);
  const auto chunks = recorder().chunks();
  ASSERT_GT(chunks.size(), 10u);
  EXPECT_EQ(chunks.back().size, 50u);
  EXPECT_EQ(chunks[chunks.size() - 2].size, 50u);
  ASSERT_TRUE(reconfigure("clearance_um", 0.0));
  ASSERT_TRUE(reconfigure("chunk_samples", 100, true));
  settle(recorder().next_index(), 0.5);
  EXPECT_EQ(recorder().chunks().back().size, 100u);
}

TEST_F(NodeInputs, BadReconfigureValuesAndDefectGrowthsAreRefused) {
  const bearing_sim::BearingModel model = ct_model();
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  diagnostic_msgs::DiagnosticStatus in;
  const int rejected_before = inputs_diagnostic(1, &in);
  const std::uint64_t sent = recorder().next_index();
  // The good values of ct_gantry.launch / the cfg defaults that must come back.
  dynamic_reconfigure::Config before;
  ASSERT_TRUE(reconfigure("level_rate_hz", 10.0, false, &before));
  int refused = 0;
  for (const char* name :
       {"clearance_um", "contact_damping_Ns_per_m", "level_window_s", "level_rate_hz", "ball_loads_rate_hz"}) {
    // NaN passes the server's clamp and must be refused by the node (reverted).
    dynamic_reconfigure::Config applied;
    ASSERT_TRUE(reconfigure(name, nan, false, &applied)) << name;
    EXPECT_EQ(applied_value(applied, name), applied_value(before, name)) << name << " = nan not reverted";
    ++refused;
    // +-inf the server clamps to the cfg range before the node sees it: finite, in range.
    for (double v : {inf, -inf}) {
      ASSERT_TRUE(reconfigure(name, v, false, &applied)) << name;
      EXPECT_TRUE(std::isfinite(applied_value(applied, name))) << name << " = " << v;
    }
    ASSERT_TRUE(reconfigure(name, applied_value(before, name)));  // back to the good value
  }
  // After the NaN clearance, a good one is still applied (the node recovered).
  ASSERT_TRUE(reconfigure("clearance_um", 0.0));
  // Defects: non-finite and absurd growth rates (1 m/s passes any spall the bearing holds in ms).
  for (double w : {nan, inf, 1.0}) {
    for (int which = 0; which < 2; ++which) {
      bearing_sim::InjectDefect srv;
      srv.request.surface = "outer_race";
      srv.request.width_m = 1e-3;
      srv.request.depth_m = 10e-6;
      (which == 0 ? srv.request.width_growth_m_per_s : srv.request.depth_growth_m_per_s) = w;
      ASSERT_TRUE(bearing_sim::test::call_until_answered("inject_defect", srv));
      EXPECT_FALSE(srv.response.success) << "growth " << w;
      EXPECT_NE(srv.response.message.find("growth"), std::string::npos) << srv.response.message;
      EXPECT_EQ(srv.response.defects_present, 0u);
    }
  }
  settle(sent, 1.5);
  const std::uint64_t after = recorder().next_index();
  settle(after, 1.0);
  expect_mean_at_static(ct_load(), after, after + 10000, "after bad reconfigure values", model);
  EXPECT_GE(inputs_diagnostic(2, &in) - rejected_before, refused);
  // The last one refused names the parameter and the accepted range.
  const std::string last = Recorder::value(in, "last rejection");
  EXPECT_NE(last.find("ball_loads_rate_hz"), std::string::npos) << last;
  EXPECT_NE(last.find("[0.1, 200]"), std::string::npos) << last;
}

// The rotor (outer ring) 4 K warmer than the inner ring opens the CT bearing's clearance by
// alpha 4 K (dm/2) cos a0 = 20.9 um: the equilibrium moves as a cold bearing with that
// clearance, which the 0.5 % check tells apart from the start (as clearance_um 20 does above).
// NaN, inf and an interference beyond the model are refused, naming the input, and the last
// good value stays.
TEST_F(NodeInputs, RingTemperatureDifferenceReachesTheModelAndBadValuesAreRefused) {
  bearing_sim::BearingModel model = ct_model();
  auto config = model.config();
  config.ring_temperature_difference_K = -4.0;
  const bearing_sim::BearingModel warm_rotor(config);
  ASSERT_NEAR(warm_rotor.clearance_m(), 20.9e-6, 0.1e-6);
  diagnostic_msgs::DiagnosticStatus in;
  const int rejected_before = inputs_diagnostic(1, &in);
  const std::uint64_t sent = recorder().next_index();
  inputs().ring_temperature.publish(kelvin(-4.0));
  settle(sent, 1.0);
  expect_mean_at_static(ct_load(), sent + 5000, sent + 10000, "outer ring 4 K warmer", warm_rotor);

  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 120.0}) {
    inputs().ring_temperature.publish(kelvin(bad));
    ros::WallDuration(0.05).sleep();
  }
  const std::uint64_t after = recorder().next_index();
  settle(after, 1.0);
  expect_mean_at_static(ct_load(), after, after + 10000, "after bad temperature differences", warm_rotor);
  EXPECT_EQ(inputs_diagnostic(2, &in) - rejected_before, 3);
  const std::string last = Recorder::value(in, "last rejection");
  EXPECT_NE(last.find("ring_temperature_difference_K"), std::string::npos) << last;
  EXPECT_NE(last.find("interference"), std::string::npos) << last;

  inputs().ring_temperature.publish(kelvin(0.0));  // back to equal ring temperatures
  const std::uint64_t back = recorder().next_index();
  settle(back, 1.0);
  expect_mean_at_static(ct_load(), back + 5000, back + 10000, "equal ring temperatures again", model);
}

// inject_defect refuses, naming the limit, a place no double holds (1e300 rad), a spall below
// a micrometre (1e-300 m was accepted as "0.00 mm wide" and counted), and the spall after the
// 64 a bearing may hold at once (10,000 calls put the node 15 s behind real time).
TEST_F(NodeInputs, InjectDefectRefusesAbsurdSpallsAndOneBeyondTheCap) {
  bearing_sim::test::PersistentService<bearing_sim::InjectDefect> service("inject_defect");
  const auto inject = [&service](double position_rad, double width_m, double depth_m) {
    bearing_sim::InjectDefect srv;
    srv.request.surface = "outer_race";
    srv.request.position_rad = position_rad;
    srv.request.width_m = width_m;
    srv.request.depth_m = depth_m;
    EXPECT_TRUE(service.call(srv));
    return srv.response;
  };
  auto r = inject(1e300, 1e-3, 10e-6);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("position 1e+300 rad is beyond +-1e+06 rad"), std::string::npos) << r.message;
  r = inject(0.0, 1e-300, 10e-6);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("at least 1 um wide and deep"), std::string::npos) << r.message;
  EXPECT_EQ(r.defects_present, 0u);
  // 64 small spalls (0.1 mm x 1 um: barely felt by the CT bearing's balls), then one more.
  for (unsigned i = 1; i <= static_cast<unsigned>(bearing_sim::kMaxSpalls); ++i) {
    r = inject(0.09 * i, 0.1e-3, 1e-6);
    ASSERT_TRUE(r.success) << i << ": " << r.message;
    EXPECT_EQ(r.defects_present, i);
  }
  EXPECT_NE(r.message.find("0.1 mm wide, 1 um deep"), std::string::npos) << r.message;
  r = inject(0.0, 1e-3, 10e-6);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("64 spalls are present, at most 64"), std::string::npos) << r.message;
  EXPECT_EQ(r.defects_present, 64u);
  std_srvs::Trigger clear;
  ASSERT_TRUE(bearing_sim::test::call_until_answered("clear_defects", clear));
  EXPECT_NE(clear.response.message.find("cleared 64 defect(s)"), std::string::npos) << clear.response.message;
  // The node ran on: a healthy bearing at the static equilibrium again.
  const std::uint64_t after = recorder().next_index();
  settle(after, 1.0);
  expect_mean_at_static(ct_load(), after + 5000, after + 10000, "after 64 spalls cleared", ct_model());
}

// DivergenceIsReportedAsErrorAndResetNeverNaN: test_node_divergence.cpp (a light ring with a
// fixed step; the cfg's damping is capped at a physical value that no longer diverges here).

NODE_TEST_MAIN("test_node_inputs")
