// Per-row raceways (docs/model.md section 9.1): a race spall is on one row's raceway and gives
// that row's signature, radial plus axial and tilt; waviness and roughness given for one row
// change only that row's balls; row indices that the bearing does not have are rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

// The INS 618/22 DB pair (back-to-back, 2 x 10 balls, rows 7 mm apart, outer ring moving),
// with extra keys appended to its file.
BearingConfig ins_pair(const std::string& extra = "") {
  return bearing_config_from_string(test::read_text(test::bearing_file("ins_618_22_db.yaml")) + extra, "ins.yaml");
}

// Every ball's imperfection offset at a phase.
std::vector<double> offsets_at(const BearingModel& model, const RollingPhase& phase) {
  std::vector<double> offsets(model.ball_count(), 0.0);
  model.imperfections().add_offsets(phase, offsets.data());
  return offsets;
}

// Change of the contact force on the moving ring when spalls are added, at a fixed
// displacement q and cage angle 0.
Vector5 force_change(const BearingConfig& config, const Vector5& q, const std::vector<Spall>& spalls) {
  BearingModel model(config);
  const Vector5 zero = Vector5::Zero();
  const Vector5 healthy = model.contact_force(q, zero, RollingPhase{}, model.balls());
  for (const Spall& s : spalls) model.add_spall(s);
  return model.contact_force(q, zero, RollingPhase{}, model.balls()) - healthy;
}

TEST(RowSpall, OneRowGivesAxialForceAndTiltThatTwoRowsInPhaseCancel) {
  const BearingConfig config = ins_pair();
  const BearingModel model(config);
  // Radial equilibrium under 500 N along x: z and the tilts are zero by the pair's mirror
  // symmetry, so the two rows carry mirror-image loads.
  const StaticSolution s = solve_static(model, test::load5(500.0, 0, 0, 0, 0));
  ASSERT_LT(s.displacement.tail<3>().cwiseAbs().maxCoeff(), 1e-12);
  int loaded = 0;  // the most loaded ball of row 0 (balls are row-major)
  for (int b = 0; b < config.balls_per_row; ++b)
    if (s.balls[b].load_N > s.balls[loaded].load_N) loaded = b;
  const BallState& ball = s.balls[loaded];
  ASSERT_GT(ball.load_N, 50.0);
  // 1 mm x 20 um on the outer race under that ball (outer ring angle 0: race frame = bearing
  // frame). The ball's deflection is a few um, so it loses its whole load; its neighbours are
  // 36 deg away, the spall 3.7 deg wide.
  Spall spall{Surface::OuterRace, ball.azimuth_rad, 0, 1e-3, 20e-6};
  ASSERT_LT(ball.deflection_m, 20e-6);
  const Vector5 one_row = force_change(config, s.displacement, {spall});
  Spall other = spall;
  other.row = 1;
  const Vector5 both_rows = force_change(config, s.displacement, {spall, other});

  // One row: the force of the lost ball, -s Q e with its loaded contact normal e, and its
  // moment -s Q (P_o x e) about the centre, P_o its outer-groove centre (section 3.4).
  const double q_load = ball.load_N, sign = model.moving_sign();
  const Eigen::Vector3d e = ball.normal;
  const double d = config.ball_diameter_m, a0 = config.contact_angle_rad;
  const double c0 = model.row_contact_sign(0);
  const double rho = config.pitch_diameter_m / 2.0 - (config.outer_groove_curvature - 0.5) * d * std::cos(a0);
  const Eigen::Vector3d p(
      rho * std::cos(ball.azimuth_rad), rho * std::sin(ball.azimuth_rad),
      model.row_axial_position_m(0) - (config.outer_groove_curvature - 0.5) * d * c0 * std::sin(a0));
  const Eigen::Vector3d force = -sign * q_load * e, moment = -sign * q_load * p.cross(e);
  const double scale = q_load;  // rounding of sums of a few loads of this size
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(one_row[i], force[i], 1e-9 * scale) << "force " << i;
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(one_row[3 + i], moment[i], 1e-9 * scale * p.norm()) << "moment " << i;
  // Back-to-back, row 0 at z > 0 has c_0 = -1: its contact line leans to -z from the inner to
  // the outer race, so losing it leaves the outer ring pushed to +z (s = +1): Fz = Q sin(a) > 0,
  // with the loaded contact angle a of the ball; Fz / Fx = e_z / e_x = -tan(a) / cos(phi).
  ASSERT_EQ(c0, -1.0);
  EXPECT_NEAR(one_row[2], q_load * std::sin(ball.contact_angle_rad), 1e-9 * scale);
  EXPECT_NEAR(one_row[2] / one_row[0], -std::tan(ball.contact_angle_rad) / std::cos(ball.azimuth_rad), 1e-9);
  // And it is not small: the axial force is a sizeable fraction of the radial one
  // (tan 10 deg = 0.18 at the nominal angle), the tilt moment that of the force on a lever of
  // millimetres.
  EXPECT_GT(std::abs(one_row[2]), 0.1 * std::abs(one_row[0]));
  EXPECT_GT(one_row.tail<2>().norm(), 1e-3 * std::abs(one_row[0]));

  // Both rows in phase: the mirror-image ball of row 1 is lost too. Its axial force and
  // moment are those of row 0's with the opposite sign: they cancel; the radial part doubles.
  EXPECT_NEAR(both_rows[0], 2.0 * one_row[0], 1e-9 * scale);
  EXPECT_NEAR(both_rows[1], 2.0 * one_row[1], 1e-9 * scale);
  EXPECT_LT(std::abs(both_rows[2]), 1e-9 * scale);
  EXPECT_LT(both_rows.tail<2>().norm(), 1e-9 * scale * p.norm());
}

