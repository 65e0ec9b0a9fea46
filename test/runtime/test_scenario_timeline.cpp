// ScenarioTimeline (the scenario player's time line, no ROS): which command goes out when.
// Inputs equal Scenario::inputs_at at the times they are sent, on their grids and only
// when they change; each defect event fires exactly once per pass, in order, at the first
// tick at or after its time; labels at their rate and after every event; the end; loops.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/load_ramp.hpp"
#include "bearing_sim/runtime/scenario_timeline.hpp"

using namespace bearing_sim;
using namespace bearing_sim::runtime;
using Kind = TimelineCommand::Kind;

namespace {

const std::string kBearing = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ct_gantry_lyc.yaml";

// 6 s: 60 rpm, ramp to 180 rpm from 1 to 3 s; load step at 4 s; an inner-race spall at
// 2 s growing, cleared at 5 s.
std::string scenario_text(const std::string& load_extra = "") {
  return "name: timeline\nduration_s: 6\nseed: 7\nbearing_file: " + kBearing +
         "\n"
         "phases: [{name: slow, start_s: 0}, {name: ramp, start_s: 1}, {name: fast, start_s: 3}]\n"
         "speed:\n"
         "  initial_speed_rpm: 60\n"
         "  segments:\n"
         "    - {type: ramp, start_s: 1, end_s: 3, to_speed_rpm: 180}\n"
         "load:\n"
         "  initial: {force_N: [6800, 0, 0], moment_Nm: [0, 2100]}\n"
         "  segments:\n"
         "    - {type: step, start_s: 4, force_N: [9000, 0, 0]}\n" +
         load_extra +
         "defects:\n"
         "  - {type: spall, at_s: 2, surface: inner_race, position_deg: 180, width_mm: 1.0, depth_um: 10,\n"
         "     width_growth_mm_per_s: 0.1, depth_growth_um_per_s: 1}\n"
         "  - {type: clear, at_s: 5}\n";
}

Scenario make_scenario(const std::string& load_extra = "") {
  return Scenario::from_string(scenario_text(load_extra), "/tmp/timeline_test.yaml");
}

struct Sent {
  double tick_s;  // elapsed time of the advance() call
  TimelineCommand command;
};

// advance() at k * step_s for k = 0 .. until_s / step_s.
std::vector<Sent> play(ScenarioTimeline& tl, double step_s, double until_s) {
  std::vector<Sent> out;
  const long n = std::lround(until_s / step_s);
  for (long k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) * step_s;
    for (const TimelineCommand& c : tl.advance(t)) out.push_back({t, c});
  }
  return out;
}

std::vector<Sent> of_kind(const std::vector<Sent>& all, Kind kind) {
  std::vector<Sent> out;
  for (const Sent& s : all)
    if (s.command.kind == kind) out.push_back(s);
  return out;
}

}  // namespace

TEST(ScenarioTimeline, SpeedEqualsTheScenarioAtEachSendTimeOnItsGrid) {
  const Scenario sc = make_scenario();
  TimelineSettings settings;
  settings.speed_rate_hz = 200.0;
  ScenarioTimeline tl(sc, settings);
  const std::vector<Sent> speeds = of_kind(play(tl, 1e-3, 7.0), Kind::Speed);
  std::set<long> cells;
  for (const Sent& s : speeds) {
    EXPECT_EQ(s.command.scenario_time_s, s.tick_s);  // sent at once, evaluated at the send time
    EXPECT_EQ(s.command.speed_rad_s, sc.inputs_at(s.tick_s).ring_speed_rad_s) << "t = " << s.tick_s;
    EXPECT_TRUE(cells.insert(static_cast<long>(std::floor(s.tick_s * 200.0 + 1e-9))).second)
        << "two speeds in one 5 ms cell at " << s.tick_s;
    // Only at the start and while the speed changes (the ramp from 1 to 3 s).
    EXPECT_TRUE(s.tick_s == 0.0 || (s.tick_s > 1.0 && s.tick_s < 3.0 + 5e-3)) << "t = " << s.tick_s;
  }
  // One per 5 ms cell over the 2 s ramp, plus the first.
  EXPECT_NEAR(static_cast<double>(speeds.size()), 1.0 + 2.0 * 200.0, 2.0);
}

