// The ring temperature difference of a scenario (docs/scenarios.md): its time line against
// hand values (ramps as a staircase of 0.1 K that ends on the target), and the bad files.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
const char* kTemperatureSource = "/tmp/unit_test_scenario_temperature.yaml";

Scenario with_temperature(const std::string& block) {
  return Scenario::from_string(
      "name: unit\nduration_s: 30\nbearing_file: " + bearing_file("ct_gantry_lyc.yaml") + "\n" + block, kTemperatureSource);
}

void expect_temperature_error(const std::string& block, std::vector<std::string> words) {
  words.push_back(kTemperatureSource);
  expect_config_error([&] { with_temperature(block); }, words, block);
}
}  // namespace

TEST(ScenarioTemperature, StepsAndStaircaseRamps) {
  // The rotor (outer ring) warms by 8 K over 20 s, then a step back to 2 K at 25 s.
  const Scenario s = with_temperature(
      "ring_temperature_difference:\n"
      "  initial_K: 0\n"
      "  segments:\n"
      "    - {type: ramp, start_s: 2, end_s: 22, difference_K: -8}\n"
      "    - {type: step, start_s: 25, difference_K: 2}\n");
  EXPECT_TRUE(s.has_ring_temperature_difference());
  EXPECT_EQ(s.ring_temperature_difference_at(0.0), 0.0);
  EXPECT_EQ(s.ring_temperature_difference_at(2.0), 0.0);
  // 0.4 K/s: at 7.01 s the exact value is -2.004 K, the staircase has done 20 steps of 0.1 K.
  EXPECT_NEAR(s.ring_temperature_difference_at(7.01), -2.0, 1e-12);
  EXPECT_NEAR(s.ring_temperature_difference_at(7.26), -2.1, 1e-12);
  // Never more than one step behind the exact ramp, never past it.
  for (double t = 2.0; t < 22.0; t += 0.013) {
    const double exact = -8.0 * (t - 2.0) / 20.0, v = s.ring_temperature_difference_at(t);
    EXPECT_LE(exact, v + 1e-12);
    EXPECT_LT(v - exact, Scenario::kTemperatureStepK);
  }
  EXPECT_EQ(s.ring_temperature_difference_at(22.0), -8.0);
  EXPECT_EQ(s.ring_temperature_difference_at(24.9), -8.0);
  EXPECT_EQ(s.ring_temperature_difference_at(25.0), 2.0);
  EXPECT_EQ(s.inputs_at(29.0).ring_temperature_difference_K, 2.0);
  // Without the key: equal ring temperatures throughout.
  const Scenario none = with_temperature("");
  EXPECT_FALSE(none.has_ring_temperature_difference());
  EXPECT_EQ(none.ring_temperature_difference_at(10.0), 0.0);
}

TEST(ScenarioTemperature, BadTimeLinesAreNamed) {
  expect_temperature_error("ring_temperature_difference: {initial_K: .nan}\n", {"ring_temperature_difference.initial_K", "finite"});
  expect_temperature_error("ring_temperature_difference: {segments: [{type: hold, start_s: 1}]}\n",
               {"ring_temperature_difference.segments[0].type", "step or ramp"});
  expect_temperature_error("ring_temperature_difference: {segments: [{type: ramp, start_s: 1, difference_K: 3}]}\n",
               {"segments[0].end_s", "required"});
  expect_temperature_error("ring_temperature_difference: {segments: [{type: step, start_s: 1}]}\n",
               {"segments[0].difference_K", "required"});
  // The CT bearing's 1111 mm pitch circle: 120 K more on the inner ring is an interference
  // beyond the model's 5 % of the ball diameter.
  expect_temperature_error("ring_temperature_difference: {segments: [{type: ramp, start_s: 1, end_s: 5, difference_K: 120}]}\n",
               {"segments[0].difference_K", "interference", "120 K"});
  expect_temperature_error("ring_temperature_difference: {initial_K: 200}\n", {"initial_K", "150 K"});
  expect_temperature_error(
      "ring_temperature_difference: {segments: [{type: step, start_s: 5, difference_K: 1}, "
      "{type: step, start_s: 4, difference_K: 2}]}\n",
      {"segments[1].start_s", "time order"});
}
