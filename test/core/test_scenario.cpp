// Scenario time lines (docs/scenarios.md): speed, ring angle, load with unbalance, phases
// and defects against hand values and closed forms; every kind of bad file is a
// ConfigError naming the file and the key; the shipped scenarios load.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
const char* kScenarioSource = "/tmp/unit_test_scenario.yaml";
constexpr double kRpm = 2.0 * kPi / 60.0;

// Header of a valid scenario on the CT bearing (absolute path), 25 s long.
std::string header(const std::string& extra_top = "") {
  return "name: unit\nduration_s: 25\nseed: 42\nbearing_file: " + bearing_file("ct_gantry_lyc.yaml") + "\n" + extra_top;
}

// Speed: 30 rpm held to 1 s, ramp to 120 rpm at 11 s, step to 150 rpm held to 15 s (held on
// to 16 s through the gap), coast with tau = 2 s to 20 s, linear ramp to rest at 22 s.
const std::string kSpeed =
    "speed:\n"
    "  initial_speed_rpm: 30\n"
    "  segments:\n"
    "    - {type: ramp, start_s: 1, end_s: 11, to_speed_rpm: 120}\n"
    "    - {type: hold, start_s: 11, end_s: 15, speed_rpm: 150}\n"
    "    - {type: coast, start_s: 16, end_s: 20, time_constant_s: 2}\n"
    "    - {type: ramp, start_s: 20, end_s: 22, to_speed_rad_s: 0}\n";

Scenario speed_scenario(const std::string& extra = "") {
  return Scenario::from_string(header() + kSpeed + extra, kScenarioSource);
}

// The hand-written piecewise speed of kSpeed, rad/s, and its integral in closed form.
double hand_speed(double t) {
  const double w0 = 30 * kRpm, w1 = 120 * kRpm, w2 = 150 * kRpm, w3 = w2 * std::exp(-2.0);
  if (t < 1) return w0;
  if (t < 11) return w0 + (w1 - w0) * (t - 1) / 10;
  if (t < 16) return w2;
  if (t < 20) return w2 * std::exp(-(t - 16) / 2);
  if (t < 22) return w3 * (1 - (t - 20) / 2);
  return 0.0;
}
double hand_angle(double t) {
  const double w0 = 30 * kRpm, w1 = 120 * kRpm, w2 = 150 * kRpm, w3 = w2 * std::exp(-2.0);
  const double a1 = w0 * 1, a11 = a1 + 0.5 * (w0 + w1) * 10, a16 = a11 + w2 * 5,
               a20 = a16 + w2 * 2 * (1 - std::exp(-2.0));
  const double a22 = a20 + 0.5 * w3 * 2;
  if (t < 1) return w0 * t;
  if (t < 11) return a1 + w0 * (t - 1) + 0.5 * (w1 - w0) / 10 * (t - 1) * (t - 1);
  if (t < 16) return a11 + w2 * (t - 11);
  if (t < 20) return a16 + w2 * 2 * (1 - std::exp(-(t - 16) / 2));
  if (t < 22) return a20 + w3 * (t - 20) - 0.5 * w3 / 2 * (t - 20) * (t - 20);
  return a22;
}

void expect_scenario_error(const std::string& yaml, const std::string& key, const std::string& what = "") {
  try {
    Scenario::from_string(yaml, kScenarioSource);
    ADD_FAILURE() << "no error for key " << key;
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(kScenarioSource), std::string::npos) << msg;
    EXPECT_NE(msg.find("'" + key + "'"), std::string::npos) << "expected key '" << key << "' in: " << msg;
    if (!what.empty()) {
      EXPECT_NE(msg.find(what), std::string::npos) << "expected '" << what << "' in: " << msg;
    }
  }
}
}  // namespace