TEST(ScenarioTimeline, LoadOnlyWhenItChanges) {
  const Scenario sc = make_scenario();
  ScenarioTimeline tl(sc, TimelineSettings{});
  const std::vector<Sent> loads = of_kind(play(tl, 1e-3, 7.0), Kind::Load);
  ASSERT_EQ(loads.size(), 2u);  // at 0 and at the step
  EXPECT_EQ(loads[0].tick_s, 0.0);
  EXPECT_EQ(loads[0].command.load, sc.inputs_at(0.0).load);
  EXPECT_EQ(loads[0].command.load[0], 6800.0);
  EXPECT_GE(loads[1].tick_s, 4.0);
  EXPECT_LT(loads[1].tick_s, 4.0 + 1.0 / 50.0);  // within one cell of the load grid
  EXPECT_EQ(loads[1].command.load, sc.inputs_at(loads[1].tick_s).load);
  EXPECT_EQ(loads[1].command.load[0], 9000.0);
}

TEST(ScenarioTimeline, RotatingUnbalanceGoesOutOncePerLoadCell) {
  // 0.2 kg at 0.55 m: the load turns with the ring, so it changes in every cell.
  const Scenario sc = make_scenario("  unbalance: {mass_kg: 0.2, radius_m: 0.55, phase_deg: 0}\n");
  TimelineSettings settings;
  settings.load_rate_hz = 50.0;
  ScenarioTimeline tl(sc, settings);
  const std::vector<Sent> loads = of_kind(play(tl, 1e-3, 6.0), Kind::Load);
  for (const Sent& s : loads) EXPECT_EQ(s.command.load, sc.inputs_at(s.tick_s).load) << "t = " << s.tick_s;
  EXPECT_NEAR(static_cast<double>(loads.size()), 6.0 * 50.0, 2.0);
  // At 60 rpm the unbalance force m e w^2 = 0.11 * (2 pi)^2 = 4.3 N is on top of 6800 N.
  const double f = std::hypot(loads[10].command.load[0] - 6800.0, loads[10].command.load[1]);
  EXPECT_NEAR(f, 0.2 * 0.55 * 4.0 * M_PI * M_PI, 1e-9);
}

TEST(ScenarioTimeline, EachDefectEventFiresOnceInOrderAtItsTime) {
  const Scenario sc = make_scenario();
  ASSERT_EQ(sc.defect_events().size(), 2u);
  for (double step : {1e-3, 0.01, 0.7, 2.9}) {
    ScenarioTimeline tl(sc, TimelineSettings{});
    const std::vector<Sent> events = of_kind(play(tl, step, 7.0), Kind::DefectEvent);
    ASSERT_EQ(events.size(), 2u) << "step " << step;
    for (std::size_t i = 0; i < 2; ++i) {
      const ScenarioDefectEvent& e = sc.defect_events()[i];
      EXPECT_EQ(events[i].command.event.kind, e.kind);
      EXPECT_EQ(events[i].command.event.time_s, e.time_s);
      EXPECT_GE(events[i].tick_s, e.time_s);         // never early
      EXPECT_LT(events[i].tick_s, e.time_s + step);  // at the first tick at or after it
    }
    EXPECT_EQ(events[0].command.event.kind, ScenarioDefectEvent::Kind::Spall);
    EXPECT_EQ(events[0].command.event.spall.surface, Surface::InnerRace);
    EXPECT_DOUBLE_EQ(events[0].command.event.spall.width_m, 1e-3);
    EXPECT_DOUBLE_EQ(events[0].command.event.spall.width_growth_m_per_s, 1e-4);
    EXPECT_EQ(events[1].command.event.kind, ScenarioDefectEvent::Kind::Clear);
  }
  // One call past everything: both, in order, then the end.
  ScenarioTimeline tl(sc, TimelineSettings{});
  tl.advance(0.0);
  const std::vector<TimelineCommand> all = tl.advance(100.0);
  std::vector<Kind> kinds;
  for (const TimelineCommand& c : all)
    if (c.kind == Kind::DefectEvent || c.kind == Kind::End) kinds.push_back(c.kind);
  EXPECT_EQ(kinds, (std::vector<Kind>{Kind::DefectEvent, Kind::DefectEvent, Kind::End}));
}