TEST(RowSpall, OneRowSpallMakesTheRingVibrateAxiallyAndTwoRowsInPhaseDoNot) {
  // The dynamic signature: the outer ring at 600 rpm under 500 N radial runs over a spall on
  // row 0, or on both rows in phase. The mirror-symmetric pair has no axial or tilt motion
  // unless the two rows differ.
  const auto axial_and_radial = [](const std::vector<int>& rows) {
    BearingModel model(ins_pair());
    for (int row : rows) {
      Spall s{Surface::OuterRace, kPi, 0, 1e-3, 20e-6};
      s.row = row;
      model.add_spall(s);
    }
    BearingDynamics dynamics(model, test::load5(500.0, 0, 0, 0, 0), 600.0 * 2.0 * kPi / 60.0,
                             DynamicsOptions{20000.0, 0});
    double peak_z = 0.0, peak_x = 0.0, peak_tilt = 0.0;
    for (int i = 0; i < 4000; ++i) {  // 0.2 s: two turns of the outer ring
      const DynamicSample s = dynamics.step();
      peak_x = std::max(peak_x, std::abs(s.acceleration[0]));
      peak_z = std::max(peak_z, std::abs(s.acceleration[2]));
      peak_tilt = std::max(peak_tilt, s.acceleration.tail<2>().norm());
    }
    return std::array<double, 3>{peak_x, peak_z, peak_tilt};
  };
  const std::array<double, 3> one = axial_and_radial({0}), both = axial_and_radial({0, 1});
  // Both runs see impacts; one row's carry an axial part of the order of tan(a) of the
  // radial one (> 5 %), the two rows' in-phase axial acceleration is rounding
  // (< 1e-6 of the radial).
  EXPECT_GT(one[0], 0.0);
  EXPECT_GT(one[1], 0.05 * one[0]);
  EXPECT_GT(one[2], 0.0);
  EXPECT_LT(both[1], 1e-6 * both[0]);
  EXPECT_LT(both[2], 1e-6 * one[2]);
}

TEST(RowWaviness, AHarmonicOfOneRowChangesOnlyThatRowsBalls) {
  // Inner race, 3 lobes, 0.5 um, phase 30 deg, on row 1 only; and the same on every row.
  const std::string harmonic = "{surface: inner_race, order: 3, amplitude_um: 0.5, phase_deg: 30";
  const BearingModel one_row(ins_pair("imperfections:\n  waviness:\n    - " + harmonic + ", row: 1}\n"));
  const BearingModel every_row(ins_pair("imperfections:\n  waviness:\n    - " + harmonic + "}\n"));
  RollingPhase phase;
  phase.cage = 0.3;
  phase.inner_ring = 1.1;
  const int n = one_row.ball_count(), z = one_row.balls_per_row();
  const std::vector<double> a = offsets_at(one_row, phase), b = offsets_at(every_row, phase);
  for (int ball = 0; ball < n; ++ball) {
    // Closed form a cos(q theta + p), theta = base + cage - ring (section 9.2).
    const double theta = one_row.base_azimuth_rad(ball) + phase.cage - phase.inner_ring;
    const double expected = 0.5e-6 * std::cos(3.0 * theta + kPi / 6.0);
    EXPECT_NEAR(b[ball], expected, 1e-15) << "ball " << ball;
    if (ball < z) EXPECT_EQ(a[ball], 0.0) << "row 0 ball " << ball;
    else EXPECT_NEAR(a[ball], expected, 1e-15) << "row 1 ball " << ball;
  }
}