TEST(Scenario, SpeedAtSegmentBoundariesAndInsidePieces) {
  const Scenario sc = speed_scenario();
  // Relative 1e-12: the same formulas evaluated in another order.
  for (double t : {0.0,  0.5,  1.0,  3.7,   6.0,  10.999, 11.0, 13.0, 15.0, 15.5,
                   16.0, 17.3, 18.0, 19.99, 20.0, 21.0,   22.0, 24.0, 25.0, 40.0}) {
    EXPECT_NEAR(sc.ring_speed_at(t), hand_speed(t), 1e-12 * 20.0) << "t = " << t;
    EXPECT_NEAR(sc.inputs_at(t).ring_speed_rad_s, hand_speed(t), 1e-12 * 20.0) << "t = " << t;
  }
  // Values a gantry engineer would check by eye.
  EXPECT_NEAR(sc.ring_speed_at(6.0), 75 * kRpm, 1e-12);                    // half-way up the ramp
  EXPECT_NEAR(sc.ring_speed_at(11.0), 150 * kRpm, 1e-12);                  // the step of the hold
  EXPECT_NEAR(sc.ring_speed_at(18.0), 150 * kRpm / std::exp(1.0), 1e-12);  // one time constant
  EXPECT_EQ(sc.ring_speed_at(22.0), 0.0);
  EXPECT_THROW(sc.inputs_at(-0.1), InvalidInputError);
  EXPECT_THROW(sc.inputs_at(std::nan("")), InvalidInputError);
}

TEST(Scenario, RingAngleIsTheIntegralOfTheSpeed) {
  const Scenario sc = speed_scenario();
  for (double t : {0.0, 0.7, 1.0, 5.5, 11.0, 14.0, 16.0, 17.9, 20.0, 21.3, 22.0, 25.0})
    EXPECT_NEAR(sc.ring_angle_at(t), hand_angle(t), 1e-11 * hand_angle(25.0)) << "t = " << t;
  // Independent check: composite Simpson quadrature of ring_speed_at over each smooth
  // piece (error ~ h^4 w'''' : far below 1e-9 rad with 2000 intervals per piece).
  const double knots[] = {0, 1, 11, 15, 16, 20, 22, 25};
  double angle = 0.0;
  for (int k = 0; k + 1 < 8; ++k) {
    const double a = knots[k], b = knots[k + 1];
    const int n = 2000;
    const double h = (b - a) / n;
    // The speed is discontinuous at 11 s (a step): stay inside the piece at its ends.
    auto w = [&](double t) { return sc.ring_speed_at(std::min(std::max(t, a + 1e-15 * b), b - 1e-12)); };
    double sum = w(a) + w(b);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * w(a + i * h);
    angle += sum * h / 3.0;
    EXPECT_NEAR(sc.ring_angle_at(b), angle, 1e-9) << "angle at " << b << " s";
  }
}

TEST(Scenario, LoadStepsAndRamps) {
  const Scenario sc = Scenario::from_string(header() +
                                                "load:\n"
                                                "  initial: {force_N: [100, 0, -50], moment_Nm: [0, 20]}\n"
                                                "  segments:\n"
                                                "    - {type: step, start_s: 2, force_N: [300, 10, -50]}\n"
                                                "    - {type: ramp, start_s: 4, end_s: 8, moment_Nm: [40, 60]}\n"
                                                "    - {type: ramp, start_s: 8, end_s: 10, force_N: [0, 0, 0]}\n",
                                            kScenarioSource);
  auto expect_load = [&](double t, Vector5 expected) {
    const Vector5 l = sc.inputs_at(t).load;
    for (int i = 0; i < 5; ++i) EXPECT_NEAR(l[i], expected[i], 1e-12) << "t = " << t << " component " << i;
  };
  expect_load(0.0, load5(100, 0, -50, 0, 20));
  expect_load(1.999, load5(100, 0, -50, 0, 20));
  expect_load(2.0, load5(300, 10, -50, 0, 20));
  expect_load(4.0, load5(300, 10, -50, 0, 20));
  expect_load(5.0, load5(300, 10, -50, 10, 30));  // a quarter of the way: moments only
  expect_load(8.0, load5(300, 10, -50, 40, 60));
  expect_load(9.5, load5(75, 2.5, -12.5, 40, 60));
  expect_load(10.0, load5(0, 0, 0, 40, 60));
  expect_load(25.0, load5(0, 0, 0, 40, 60));
}

