// Cage, ball-pass and ball-spin frequencies (docs/model.md section 8.1).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

TEST(Frequencies, Bearing6205PublishedMultipliers) {
  // 6205-2RS JEM SKF (the Case Western Reserve bearing data set): Z = 9, d = 7.94 mm,
  // dm = 39.04 mm; published multipliers of the shaft (inner ring) speed: BPFO 3.5848,
  // BPFI 5.4152, FTF 0.39828, BSF 4.7135 (= 2 x ball spin, two race impacts per turn).
  const BearingModel model(single_row(9, 7.94, 39.04, 0.0, 0.52, 0.52, 0.0, "rotating_ring: inner\n"));
  const double shaft_hz = 29.95;  // 1797 rpm
  const BearingFrequencies f = bearing_frequencies(model, 2.0 * kPi * shaft_hz);
  // The multipliers are published to 5 digits: 0.1% is the brief's tolerance and ~10x their rounding.
  EXPECT_NEAR(f.ball_pass_outer_race_hz / shaft_hz, 3.5848, 1e-3 * 3.5848);
  EXPECT_NEAR(f.ball_pass_inner_race_hz / shaft_hz, 5.4152, 1e-3 * 5.4152);
  EXPECT_NEAR(f.cage_hz / shaft_hz, 0.39828, 1e-3 * 0.39828);
  EXPECT_NEAR(2.0 * f.ball_spin_hz / shaft_hz, 4.7135, 1e-3 * 4.7135);
  EXPECT_NEAR(f.relative_ring_hz, shaft_hz, 1e-12 * shaft_hz);
  // Ring speeds in the load frame (the modulation of race defects): inner turns, outer stands.
  EXPECT_NEAR(f.inner_ring_hz, shaft_hz, 1e-12 * shaft_hz);
  EXPECT_EQ(f.outer_ring_hz, 0.0);
  // Conservation: BPFO + BPFI = Z f_r for any bearing (rounding only).
  EXPECT_NEAR(f.ball_pass_outer_race_hz + f.ball_pass_inner_race_hz, 9.0 * shaft_hz, 1e-12 * shaft_hz);
  // Outer ring fixed: the load zone is fixed to it, so the varying compliance is BPFO.
  EXPECT_NEAR(f.varying_compliance_hz, f.ball_pass_outer_race_hz, 1e-12 * shaft_hz);
}

TEST(Frequencies, CtBearingOuterRingAt180Rpm) {
  const BearingModel model(ct_bearing());
  const BearingFrequencies f = bearing_frequencies(model, kCtSpeedRadS);
  // docs/model.md section 8.1: cage about 1.513 Hz, varying compliance about 313 Hz.
  // Hand: gamma = 12 cos 35 / 1111 = 0.008848; f_c = 3 (1 + gamma)/2 = 1.51327 Hz;
  // 207 f_c = 313.25 Hz. 0.1% covers the three-digit rounding of the MODEL values.
  EXPECT_NEAR(f.cage_hz, 1.513, 1e-3 * 1.513);
  EXPECT_NEAR(f.varying_compliance_hz, 313.25, 1e-3 * 313.25);
  EXPECT_NEAR(f.varying_compliance_hz, 207.0 * f.cage_hz, 1e-12 * f.varying_compliance_hz);
  // Inner ring fixed: the balls pass it at Z f_c = BPFI, and BPFO = Z (f_o - f_c).
  EXPECT_NEAR(f.ball_pass_inner_race_hz, f.varying_compliance_hz, 1e-9);
  EXPECT_NEAR(f.ball_pass_outer_race_hz, 207.0 * (3.0 - f.cage_hz), 1e-9);
  EXPECT_NEAR(f.relative_ring_hz, 3.0, 1e-12);
  EXPECT_EQ(f.inner_ring_hz, 0.0);
  EXPECT_NEAR(f.outer_ring_hz, 3.0, 1e-12);
}

TEST(Frequencies, CageSpeedIsLinearInRingSpeeds) {
  // Rolling without slip: both rings at the same speed carry the cage with them.
  const BearingModel model(ct_bearing());
  EXPECT_NEAR(model.cage_speed_rad_s(10.0, 10.0), 10.0, 1e-12);
  const BearingFrequencies f = bearing_frequencies(model, 10.0, 10.0);
  EXPECT_NEAR(f.ball_pass_outer_race_hz, 0.0, 1e-12);
  EXPECT_NEAR(f.ball_pass_inner_race_hz, 0.0, 1e-12);
  EXPECT_NEAR(f.ball_spin_hz, 0.0, 1e-12);
}

// A speed that is not a number has no frequencies: refused, naming the speeds (a NaN would
// otherwise make every fault line NaN and every analysis "healthy").
TEST(Frequencies, NonFiniteSpeedIsRefused) {
  const BearingModel model(ct_bearing());
  EXPECT_THROW(bearing_frequencies(model, std::nan("")), InvalidInputError);
  EXPECT_THROW(bearing_frequencies(model, 1.0, std::numeric_limits<double>::infinity()), InvalidInputError);
  try {
    bearing_frequencies(model, std::nan(""), 0.0);
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos) << e.what();
  }
}

// One physical speed limit for every front: the pitch circle at kMaxPitchLineSpeedMPerS.
// 1e300 rpm and sweeps over 1e12 rpm ran and printed a number.
TEST(Frequencies, ASpeedBeyondThePitchLineLimitIsRefusedNamingItAndTheLimit) {
  const BearingModel model(ct_bearing());
  const double dm = model.config().pitch_diameter_m, limit = max_ring_speed_rad_s(dm);
  EXPECT_DOUBLE_EQ(limit * 0.5 * dm, kMaxPitchLineSpeedMPerS);
  EXPECT_NEAR(max_ring_speed_rad_s(0.03904), 25615.0, 1.0);  // the 6205: 244,600 rpm
  std::string why;
  try {
    bearing_frequencies(model, 0.0, 1e300 * 2.0 * kPi / 60.0);
  } catch (const InvalidInputError& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("outer ring speed: 1.047e+299 rad/s (1e+300 rpm) is beyond +-"), std::string::npos) << why;
  EXPECT_NE(why.find("500 m/s"), std::string::npos) << why;
  // The limit itself is a speed; just beyond it is not, in either direction and in the dynamics.
  EXPECT_NO_THROW(bearing_frequencies(model, -limit, limit));
  EXPECT_THROW(bearing_frequencies(model, -1.001 * limit, 0.0), InvalidInputError);
  EXPECT_THROW(BearingDynamics(model, Vector5::Zero(), 1e12 * 2.0 * kPi / 60.0), InvalidInputError);
  EXPECT_TRUE(ring_speed_refusal(limit, dm).empty());
  EXPECT_FALSE(ring_speed_refusal(std::nan(""), dm).empty());
}
