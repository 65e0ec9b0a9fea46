// Sweeps (core/sweep.hpp): the results of a small sweep move the way physics demands,
// parallel runs give the serial results, and bad definitions are clear errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/sweep.hpp"

namespace bearing_sim {
namespace {

const std::string kBearings = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings";

SweepDefinition parse(const std::string& yaml) { return sweep_definition_from_string(yaml, "<test>", kBearings); }

std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(Sweep, StiffnessRisesWithLoadAndWithPreload) {
  const auto def = parse(R"(
bearing: ins_618_22_db.yaml
analysis: static
operating_point: {force_N: [0, 0, 0], moment_Nm: [0, 0]}
studies:
  - parameter: radial_load_N
    values: [300, 1000, 3400]
  - parameter: axial_load_N
    range: {from: 200, to: 1750, count: 3}
)");
  const auto r = run_sweep(def, 2);
  ASSERT_EQ(r.size(), 6u);
  for (const auto& x : r) ASSERT_TRUE(x.ok) << x.error;
  EXPECT_LT(r[0].statics.stiffness(0, 0), r[1].statics.stiffness(0, 0));
  EXPECT_LT(r[1].statics.stiffness(0, 0), r[2].statics.stiffness(0, 0));
  EXPECT_LT(r[3].statics.stiffness(2, 2), r[4].statics.stiffness(2, 2));
  EXPECT_LT(r[4].statics.stiffness(2, 2), r[5].statics.stiffness(2, 2));

  const auto pre = parse(R"(
bearing: ins_618_22_db.yaml
analysis: static
operating_point: {force_N: [200, 0, 0]}
parameter: clearance_um
values: [0, -1, -2, -4]
)");
  // At a light load, where preload matters (at the allowable 3400 N the larger loaded contact
  // angle of a preloaded pair even lowers Kxx by a fraction of a percent: docs/validation.md).
  const auto p = run_sweep(pre, 1);
  for (std::size_t i = 1; i < p.size(); ++i) {
    ASSERT_TRUE(p[i].ok) << p[i].error;
    EXPECT_GT(p[i].statics.stiffness(0, 0), p[i - 1].statics.stiffness(0, 0)) << "clearance " << p[i].c.value;
    EXPECT_GT(p[i].statics.stiffness(2, 2), p[i - 1].statics.stiffness(2, 2)) << "clearance " << p[i].c.value;
  }
}

TEST(Sweep, DynamicSweepInParallelEqualsSerialAndWavinessRaisesTheLevel) {
  const auto def = parse(R"(
bearing: ct_gantry_lyc.yaml
operating_point: {force_N: [6800, 0, 0], moment_Nm: [0, 2100], speed_rpm: 180, duration_s: 0.06}
imperfection_sets:
  - {name: smooth, imperfections: null}
  - name: wavy
    imperfections:
      waviness:
        - {surface: inner_race, order: Z-1, amplitude_um: 0.1}
        - {surface: inner_race, order: Z+1, amplitude_um: 0.1}
studies:
  - parameter: groove_curvature
    values: [0.52, 0.554]
  - parameter: balls_per_row
    values: [190]
)");
  const auto cases = sweep_cases(def);
  ASSERT_EQ(cases.size(), 6u);
  // Z-1 and Z+1 follow balls_per_row.
  EXPECT_EQ(cases[5].config.imperfections.waviness[0].order, 189);
  EXPECT_EQ(cases[5].config.imperfections.waviness[1].order, 191);
  EXPECT_EQ(cases[2].config.imperfections.waviness[0].order, 206);
  const auto serial = run_sweep(def, 1);
  const auto parallel = run_sweep(def, 3);
  ASSERT_EQ(serial.size(), parallel.size());
  for (std::size_t i = 0; i < serial.size(); ++i) {
    ASSERT_TRUE(serial[i].ok) << serial[i].error;
    ASSERT_TRUE(serial[i].dynamic);
    EXPECT_EQ(serial[i].dynamics.a_rms_x, parallel[i].dynamics.a_rms_x) << "case " << i;
    EXPECT_EQ(serial[i].statics.stiffness, parallel[i].statics.stiffness);
  }
  // The ring's modes on its contacts: ascending, and above the ball-pass frequency here.
  for (const auto& r : serial) {
    EXPECT_GT(r.ring_modes_hz[0], 313.0);
    for (int i = 1; i < 5; ++i) EXPECT_GE(r.ring_modes_hz[i], r.ring_modes_hz[i - 1]);
  }
  // Tighter grooves: stiffer. Waviness at Z +- 1: far above the smooth bearing's level.
  EXPECT_GT(serial[0].statics.stiffness(0, 0), serial[1].statics.stiffness(0, 0));
  EXPECT_LT(serial[0].dynamics.level_db, 0.0);
  EXPECT_GT(serial[2].dynamics.level_db, serial[0].dynamics.level_db + 30.0);
  // The CSV row has every header column.
  const auto count = [](const std::string& s) { return std::count(s.begin(), s.end(), ','); };
  EXPECT_EQ(count(sweep_csv_row(serial[0])), count(sweep_csv_header()));
}

TEST(Sweep, BadDefinitionsAreClearErrors) {
  EXPECT_NE(error_of("bearing: ct_gantry_lyc.yaml\nparameter: groove_curvatur\nvalues: [0.52]\n")
                .find("unknown parameter 'groove_curvatur'"),
            std::string::npos);
  EXPECT_NE(error_of("bearing: nope.yaml\nparameter: clearance_um\nvalues: [1]\n").find("key 'bearing'"),
            std::string::npos);
  const std::string bad_value =
      error_of("bearing: ct_gantry_lyc.yaml\nparameter: inner_groove_curvature\nvalues: [0.52, 0.49]\n");
  EXPECT_NE(bad_value.find("inner_groove_curvature = 0.49"), std::string::npos) << bad_value;
  EXPECT_NE(error_of("bearing: ct_gantry_lyc.yaml\nparameter: clearance_um\n").find("values"), std::string::npos);
  EXPECT_NE(error_of("bearing: ct_gantry_lyc.yaml\nparameter: clearance_um\nvalues: [1]\nspeed: 3\n")
                .find("key 'speed': unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("bearing: ct_gantry_lyc.yaml\nparameter: balls_per_row\nvalues: [200.5]\n").find("integer"),
            std::string::npos);
  EXPECT_NE(error_of("bearing: ct_gantry_lyc.yaml\nimperfections: {waviness: [{surface: inner_race, order: Q+1, "
                     "amplitude_um: 0.1}]}\nparameter: clearance_um\nvalues: [1]\n")
                .find("order 'Q+1'"),
            std::string::npos);
  EXPECT_THROW(load_sweep_definition("/nonexistent/sweep.yaml"), InvalidInputError);
}

TEST(Sweep, ASpeedBeyondTheBearingsLimitIsRefusedBeforeAnyCaseRuns) {
  // 1e12 rpm ran and gave a number; the CT bearing's limit is ~8,600 rpm (500 m/s at dm 1111 mm).
  std::string why;
  try {
    sweep_cases(
        parse("bearing: ct_gantry_lyc.yaml\noperating_point: {force_N: [6800, 0, 0], duration_s: 0.01}\n"
              "parameter: speed_rpm\nvalues: [180, 1e12]\n"));
  } catch (const InvalidInputError& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("speed_rpm 1e+12"), std::string::npos) << why;
  EXPECT_NE(why.find("is beyond +-900.1 rad/s (8595 rpm)"), std::string::npos) << why;
  EXPECT_EQ(sweep_cases(parse("bearing: ct_gantry_lyc.yaml\noperating_point: {force_N: [6800, 0, 0]}\n"
                              "parameter: speed_rpm\nvalues: [180, 8500]\n"))
                .size(),
            2u);
}

TEST(Sweep, ALoadTheBearingCannotCarryIsReportedPerCase) {
  const auto def = parse(R"(
bearing: ins_618_22_db.yaml
analysis: static
parameter: axial_load_N
values: [100, 1.0e7]
)");
  const auto r = run_sweep(def, 2);
  EXPECT_TRUE(r[0].ok);
  EXPECT_FALSE(r[1].ok);
  EXPECT_NE(r[1].error.find("cannot carry"), std::string::npos) << r[1].error;
}

}  // namespace
}  // namespace bearing_sim