TEST(Scenario, UnbalanceForceTurnsWithTheRing) {
  const double m = 0.2, e = 0.55, phase_deg = 30.0;
  const Scenario sc = speed_scenario(
      "load:\n  initial: {force_N: [6800, 0, 0], moment_Nm: [0, 2100]}\n"
      "  unbalance: {mass_kg: 0.2, radius_m: 0.55, phase_deg: 30}\n");
  // Holds (no angular acceleration): |F| = m e w^2, along the mass at ring angle + phase.
  for (double t : {0.5, 12.0, 13.37, 15.5}) {
    const ScenarioInputs in = sc.inputs_at(t);
    const double fx = in.load[0] - 6800.0, fy = in.load[1];
    const double w = hand_speed(t);
    EXPECT_NEAR(std::hypot(fx, fy), m * e * w * w, 1e-9) << "t = " << t;
    EXPECT_NEAR(std::remainder(std::atan2(fy, fx) - (hand_angle(t) + phase_deg * kPi / 180.0), 2 * kPi), 0.0, 1e-9)
        << "t = " << t;
    EXPECT_EQ(in.load[2], 0.0);
    EXPECT_EQ(in.load[3], 0.0);
    EXPECT_EQ(in.load[4], 2100.0);
  }
  // Ramp and coast: radial m e w^2 and, against the rotation, m e alpha.
  for (double t : {4.0, 17.0}) {
    const ScenarioInputs in = sc.inputs_at(t);
    const double a = hand_angle(t) + phase_deg * kPi / 180.0;
    const double fx = in.load[0] - 6800.0, fy = in.load[1];
    const double radial = fx * std::cos(a) + fy * std::sin(a);
    const double tangential = -fx * std::sin(a) + fy * std::cos(a);
    const double w = hand_speed(t);
    const double alpha = t < 11 ? 90 * kRpm / 10 : -w / 2.0;
    EXPECT_NEAR(radial, m * e * w * w, 1e-9) << "t = " << t;
    EXPECT_NEAR(tangential, -m * e * alpha, 1e-9) << "t = " << t;
  }
  // At rest, no unbalance force.
  EXPECT_NEAR(sc.inputs_at(23.0).load[0], 6800.0, 1e-12);
  EXPECT_NEAR(sc.inputs_at(23.0).load[1], 0.0, 1e-12);
}