TEST(ScenarioTimeline, LabelsAtTheirRateAndAfterEachEvent) {
  const Scenario sc = make_scenario();
  ScenarioTimeline tl(sc, TimelineSettings{});  // 10 Hz
  const std::vector<Sent> all = play(tl, 1e-3, 7.0);
  const std::vector<Sent> states = of_kind(all, Kind::State);
  // One per 0.1 s cell over 6 s, one at the end, and one after each of the two events
  // (the events at 2 s and 5 s fall on a cell start, where a label goes out anyway).
  EXPECT_NEAR(static_cast<double>(states.size()), 60.0 + 1.0, 1.0);
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i].command.kind != Kind::DefectEvent) continue;
    bool labelled = false;
    for (std::size_t j = i + 1; j < all.size() && all[j].tick_s == all[i].tick_s; ++j)
      labelled |= all[j].command.kind == Kind::State;
    EXPECT_TRUE(labelled) << "no label after the event at " << all[i].tick_s;
  }
  for (std::size_t i = 1; i < states.size(); ++i)
    EXPECT_GT(states[i].command.scenario_time_s, states[i - 1].command.scenario_time_s);
}

TEST(ScenarioTimeline, EndsOnceWithTheFinalValues) {
  const Scenario sc = make_scenario();
  ScenarioTimeline tl(sc, TimelineSettings{});
  const std::vector<Sent> all = play(tl, 0.013, 8.0);
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.back().command.kind, Kind::End);
  EXPECT_EQ(all.back().command.scenario_time_s, 6.0);
  EXPECT_EQ(of_kind(all, Kind::End).size(), 1u);
  const std::vector<Sent> states = of_kind(all, Kind::State);
  EXPECT_EQ(states.back().command.scenario_time_s, 6.0);  // labels exactly at the end
  EXPECT_TRUE(tl.finished());
  EXPECT_TRUE(tl.advance(9.0).empty());
  EXPECT_TRUE(of_kind(all, Kind::ClearDefects).empty());
}

TEST(ScenarioTimeline, LoopsWithTheDefectsClearedAtEachPass) {
  const Scenario sc = make_scenario();
  TimelineSettings settings;
  settings.loop = true;
  ScenarioTimeline tl(sc, settings);
  const std::vector<Sent> all = play(tl, 1e-3, 15.0);  // 2.5 passes of 6 s
  EXPECT_FALSE(tl.finished());
  EXPECT_EQ(tl.pass(), 2u);
  const std::vector<Sent> clears = of_kind(all, Kind::ClearDefects);
  ASSERT_EQ(clears.size(), 2u);
  EXPECT_NEAR(clears[0].tick_s, 6.0, 1e-9);
  EXPECT_NEAR(clears[1].tick_s, 12.0, 1e-9);
  EXPECT_EQ(clears[1].command.pass, 2u);
  // Spall at 2, clear at 5 in each full pass; the spall of the third at 14 s.
  const std::vector<Sent> events = of_kind(all, Kind::DefectEvent);
  ASSERT_EQ(events.size(), 5u);
  const double expected_ticks[5] = {2.0, 5.0, 8.0, 11.0, 14.0};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(events[i].tick_s, expected_ticks[i], 1e-9);
    EXPECT_NEAR(events[i].command.scenario_time_s, expected_ticks[i] - 6.0 * static_cast<double>(i / 2), 1e-9);
    EXPECT_EQ(events[i].command.pass, i / 2);
  }
  for (const Sent& s : of_kind(all, Kind::Speed))
    EXPECT_EQ(s.command.speed_rad_s, sc.inputs_at(s.command.scenario_time_s).ring_speed_rad_s);
}