TEST(RowRoughness, RoughnessOfOneRowIsTheSameProfileOnThatRowAndNothingOnTheOther) {
  const BearingModel one_row(ins_pair("imperfections:\n  seed: 3\n  roughness_rms_um: 0.05\n  roughness_row: 0\n"));
  const BearingModel every_row(ins_pair("imperfections:\n  seed: 3\n  roughness_rms_um: 0.05\n"));
  RollingPhase phase;
  phase.cage = 0.7;
  phase.outer_ring = 2.0;
  const int z = one_row.balls_per_row();
  const std::vector<double> a = offsets_at(one_row, phase), b = offsets_at(every_row, phase);
  double rms = 0.0;
  for (int ball = 0; ball < z; ++ball) {
    EXPECT_EQ(a[ball], b[ball]) << "row 0 ball " << ball;  // same seed: the same profile
    EXPECT_EQ(a[z + ball], 0.0) << "row 1 ball " << ball;
    rms += b[ball] * b[ball] / z;
  }
  // The profile is really there (two races of 0.05 um RMS each at 10 points).
  EXPECT_GT(std::sqrt(rms), 0.01e-6);
}

void expect_row_error(const std::string& file_text, const std::string& key) {
  test::expect_config_error([&] { bearing_config_from_string(file_text, "rows.yaml"); }, {"rows.yaml", "'" + key + "'"},
                            key);
}

TEST(RowKeys, RowsTheBearingDoesNotHaveAreRejectedWithFileAndKey) {
  const std::string ins = test::read_text(test::bearing_file("ins_618_22_db.yaml"));
  const std::string single = test::read_text(test::bearing_file("deep_groove_6205.yaml"));
  expect_row_error(ins + "defects:\n  - {surface: outer_race, width_mm: 1, depth_um: 10, row: 2}\n", "defects[0].row");
  expect_row_error(single + "defects:\n  - {surface: inner_race, width_mm: 1, depth_um: 10, row: 1}\n",
                   "defects[0].row");
  expect_row_error(ins + "defects:\n  - {surface: ball, ball: 12, width_mm: 0.5, depth_um: 10, row: 1}\n",
                   "defects[0].row");
  expect_row_error(
      ins + "imperfections:\n  waviness:\n    - {surface: outer_race, order: 4, amplitude_um: 0.1, row: -1}\n",
      "imperfections.waviness[0].row");
  expect_row_error(single + "imperfections:\n  roughness_rms_um: 0.05\n  roughness_row: 1\n",
                   "imperfections.roughness_row");
  // Row 1 of the pair is fine, and a race spall without `row` is on row 0.
  const BearingConfig ok = ins_pair(
      "defects:\n  - {surface: outer_race, width_mm: 1, depth_um: 10, row: 1}\n"
      "  - {surface: inner_race, width_mm: 1, depth_um: 10}\n");
  ASSERT_EQ(ok.imperfections.spalls.size(), 2u);
  EXPECT_EQ(ok.imperfections.spalls[0].row, 1);
  EXPECT_EQ(ok.imperfections.spalls[1].row, 0);
  // At run time (node service, scenario player): the core's check.
  BearingModel model(ok);
  Spall bad{Surface::OuterRace, 0.0, 0, 1e-3, 10e-6};
  bad.row = 2;
  EXPECT_THROW(model.add_spall(bad), InvalidInputError);
}

TEST(RowKeys, ScenarioSpallEventsTakeARow) {
  const std::string head =
      "name: rows\nduration_s: 10\nbearing_file: " + test::bearing_file("ins_618_22_db.yaml") + "\ndefects:\n";
  const Scenario sc =
      Scenario::from_string(head +
                                "  - {type: spall, at_s: 1, surface: outer_race, width_mm: 1, depth_um: 10, row: 1}\n"
                                "  - {type: spall, at_s: 2, surface: inner_race, width_mm: 1, depth_um: 10}\n",
                            "rows_scenario.yaml");
  ASSERT_EQ(sc.defect_events().size(), 2u);
  EXPECT_EQ(sc.defect_events()[0].spall.row, 1);
  EXPECT_EQ(sc.defect_events()[1].spall.row, 0);
  try {
    Scenario::from_string(head + "  - {type: spall, at_s: 1, surface: outer_race, width_mm: 1, depth_um: 10, row: 2}\n",
                          "rows_scenario.yaml");
    ADD_FAILURE() << "row 2 of a two-row bearing accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'defects[0].row'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bearing_sim