TEST(Scenario, PhasesAndDefectEvents) {
  const Scenario sc = Scenario::from_string(
      header() +
          "phases:\n  - {name: spin-up, start_s: 0}\n  - {name: scan, start_s: 10}\n  - {name: spin-down, start_s: "
          "20}\n"
          "defects:\n"
          "  - {type: spall, at_s: 5, surface: outer_race, position_deg: 90, width_mm: 0.5, depth_um: 10,\n"
          "     width_growth_mm_per_s: 0.1, depth_growth_um_per_hour: 3600}\n"
          "  - {type: spall, at_s: 8, surface: ball, ball: 3, width_mm: 0.3, depth_um: 5}\n"
          "  - {type: clear, at_s: 12}\n"
          "  - {type: spall, at_s: 15, surface: inner_race, width_mm: 1, depth_um: 20}\n",
      kScenarioSource);
  EXPECT_EQ(sc.phase_at(0.0), "spin-up");
  EXPECT_EQ(sc.phase_at(9.99), "spin-up");
  EXPECT_EQ(sc.inputs_at(10.0).phase, "scan");
  EXPECT_EQ(sc.inputs_at(24.0).phase, "spin-down");
  ASSERT_EQ(sc.defect_events().size(), 4u);
  const Spall& s = sc.defect_events()[0].spall;
  EXPECT_EQ(s.surface, Surface::OuterRace);
  EXPECT_NEAR(s.position_rad, kPi / 2, 1e-15);
  EXPECT_EQ(s.created_at_s, 5.0);
  EXPECT_NEAR(s.width_growth_m_per_s, 1e-4, 1e-18);
  EXPECT_NEAR(s.depth_growth_m_per_s, 1e-6, 1e-18);  // 3600 um/h = 1 um/s
  EXPECT_EQ(sc.defect_events()[2].kind, ScenarioDefectEvent::Kind::Clear);
  EXPECT_TRUE(sc.spalls_at(4.99).empty());
  ASSERT_EQ(sc.spalls_at(9.0).size(), 2u);
  EXPECT_EQ(sc.spalls_at(9.0)[1].ball, 3);
  EXPECT_NEAR(Scenario::spall_width_at(sc.spalls_at(9.0)[0], 9.0), 0.5e-3 + 4 * 1e-4, 1e-15);
  EXPECT_NEAR(Scenario::spall_depth_at(sc.spalls_at(9.0)[0], 9.0), 10e-6 + 4 * 1e-6, 1e-15);
  EXPECT_TRUE(sc.spalls_at(12.0).empty());
  ASSERT_EQ(sc.spalls_at(25.0).size(), 1u);
  EXPECT_EQ(sc.spalls_at(25.0)[0].surface, Surface::InnerRace);
}

// `count` outer race spalls at `at_s`, 0.5 mm x 10 um unless given.
std::string spall_events(int count, double at_s, const std::string& size = "width_mm: 0.5, depth_um: 10") {
  std::string events;
  for (int i = 0; i < count; ++i)
    events += "  - {type: spall, at_s: " + std::to_string(at_s) +
              ", surface: outer_race, position_deg: " + std::to_string(i) + ", " + size + "}\n";
  return events;
}

TEST(Scenario, SpallsAreCountedAsTheRunHoldsThemAndRefusedBelowASpall) {
  // 64 at once, cleared, 64 more: the run never holds more than the cap.
  const Scenario sc = Scenario::from_string(header() + "defects:\n" + spall_events(kMaxSpalls, 1.0) +
                                                "  - {type: clear, at_s: 2}\n" + spall_events(kMaxSpalls, 3.0),
                                            kScenarioSource);
  EXPECT_EQ(sc.defect_events().size(), 2u * kMaxSpalls + 1u);
  // One more before the clear: refused naming the event and the cap.
  expect_scenario_error(header() + "defects:\n" + spall_events(kMaxSpalls + 1, 1.0), "defects[64]",
                      "at most 64 may be at once");
  // A 1e-300 m spall (or a position of 1e300 degrees): refused as the service refuses it.
  expect_scenario_error(header() + "defects:\n" + spall_events(1, 1.0, "width_mm: 1e-297, depth_um: 10"), "defects[0]",
                      "at least 1 um wide and deep");
  expect_scenario_error(
      header() + "defects:\n" + "  - {type: spall, at_s: 1, position_deg: 1e300, width_mm: 0.5, depth_um: 10}\n",
      "defects[0]", "beyond +-1e+06 rad");
}

TEST(Scenario, ASpeedBeyondTheBearingsLimitIsRefusedNamingTheKey) {
  expect_scenario_error(header() + "speed: {initial_speed_rpm: 1e300}\n", "speed.initial_speed_rpm",
                      "is beyond +-900.1 rad/s");
  expect_scenario_error(
      header() + "speed:\n  segments:\n    - {type: ramp, start_s: 1, end_s: 2, to_speed_rad_s: -1e4}\n",
      "speed.segments[0].to_speed_rad_s", "-1e+04 rad/s");
  EXPECT_NO_THROW(Scenario::from_string(header() + "speed: {initial_speed_rpm: 8500}\n", kScenarioSource));
}