TEST(ScenarioTimeline, NodeParametersAreTheInputsAtTimeZero) {
  const Scenario sc = make_scenario();
  EXPECT_EQ(scenario_node_parameter(sc, "bearing_file"), sc.bearing_file());
  EXPECT_EQ(scenario_node_parameter(sc, "sensor_file"), "");
  const ScenarioInputs in = sc.inputs_at(0.0);
  auto value = [&](const char* name) { return std::strtod(scenario_node_parameter(sc, name).c_str(), nullptr); };
  EXPECT_EQ(value("initial_speed_rad_s"), in.ring_speed_rad_s);  // %.17g round-trips
  EXPECT_DOUBLE_EQ(value("initial_speed_rad_s"), 2.0 * M_PI);
  EXPECT_EQ(value("initial_force_x_N"), 6800.0);
  EXPECT_EQ(value("initial_force_y_N"), 0.0);
  EXPECT_EQ(value("initial_force_z_N"), 0.0);
  EXPECT_EQ(value("initial_moment_x_Nm"), 0.0);
  EXPECT_EQ(value("initial_moment_y_Nm"), 2100.0);
  EXPECT_THROW(scenario_node_parameter(sc, "initial_speed_rpm"), InvalidInputError);
}

TEST(ScenarioTimeline, RejectsBadRates) {
  const Scenario sc = make_scenario();
  for (double bad : {0.0, -10.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    TimelineSettings s;
    s.speed_rate_hz = bad;
    EXPECT_THROW((ScenarioTimeline{sc, s}), InvalidInputError);
    s = TimelineSettings{};
    s.load_rate_hz = bad;
    EXPECT_THROW((ScenarioTimeline{sc, s}), InvalidInputError);
    s = TimelineSettings{};
    s.state_rate_hz = bad;
    EXPECT_THROW((ScenarioTimeline{sc, s}), InvalidInputError);
  }
}

// The node's ~load_ramp_s (set by ct_gantry.launch with a scenario): a new load reached
// linearly, exactly at the last sample; idle before the first start and with 0 samples.
TEST(LoadRamp, LinearToTheTargetOverItsSamples) {
  Vector5 a, b;
  a << 6800, 0, 0, 0, 2100;
  b << 6839, 7, 0, 0, 2100;
  LoadRamp idle(100);
  EXPECT_FALSE(idle.active());  // nothing to do before the first load arrives
  LoadRamp ramp(100);
  ramp.start(a, b);
  for (int k = 1; k <= 100; ++k) {
    ASSERT_TRUE(ramp.active());
    const Vector5 l = ramp.next();
    const Vector5 expected = a + (b - a) * (k / 100.0);
    EXPECT_NEAR((l - expected).norm(), 0.0, 1e-9) << "sample " << k;
    if (k == 100) {
      EXPECT_EQ(l, b);  // exactly the target at the end
    }
  }
  EXPECT_FALSE(ramp.active());
  // A new load mid-way starts from where the ramp is.
  ramp.start(a, b);
  for (int k = 0; k < 50; ++k) ramp.next();
  const Vector5 mid = a + (b - a) * 0.5;
  ramp.start(mid, a);
  EXPECT_NEAR((ramp.next() - (mid + (a - mid) * 0.01)).norm(), 0.0, 1e-9);
  LoadRamp step(0);
  step.start(a, b);
  EXPECT_FALSE(step.active());  // the caller applies b at once
}


// The ring temperature difference goes out on the load grid, only when its staircase steps,
// with the scenario's value at the time sent; a scenario without the key sends none.
TEST(ScenarioTimeline, RingTemperatureGoesOutOnEachStepOnly) {
  const Scenario s = Scenario::from_string(scenario_text() +
                                               "ring_temperature_difference:\n"
                                               "  segments: [{type: ramp, start_s: 1, end_s: 3, difference_K: -1}]\n",
                                           "/tmp/timeline_test.yaml");
  ScenarioTimeline tl(s, TimelineSettings{});
  const std::vector<Sent> sent = of_kind(play(tl, 0.001, 6.0), Kind::RingTemperature);
  // 0 K at the start, then 10 steps of 0.1 K down to -1 K.
  ASSERT_EQ(sent.size(), 11u);
  EXPECT_EQ(sent.front().command.ring_temperature_difference_K, 0.0);
  EXPECT_EQ(sent.back().command.ring_temperature_difference_K, -1.0);
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const TimelineCommand& c = sent[i].command;
    EXPECT_EQ(c.ring_temperature_difference_K, s.ring_temperature_difference_at(c.scenario_time_s));
    if (i > 0) {
      EXPECT_NEAR(c.ring_temperature_difference_K, sent[i - 1].command.ring_temperature_difference_K - 0.1, 1e-12);
    }
  }
  const Scenario plain = make_scenario();  // the timeline keeps a reference
  ScenarioTimeline without(plain, TimelineSettings{});
  EXPECT_TRUE(of_kind(play(without, 0.001, 6.0), Kind::RingTemperature).empty());
}

