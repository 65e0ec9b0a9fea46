// Clearance at a ring temperature difference (docs/model.md section 3.7): the closed form
// from the raceway diameters, the stiffer bearing and wider load zone of a warmer inner ring
// (the same as a cold bearing with that clearance), and the errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bearing_6205_yaml.hpp"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/thermal_clearance.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
BearingConfig bearing_6205_config(double clearance_um) {
  BearingConfig c = bearing_config_from_string(kBearing6205Yaml);
  c.clearance_m = clearance_um * 1e-6;
  return c;
}
int loaded_balls(const StaticSolution& s) {
  int n = 0;
  for (const BallState& b : s.balls) n += b.load_N > 0.0;
  return n;
}
}  // namespace

// Independent form: each ring's raceway diameter grows by alpha T D; with the outer ring at
// the reference, the inner ring dT warmer and the balls at the mean dT/2, the diametral
// clearance d_o - d_i - 2 D changes by -alpha dT (d_i + D); g0 is half of it (a0 = 0).
TEST(ThermalClearance, ChangeMatchesTheRacewayExpansion) {
  BearingConfig c = bearing_6205_config(10.0);
  const double alpha = 11.5e-6, d = c.ball_diameter_m, d_inner_race = c.pitch_diameter_m - d;
  for (double dT : {-30.0, -5.0, 0.0, 5.0, 20.0}) {
    c.ring_temperature_difference_K = dT;
    const double d_pd = alpha * (0.0 - dT * d_inner_race - 2.0 * (dT / 2.0) * d);
    EXPECT_NEAR(operating_clearance_m(c), 10e-6 + d_pd / 2.0, 1e-15) << dT << " K";
  }
  // 20 K on a 39 mm pitch circle: 4.5 um less per ball, the order a bearing catalogue warns of.
  c.ring_temperature_difference_K = 20.0;
  EXPECT_NEAR(operating_clearance_m(c) - 10e-6, -4.49e-6, 0.01e-6);
  // The contact line of an angular contact bearing sees the radial closing times cos a0.
  BearingConfig angular = single_row(12, 10.0, 50.0, 40.0, 0.52, 0.53, 0.0);
  angular.ring_temperature_difference_K = 10.0;
  EXPECT_NEAR(operating_clearance_m(angular), -alpha * 10.0 * 0.025 * std::cos(40.0 * kPi / 180.0), 1e-15);
}

// Numbers of the 6205 (probed once): at 300 N the cold bearing (5 um) carries on 3 balls
// with Qmax 172 N and x 11.9 um; 30 K closes 6.7 um (-1.7 um: a slight preload) and 5 balls
// carry, Qmax 131 N, x 4.1 um. At 50 N the preload puts all 9 balls in contact and doubles K_xx.
TEST(ThermalClearance, WarmerInnerRingStiffensAndWidensTheLoadZone) {
  BearingConfig cold = bearing_6205_config(5.0);
  BearingConfig hot = cold;
  hot.ring_temperature_difference_K = 30.0;
  const BearingModel cold_model(cold), hot_model(hot);
  const double closed_m = cold_model.clearance_m() - hot_model.clearance_m();
  EXPECT_NEAR(closed_m, 6.73e-6, 0.01e-6);

  const Vector5 load = load5(300.0, 0.0, 0.0, 0.0, 0.0);
  const StaticSolution s_cold = solve_static(cold_model, load), s_hot = solve_static(hot_model, load);
  // Wider load zone: more balls share the load, the most loaded one carries less.
  EXPECT_GT(loaded_balls(s_hot), loaded_balls(s_cold));
  EXPECT_LT(s_hot.max_ball_load_N, 0.85 * s_cold.max_ball_load_N);
  // The ring moves less by at least the play that was closed (the balls also deflect less).
  EXPECT_GT(s_cold.displacement[0] - s_hot.displacement[0], closed_m);
  // At a light load the thermal preload holds every ball in contact: much stiffer.
  const Vector5 light = load5(50.0, 0.0, 0.0, 0.0, 0.0);
  const StaticSolution l_cold = solve_static(cold_model, light), l_hot = solve_static(hot_model, light);
  EXPECT_EQ(loaded_balls(l_hot), 9);
  EXPECT_GT(l_hot.stiffness(0, 0), 2.0 * l_cold.stiffness(0, 0));

  // The same as a bearing at equal ring temperatures with the operating clearance.
  BearingConfig equivalent = cold;
  equivalent.clearance_m = hot_model.clearance_m();
  const StaticSolution s_eq = solve_static(BearingModel(equivalent), load);
  EXPECT_EQ(s_hot.displacement, s_eq.displacement);
  EXPECT_EQ(s_hot.stiffness, s_eq.stiffness);
  // An outer ring warmer than the inner opens the clearance instead: the ring moves further.
  BearingConfig outer_hot = cold;
  outer_hot.ring_temperature_difference_K = -30.0;
  EXPECT_GT(solve_static(BearingModel(outer_hot), load).displacement[0], s_cold.displacement[0] + closed_m);
}

TEST(ThermalClearance, OutOfRangeIsRefusedWithTheReason) {
  BearingConfig c = ct_bearing();  // 1111 mm pitch circle: 5.2 um per K along the contact line
  c.ring_temperature_difference_K = 120.0;
  try {
    BearingModel m(c);
    ADD_FAILURE() << "no error for " << m.clearance_m() * 1e6 << " um";
  } catch (const InvalidInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("120 K"), std::string::npos) << what;
    EXPECT_NE(what.find("interference"), std::string::npos) << what;
    EXPECT_NE(what.find("5 % of the ball diameter"), std::string::npos) << what;
  }
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 151.0}) {
    c.ring_temperature_difference_K = bad;
    EXPECT_THROW(operating_clearance_m(c), InvalidInputError) << bad;
  }
  c.ring_temperature_difference_K = 10.0;  // 52 um of preload: in range
  EXPECT_NEAR(BearingModel(c).clearance_m(), -11.5e-6 * 10.0 * 0.5555 * std::cos(35.0 * kPi / 180.0), 1e-12);
}