// The node refuses a load its bearing cannot carry and runs on at the last good one, while
// scenario_state (the labels) said the refused load: such a scenario is refused when read.
TEST(Scenario, ALoadTheBearingCannotCarryIsRefusedNamingTheSegment) {
  expect_scenario_error(header() +
                          "load:\n  initial: {force_N: [6800, 0, 0]}\n  segments:\n"
                          "    - {type: step, start_s: 5, force_N: [6800, 0, 0]}\n"
                          "    - {type: step, start_s: 10, force_N: [1e9, 0, 0]}\n",
                      "load.segments[1].force_N", "the bearing cannot carry the load (1e+09");
  expect_scenario_error(header() + "load:\n  initial: {force_N: [0, 0, 1e12]}\n", "load.initial", "cannot carry");
  EXPECT_NO_THROW(Scenario::from_string(
      header() + "load:\n  segments:\n    - {type: ramp, start_s: 1, end_s: 2, force_N: [20000, 0, 0]}\n", kScenarioSource));
}

TEST(Scenario, BadInputNamesFileAndKey) {
  const std::string h = header();
  expect_scenario_error(h + "speeed: {}\n", "speeed", "unknown key");
  expect_scenario_error(h + kSpeed + "    - {type: hold, start_s: 22, end_s: 23, rpm: 3}\n", "speed.segments[4].rpm",
                      "unknown key");
  expect_scenario_error("name: x\nduration_s: -3\nbearing_file: " + bearing_file("ct_gantry_lyc.yaml") + "\n",
                      "duration_s", "must be > 0");
  expect_scenario_error("name: x\nbearing_file: " + bearing_file("ct_gantry_lyc.yaml") + "\n", "duration_s", "required");
  // Overlapping, then unsorted, speed segments.
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: ramp, start_s: 0, end_s: 5, to_speed_rpm: 10}\n"
                          "    - {type: hold, start_s: 4, end_s: 6}\n",
                      "speed.segments[1].start_s", "overlap");
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: ramp, start_s: 5, end_s: 6, to_speed_rpm: 10}\n"
                          "    - {type: ramp, start_s: 1, end_s: 2, to_speed_rpm: 20}\n",
                      "speed.segments[1].start_s", "time order");
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: ramp, start_s: 5, end_s: 5, to_speed_rpm: 10}\n",
                      "speed.segments[0].end_s", "after start_s");
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: ramp, start_s: 5, end_s: 30, to_speed_rpm: 10}\n",
                      "speed.segments[0].end_s", "after the end");
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: ramp, start_s: 5, end_s: 6}\n",
                      "speed.segments[0].to_speed_rpm");
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: coast, start_s: 5, end_s: 6, time_constant_s: 0}\n",
                      "speed.segments[0].time_constant_s");
  expect_scenario_error(h + "speed:\n  segments:\n    - {type: spin, start_s: 5, end_s: 6}\n", "speed.segments[0].type");
  expect_scenario_error(h + "speed: {initial_speed_rpm: 3, initial_speed_rad_s: 1}\n", "speed.initial_speed_rpm",
                      "not both");
  expect_scenario_error(h + "load:\n  segments:\n    - {type: ramp, start_s: 2, end_s: 4, force_N: [1, 2, 3]}\n"
                          "    - {type: step, start_s: 3, moment_Nm: [1, 1]}\n",
                      "load.segments[1].start_s", "overlap");
  expect_scenario_error(h + "load:\n  initial: {force_N: [1, 2]}\n", "load.initial.force_N", "3 numbers");
  expect_scenario_error(h + "load:\n  initial: {force_N: [1, .nan, 3]}\n", "load.initial.force_N", "finite");
  expect_scenario_error(h + "load:\n  unbalance: {mass_kg: -1, radius_m: 0.5}\n", "load.unbalance.mass_kg");
  expect_scenario_error(h + "phases:\n  - {name: a, start_s: 5}\n  - {name: b, start_s: 2}\n", "phases[1].start_s",
                      "time order");
  // Defects: unsorted, not fitting when they appear, outgrowing the bearing, bad surface.
  expect_scenario_error(
      h + "defects:\n  - {at_s: 5, width_mm: 1, depth_um: 10}\n  - {at_s: 2, width_mm: 1, depth_um: 10}\n",
      "defects[1].at_s", "time order");
  expect_scenario_error(h + "defects:\n  - {at_s: 1, width_mm: 1, depth_um: 4000}\n", "defects[0]", "does not fit");
  expect_scenario_error(h + "defects:\n  - {at_s: 1, surface: ball, ball: 414, width_mm: 1, depth_um: 10}\n",
                      "defects[0]", "ball index");
  expect_scenario_error(h + "defects:\n  - {at_s: 1, width_mm: 1, depth_um: 10, depth_growth_um_per_s: 200}\n",
                      "defects[0]", "grows too large");
  expect_scenario_error(h + "defects:\n  - {at_s: 1, surface: cage, width_mm: 1, depth_um: 10}\n", "defects[0].surface");
  expect_scenario_error(h + "defects:\n  - {at_s: 1, width_mm: 1, depth_um: 10, width_growth_mm_per_s: -1}\n",
                      "defects[0].width_growth_mm_per_s", ">= 0");
  // Files.
  expect_scenario_error("name: x\nduration_s: 3\nbearing_file: no_such_bearing.yaml\n", "bearing_file", "cannot find");
  expect_scenario_error(h + "sensor_file: no_such_sensor.yaml\n", "sensor_file", "cannot find");
  EXPECT_THROW(Scenario::load("/nonexistent/scenario.yaml"), ConfigError);
  EXPECT_THROW(Scenario::from_string("name: [unclosed\n", kScenarioSource), ConfigError);
}