// The node's input limits (its max_force_N, max_moment_Nm, max_speed_rad_s), which the
// scenario reader does not know: a scenario with an input beyond them is refused before its
// first sample, naming the key, the value, the time and the limit; the first in time.
TEST(ScenarioLimits, AForceAboveTheNodesMaxForceIsRefusedNamingTheSegment) {
  // The bearing carries 150 kN (the reader accepts it); the node's default limit is 100 kN.
  const Scenario s = make_scenario("    - {type: step, start_s: 5, force_N: [150000, 0, 0]}\n");
  EXPECT_EQ(scenario_limit_refusal(s, InputLimits{}),
            "load.segments[1].force_N: |(Fx, Fy, Fz)| = 150000 N at t = 5 s exceeds the node's max_force_N = "
            "100000 N");
  // Within the limit (the node refuses only above it): nothing to say.
  InputLimits at_the_value;
  at_the_value.max_force_N = 150000.0;
  EXPECT_EQ(scenario_limit_refusal(s, at_the_value), "");
  EXPECT_EQ(scenario_limit_refusal(make_scenario(), InputLimits{}), "");
  // A ramp reaches its target at its end; the first in time is named, not the largest.
  const Scenario ramp = make_scenario(
      "    - {type: ramp, start_s: 5, end_s: 5.5, force_N: [0, 110000, 0]}\n"
      "    - {type: step, start_s: 5.8, force_N: [0, 0, 160000]}\n");
  EXPECT_EQ(scenario_limit_refusal(ramp, InputLimits{}),
            "load.segments[1].force_N: |(Fx, Fy, Fz)| = 110000 N at t = 5.5 s exceeds the node's max_force_N = "
            "100000 N");
  // The first step beyond a lower limit; the magnitude counts (each component within the limit).
  InputLimits low;
  low.max_force_N = 8000.0;
  EXPECT_EQ(scenario_limit_refusal(s, low),
            "load.segments[0].force_N: |(Fx, Fy, Fz)| = 9000 N at t = 4 s exceeds the node's max_force_N = 8000 N");
  const Scenario diagonal = make_scenario("    - {type: step, start_s: 5, force_N: [80000, 80000, 0]}\n");
  const std::string why = scenario_limit_refusal(diagonal, InputLimits{});
  EXPECT_NE(why.find("load.segments[1].force_N: |(Fx, Fy, Fz)| = 113137 N at t = 5 s"), std::string::npos) << why;
}

