// The public datasets' bearing files (config/bearings): their characteristic frequencies
// against the figures each dataset's reference publishes. The tolerance of each check is the
// rounding of the published figure (or of the geometry it came from), so a wrong ball count,
// diameter or contact angle in a file fails.
#include <gtest/gtest.h>

#include <string>

#include "bearing_sim/core/frequencies.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {

// Frequencies of a shipped bearing file with its rotating ring (inner, in every dataset) at rpm.
BearingFrequencies at_rpm(const std::string& file, double rpm) {
  const BearingModel model(load_bearing_config(bearing_file(file)));
  EXPECT_EQ(model.config().rotating_ring, RotatingRing::Inner) << file;
  return bearing_frequencies(model, rpm * 2.0 * kPi / 60.0);
}

// The CWRU page gives its geometry to 4 significant digits (pitch 1.537 in: +-0.0005 in,
// 3.3e-4 relative) and its multipliers to 5; computed from that geometry they agree with the
// page to 1.6e-4 at worst (fan-end FTF, 0.38164 against 0.3817). 3e-4 relative: the rounding
// of the page's pitch diameter, the coarser of its inputs.
constexpr double kCwruRelative = 3e-4;

// CWRU's "rolling element" multiplier is twice the ball spin frequency (a ball defect strikes
// the inner and the outer race once each per spin turn): D/d (1 - gamma^2), not D/(2d) (...).
void expect_cwru_multipliers(const std::string& file, double bpfi, double bpfo, double ftf, double rolling_element) {
  SCOPED_TRACE(file);
  const double rpm = 1797.0, shaft_hz = rpm / 60.0;
  const BearingFrequencies f = at_rpm(file, rpm);
  EXPECT_NEAR(f.ball_pass_inner_race_hz / shaft_hz, bpfi, kCwruRelative * bpfi);
  EXPECT_NEAR(f.ball_pass_outer_race_hz / shaft_hz, bpfo, kCwruRelative * bpfo);
  EXPECT_NEAR(f.cage_hz / shaft_hz, ftf, kCwruRelative * ftf);
  EXPECT_NEAR(2.0 * f.ball_spin_hz / shaft_hz, rolling_element, kCwruRelative * rolling_element);
}

}  // namespace

TEST(DatasetFrequencies, CwruDriveEnd6205) {
  // CWRU Bearing Data Center, bearing specification page, 6205-2RS JEM SKF (drive end).
  expect_cwru_multipliers("cwru_6205_drive_end.yaml", 5.4152, 3.5848, 0.39828, 4.7135);
}

TEST(DatasetFrequencies, CwruFanEnd6203) {
  // Same page, 6203-2RS JEM SKF (fan end).
  expect_cwru_multipliers("cwru_6203_fan_end.yaml", 4.9469, 3.0530, 0.3817, 3.9874);
}

TEST(DatasetFrequencies, ImsRexnordZa2115At2000Rpm) {
  // Qiu et al., J. Sound Vib. 289 (2006), the IMS set's bearing at 2000 rpm: BPFO 236.4 Hz,
  // BPFI 296.9 Hz, BSF 139.9 Hz, FTF 14.8 Hz. Their BSF is the ball spin frequency itself,
  // D/(2d) (1 - gamma^2) f_r. Given to 0.1 Hz: +-0.05 Hz. Ball passes count one row (16).
  const BearingFrequencies f = at_rpm("ims_rexnord_za2115.yaml", 2000.0);
  EXPECT_NEAR(f.ball_pass_outer_race_hz, 236.4, 0.05);
  EXPECT_NEAR(f.ball_pass_inner_race_hz, 296.9, 0.05);
  EXPECT_NEAR(f.ball_spin_hz, 139.9, 0.05);
  EXPECT_NEAR(f.cage_hz, 14.8, 0.05);
}

TEST(DatasetFrequencies, XjtuSyUer204AtCondition1) {
  // XJTU-SY operating condition 1, 2100 rpm (35 Hz), as the set's tutorial (Lei et al., 2019)
  // tabulates for the LDK UER204: FTF 13.49 Hz, BPFO 107.91 Hz, BPFI 172.09 Hz, BSF 72.33 Hz
  // (BSF: the ball spin frequency). Given to 0.01 Hz: +-0.005 Hz.
  const BearingFrequencies f = at_rpm("xjtu_sy_ldk_uer204.yaml", 2100.0);
  EXPECT_NEAR(f.cage_hz, 13.49, 0.005);
  EXPECT_NEAR(f.ball_pass_outer_race_hz, 107.91, 0.005);
  EXPECT_NEAR(f.ball_pass_inner_race_hz, 172.09, 0.005);
  EXPECT_NEAR(f.ball_spin_hz, 72.33, 0.005);
}

TEST(DatasetFrequencies, Paderborn6203At1500Rpm) {
  // Lessmeier et al. 2016 publish the geometry (Z = 8, d = 6.75 mm, dm = 28.55 mm, 0 deg),
  // not the frequencies. By hand at 25 Hz, gamma = 6.75 / 28.55 = 0.236427:
  // BPFO = 4 x 25 (1 - gamma) = 76.3573 Hz, BPFI = 4 x 25 (1 + gamma) = 123.6427 Hz,
  // FTF = 12.5 (1 - gamma) = 9.5447 Hz, BSF = 28.55 / 13.5 x 25 (1 - gamma^2) = 49.9150 Hz.
  // Hand figures to 0.1 mHz: +-0.1 mHz.
  const BearingFrequencies f = at_rpm("paderborn_6203.yaml", 1500.0);
  EXPECT_NEAR(f.ball_pass_outer_race_hz, 76.3573, 1e-4);
  EXPECT_NEAR(f.ball_pass_inner_race_hz, 123.6427, 1e-4);
  EXPECT_NEAR(f.cage_hz, 9.5447, 1e-4);
  EXPECT_NEAR(f.ball_spin_hz, 49.9150, 1e-4);
}

TEST(DatasetFrequencies, PronostiaAt1800Rpm) {
  // Nectoux et al. 2012 publish no geometry; the file holds the commonly quoted one
  // (Z = 13, d = 3.5 mm, dm = 25.6 mm, 0 deg). By hand at 30 Hz, gamma = 3.5 / 25.6 =
  // 0.13671875 (exact in binary): BPFO = 6.5 x 30 (1 - gamma) = 168.33984375 Hz,
  // BPFI = 221.66015625 Hz, FTF = 15 (1 - gamma) = 12.94921875 Hz,
  // BSF = 25.6 / 7 x 30 (1 - gamma^2) = 107.663504 Hz. Exact but for rounding: 1e-9 relative.
  const BearingFrequencies f = at_rpm("pronostia_test_bearing.yaml", 1800.0);
  EXPECT_NEAR(f.ball_pass_outer_race_hz, 168.33984375, 1e-9 * 168.3);
  EXPECT_NEAR(f.ball_pass_inner_race_hz, 221.66015625, 1e-9 * 221.7);
  EXPECT_NEAR(f.cage_hz, 12.94921875, 1e-9 * 12.9);
  EXPECT_NEAR(f.ball_spin_hz, 107.663504, 1e-6);
}