TEST(Scenario, ShippedScenariosLoad) {
  const std::string dir = std::string(BEARING_SIM_SOURCE_DIR) + "/config/scenarios/";
  const Scenario scan = Scenario::load(dir + "ct_gantry_scan.yaml");
  EXPECT_EQ(scan.name(), "ct_gantry_scan");
  EXPECT_EQ(scan.bearing_file(), std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ct_gantry_lyc.yaml");
  EXPECT_EQ(scan.sensor_file(),
            std::string(BEARING_SIM_SOURCE_DIR) + "/config/sensors/ct_gantry_housing_accelerometer.yaml");
  EXPECT_EQ(scan.ring_speed_at(0.0), 0.0);
  EXPECT_NEAR(scan.ring_speed_at(17.0), 180 * kRpm, 1e-12);
  EXPECT_EQ(scan.phase_at(17.0), "scan");
  EXPECT_EQ(scan.ring_speed_at(scan.duration_s()), 0.0);
  // Paper load plus the unbalance at scan speed (0.11 kg*m: 39 N).
  const ScenarioInputs in = scan.inputs_at(17.0);
  EXPECT_NEAR(std::hypot(in.load[0] - 6800.0, in.load[1]), 0.11 * std::pow(180 * kRpm, 2), 1e-9);
  EXPECT_EQ(in.load[4], 2100.0);

  const Scenario rtf = Scenario::load(dir + "ct_gantry_run_to_failure.yaml");
  ASSERT_EQ(rtf.defect_events().size(), 1u);
  const Spall s = rtf.spalls_at(rtf.duration_s()).at(0);
  EXPECT_EQ(s.surface, Surface::OuterRace);
  EXPECT_NEAR(Scenario::spall_width_at(s, rtf.duration_s()), 4.2e-3, 1e-12);
  EXPECT_NEAR(Scenario::spall_depth_at(s, rtf.duration_s()), 69e-6, 1e-12);
}