TEST(ScenarioLimits, AMomentOrSpeedAboveTheNodesLimitIsRefusedNamingTheKey) {
  const Scenario s = make_scenario();  // 2100 N*m; 60 rpm, ramp to 180 rpm from 1 to 3 s
  InputLimits moment;
  moment.max_moment_Nm = 2000.0;
  EXPECT_EQ(scenario_limit_refusal(s, moment),
            "load.initial.moment_Nm: |(Mx, My)| = 2100 N*m at t = 0 s exceeds the node's max_moment_Nm = 2000 N*m");
  // The ramp's target, at its end (the speed is largest there).
  InputLimits speed;
  speed.max_speed_rad_s = 10.0;
  EXPECT_EQ(scenario_limit_refusal(s, speed),
            "speed.segments[0].to_speed_rpm: |speed| = 18.8496 rad/s (180 rpm) at t = 3 s exceeds the node's "
            "max_speed_rad_s = 10 rad/s");
  speed.max_speed_rad_s = 5.0;
  EXPECT_EQ(scenario_limit_refusal(s, speed),
            "speed.initial_speed_rpm: |speed| = 6.28319 rad/s (60 rpm) at t = 0 s exceeds the node's "
            "max_speed_rad_s = 5 rad/s");
  // A step in a hold, given in rad/s; the speed before it is named by its own key.
  const std::string text = scenario_text();
  const std::string stepped = text.substr(0, text.find("load:")) +
                              "    - {type: hold, start_s: 4, end_s: 5, speed_rad_s: -30}\n" +
                              text.substr(text.find("load:"));
  const Scenario hold = Scenario::from_string(stepped, "/tmp/timeline_test.yaml");
  speed.max_speed_rad_s = 20.0;
  EXPECT_EQ(scenario_limit_refusal(hold, speed),
            "speed.segments[1].speed_rad_s: |speed| = 30 rad/s (286.479 rpm) at t = 4 s exceeds the node's "
            "max_speed_rad_s = 20 rad/s");
}

// With a rotating unbalance the force the player sends turns: the check takes it at its worst
// angle, which the ring passes once a revolution, so it bounds every load the player sends
// and is reached within a revolution.
TEST(ScenarioLimits, TheUnbalanceCountsAtItsWorstAngle) {
  // 10 kg*m: 3553 N at 180 rpm, on the radial 6800 N (then 9000 N from 4 s).
  const Scenario s = make_scenario("  unbalance: {mass_kg: 10, radius_m: 1}\n");
  double largest_sent = 0.0, largest_extreme = 0.0;
  for (double t = 0.0; t <= s.duration_s(); t += 1e-4)
    largest_sent = std::max(largest_sent, s.load_at(t).head<3>().norm());
  for (const Scenario::InputExtreme& e : s.input_extremes()) largest_extreme = std::max(largest_extreme, e.force_N);
  EXPECT_GE(largest_extreme, largest_sent);
  EXPECT_NEAR(largest_sent, largest_extreme, 1e-3 * largest_extreme);
  EXPECT_NEAR(largest_extreme, 9000.0 + 10.0 * std::pow(180.0 * 2.0 * M_PI / 60.0, 2), 1e-6);
  // The load alone within the limit, with the unbalance beyond it: named as the unbalance's.
  InputLimits limits;
  limits.max_force_N = 10000.0;
  const std::string why = scenario_limit_refusal(s, limits);
  EXPECT_EQ(why.rfind("load.unbalance: with the load of load.initial.force_N |(Fx, Fy, Fz)| reaches 1035", 0), 0u)
      << why;
  EXPECT_NE(why.find("at t = 3 s (the unbalance's 355"), std::string::npos) << why;
  EXPECT_NE(why.find("exceeds the node's max_force_N = 10000 N"), std::string::npos) << why;
  // The load alone beyond the limit: named by its key, the unbalance included in the value.
  limits.max_force_N = 6000.0;
  EXPECT_EQ(scenario_limit_refusal(s, limits),
            "load.initial.force_N: |(Fx, Fy, Fz)| = 7194.78 N at t = 0 s (the unbalance included) exceeds the node's "
            "max_force_N = 6000 N");
}
