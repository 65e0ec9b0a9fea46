// ISO 281 life against hand calculations and catalogue ratings, the ISO/TS 16281-style
// reference life against ISO 281, and Palmgren-Miner damage against its closed form.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/bearing_life.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

BearingConfig bearing_6205() { return test::single_row(9, 7.94, 39.04, 0.0, 0.52, 0.52); }

TEST(Iso281, RatingOf6205ByHandAndCatalogue) {
  // D_w cos a / D_pw = 7.94 / 39.04 = 0.20338; ISO 281 Table 2 between 0.20 (59.9) and
  // 0.22 (59.6): f_c = 59.9 - (0.00338/0.02) * 0.3 = 59.849.
  const double fc = 59.9 - (7.94 / 39.04 - 0.20) / 0.02 * 0.3;
  EXPECT_NEAR(iso281_fc(7.94 / 39.04, false), fc, 1e-9);
  // C = b_m f_c (i cos a)^0.7 Z^(2/3) D_w^1.8 = 1.3 * 59.849 * 1 * 4.3267 * 41.656 = 14023 N.
  const double c_hand = 1.3 * 59.849 * 1.0 * 4.3267 * 41.656;
  const double c = basic_dynamic_load_rating_N(bearing_6205());
  EXPECT_NEAR(c, c_hand, 0.001 * c_hand);  // the hand factors are rounded to 5 digits
  // Catalogues (NSK, FAG) give C_r = 14.0 kN for a 6205 (d = 7.938 mm): within 1%.
  EXPECT_NEAR(c, 14000.0, 140.0);
  // A catalogue value in the life configuration wins over the geometry.
  LifeConfig given;
  given.dynamic_load_rating_N = 14800.0;
  EXPECT_EQ(basic_dynamic_load_rating_N(bearing_6205(), given), 14800.0);
}

TEST(Iso281, LifeOfPureRadialLoad) {
  // P = Fr = 2000 N: L10 = (14026/2000)^3 = 344.9 million revolutions; at 1800 rpm
  // 344.9e6 / (1800 * 60) = 3194 h.
  const BasicRatingLife l =
      basic_rating_life(bearing_6205(), test::load5(2000.0, 0.0, 0.0, 0.0, 0.0), 1800.0 * 2.0 * kPi / 60.0);
  EXPECT_DOUBLE_EQ(l.equivalent.X, 1.0);
  EXPECT_DOUBLE_EQ(l.equivalent.Y, 0.0);
  const double l10 = std::pow(l.dynamic_load_rating_N / 2000.0, 3.0);
  EXPECT_NEAR(l.life_million_rev, 344.9, 0.5);  // from C = 14026 N (hand value above)
  EXPECT_NEAR(l.life_hours, l10 * 1e6 / (1800.0 * 60.0), 1e-9 * l.life_hours);
}

TEST(Iso281, EquivalentLoadDeepGrooveCombined) {
  // Fr = 1000 N, Fa = 500 N: f0 Fa / C0r = Fa / (i Z D_w^2) = 500 / (9 * 63.04) = 0.8813 N/mm^2,
  // between 0.689 (e 0.26, Y 1.71) and 1.03 (e 0.28, Y 1.55): t = 0.5637,
  // e = 0.2713 < Fa/Fr = 0.5, so X = 0.56, Y = 1.71 - 0.5637 * 0.16 = 1.6198;
  // P = 0.56 * 1000 + 1.6198 * 500 = 1369.9 N.
  const EquivalentLoad p = equivalent_dynamic_load(bearing_6205(), 1000.0, 500.0);
  EXPECT_NEAR(p.e, 0.2713, 1e-4);
  EXPECT_DOUBLE_EQ(p.X, 0.56);
  EXPECT_NEAR(p.Y, 1.6198, 1e-4);
  EXPECT_NEAR(p.load_N, 1369.9, 0.1);
  // A small axial load (Fa/Fr <= e): P = Fr.
  EXPECT_DOUBLE_EQ(equivalent_dynamic_load(bearing_6205(), 1000.0, 100.0).load_N, 1000.0);
}

TEST(Iso281, DoubleRowAngularContactCtBearing) {
  const BearingConfig ct = test::ct_bearing();  // 2 x 207 balls, 12 mm, dm 1111 mm, 35 deg
  // Double row 35 deg, ISO 281 Table 3: e = 0.95; Fa/Fr <= e: P = Fr + 0.66 Fa;
  // otherwise P = 0.60 Fr + 1.07 Fa.
  EXPECT_NEAR(equivalent_dynamic_load(ct, 6800.0, 1000.0).load_N, 6800.0 + 0.66 * 1000.0, 1e-9);
  EXPECT_NEAR(equivalent_dynamic_load(ct, 1000.0, 6800.0).load_N, 0.60 * 1000.0 + 1.07 * 6800.0, 1e-9);
  // D_w cos a / D_pw = 12 cos35 / 1111 = 0.008848, below the table: 29.1 (0.8848)^0.3 = 28.05.
  const double ratio = 12.0 * std::cos(35.0 * kPi / 180.0) / 1111.0;
  const double fc = 29.1 * std::pow(ratio / 0.01, 0.3);
  EXPECT_NEAR(iso281_fc(ratio, false), fc, 1e-9);
  // The table's f_c holds up to groove radii 0.52 D_w / 0.53 D_w; the CT's 0.554 reduces it
  // by 0.7440 (GrooveRadiusFactor.WideGroovesOfTheCtBearing).
  // C = 1.3 f_c 0.7440 (2 cos35)^0.7 207^(2/3) 12^1.8 = 1.3 * 28.05 * 0.7440 * 1.4128 * 34.993 * 87.604 = 117.5 kN.
  const double c_hand = 1.3 * fc * 0.744034 * std::pow(2.0 * std::cos(35.0 * kPi / 180.0), 0.7) *
                        std::pow(207.0, 2.0 / 3.0) * std::pow(12.0, 1.8);
  EXPECT_NEAR(basic_dynamic_load_rating_N(ct), c_hand, 1e-6 * c_hand);
  EXPECT_NEAR(c_hand, 117.5e3, 0.1e3);  // the rounded product above
}

TEST(GrooveRadiusFactor, NoChangeAtOrBelowTheTableRadii) {
  // ISO 281 Table 2 assumes 0.52 (inner) and 0.53 (outer); tighter grooves do not raise C.
  EXPECT_DOUBLE_EQ(iso281_groove_radius_factor(test::single_row(9, 7.94, 39.04, 0.0, 0.52, 0.53)), 1.0);
  EXPECT_DOUBLE_EQ(iso281_groove_radius_factor(test::single_row(9, 7.94, 39.04, 0.0, 0.51, 0.515)), 1.0);
}

TEST(GrooveRadiusFactor, WideGroovesOfTheCtBearing) {
  // The closed form behind Table 2 (ISO/TR 1281-1): f_c ~ Q_ci [1 + (Q_ci/Q_ce)^(10/3)]^-0.3,
  // Q_ci ~ (2f_i/(2f_i - 1))^0.41 (1-g)^1.39 / (1+g)^(1/3), Q_ce ~ (2f_e/(2f_e - 1))^0.41 (1+g)^1.39 / (1-g)^(1/3).
  // CT: g = 12 cos35 / 1111 = 0.008848. At 0.52/0.53: Q_ci 3.7454, Q_ce 3.2956, ring 2.8345;
  // at 0.554/0.554: Q_ci 2.5581, Q_ce 2.6373, ring 2.1089; ratio 0.7440: the table's C
  // is 1.344 times too high for these grooves, the L10 = (C/P)^3 2.43 times.
  EXPECT_NEAR(iso281_groove_radius_factor(test::ct_bearing()), 0.74403, 2e-5);
  // Wider grooves, lower rating: the INS pair's 0.528 inner groove costs ~9 % at g = 0.1.
  const double ins_like = iso281_groove_radius_factor(test::single_row(20, 8.0, 80.0, 0.0, 0.528, 0.53));
  EXPECT_NEAR(ins_like, 0.91210, 2e-5);
  EXPECT_LT(iso281_groove_radius_factor(test::single_row(20, 8.0, 80.0, 0.0, 0.56, 0.53)), ins_like);
}

TEST(ReferenceLife, UniformBallLoadsByHand) {
  // Pure axial load on a deep groove bearing: every ball carries the same Q, so
  // Q_e = Q for both races whatever the exponent, and L_k = (Q_c,k / Q)^3.
  const BearingModel model(bearing_6205());
  std::vector<BallState> balls(9);
  for (int j = 0; j < 9; ++j) {
    balls[j].index_in_row = j;
    balls[j].load_N = 300.0;
  }
  const ReferenceLife r = reference_life(model, balls);
  ASSERT_EQ(r.races.size(), 2u);
  // Q_c by hand, D_w = 7.94 mm, g = 0.20338, f = 0.52: 98.1 * 0.95 * 1.3 = 121.15;
  // (1.04/0.04)^0.41 = 3.8031; (1-g)^1.39/(1+g)^(1/3) = 0.72902/1.06366 = 0.68539 (inner),
  // (1+g)^1.39/(1-g)^(1/3) = 1.29348/0.92701 = 1.39533 (outer); (7.94/39.04)^0.3 = 0.62014;
  // 7.94^1.8 = 41.656; 9^(-1/3) = 0.48075.
  const double common = 121.15 * 3.8031 * 0.62014 * 41.656 * 0.48075;
  const double qci = common * 0.68539, qce = common * 1.39533;
  EXPECT_NEAR(r.races[0].contact_rating_N, qci, 0.001 * qci);  // 5-digit hand factors
  EXPECT_NEAR(r.races[1].contact_rating_N, qce, 0.001 * qce);
  // test::single_row leaves rotating_ring at its default, outer: the outer race turns
  // relative to the fixed load, the inner race does not.
  EXPECT_FALSE(r.races[0].rotating_relative_to_load);
  EXPECT_TRUE(r.races[1].rotating_relative_to_load);
  const double li = std::pow(qci / 300.0, 3.0), le = std::pow(qce / 300.0, 3.0);
  // Combined with the Weibull slope e = 10/9: L = (Li^-e + Le^-e)^(-1/e).
  const double e = 10.0 / 9.0;
  EXPECT_NEAR(r.life_million_rev, std::pow(std::pow(li, -e) + std::pow(le, -e), -1.0 / e), 0.004 * r.life_million_rev);
}

TEST(ReferenceLife, AgreesWithIso281ForRadialLoad) {
  // With many balls, zero clearance and pure radial load the Lundberg-Palmgren ball-load
  // route and ISO 281 rest on the same theory (C_i = 0.407 Q_ci Z cos a). A 20-ball bearing
  // with D_w/D_pw = 0.1 and the groove curvatures ISO 281 assumes (0.52 inner, 0.53 outer).
  const BearingConfig b = test::single_row(20, 8.0, 80.0, 0.0, 0.52, 0.53);
  const BearingModel model(b);
  const double fr = 3000.0;
  double mean_life = 0.0;
  constexpr int kPhases = 8;  // over one ball pitch: the discrete ball positions average out
  for (int k = 0; k < kPhases; ++k) {
    const StaticSolution s = solve_static(model, test::load5(fr, 0.0, 0.0, 0.0, 0.0), 2.0 * kPi / 20.0 * k / kPhases);
    mean_life += reference_life(model, s.balls).life_million_rev / kPhases;
  }
  const double iso = std::pow(basic_dynamic_load_rating_N(b) / fr, 3.0);
  // The closed form behind ISO 281 Table 2 (ISO/TR 1281-1, lambda = 0.95) at g = 0.1,
  // fi = 0.52, fe = 0.53: f_c = 37.91 [1 + (1.04 (0.9/1.1)^1.72 (0.52*0.06/(0.53*0.04))^0.41)^(10/3)]^-0.3
  //   x 0.1^0.3 0.9^1.39 / 1.1^(1/3) x (1.04/0.04)^0.41 = 37.91 x 0.8666 x 1.5949 = 52.40,
  // against 55.5 in the table: the ball-load route should give (52.40/55.5)^3 = 0.841 of the
  // table's L10. 0.04: the computed (8-phase mean) load distribution against Stribeck's
  // continuous one, a few percent in the cubed loads.
  EXPECT_NEAR(mean_life / iso, 0.841, 0.04);
}

TEST(MinerDamage, TwoLevelHistory) {
  const double c = 14000.0;
  // Level 1: P = 2000 N at 1800 rpm for 100 h; level 2: P = 4000 N at 3000 rpm for 20 h.
  // L1 = (14000/2000)^3 = 343 Mrev = 343e6 / (1800*60) h = 3175.9 h;
  // L2 = (14000/4000)^3 = 42.875 Mrev = 42.875e6 / (3000*60) h = 238.19 h.
  const double l1_h = 343e6 / (1800.0 * 60.0), l2_h = 42.875e6 / (3000.0 * 60.0);
  const double d_expected = 100.0 / l1_h + 20.0 / l2_h;  // 0.031487 + 0.083965 = 0.115452
  MinerDamage m;
  const double w1 = 1800.0 * 2.0 * kPi / 60.0, w2 = -3000.0 * 2.0 * kPi / 60.0;  // sign ignored
  const double life1 = rating_life_million_rev(c, 2000.0), life2 = rating_life_million_rev(c, 4000.0);
  EXPECT_NEAR(life1, 343.0, 1e-9);
  EXPECT_NEAR(life2, 42.875, 1e-9);
  for (int i = 0; i < 1000; ++i) m.add(life1, w1, 100.0 * 3600.0 / 1000.0);
  for (int i = 0; i < 500; ++i) m.add(life2, w2, 20.0 * 3600.0 / 500.0);
  EXPECT_NEAR(m.damage(), d_expected, 1e-9 * d_expected);
  EXPECT_NEAR(m.damage(), 0.115452, 1e-6);
  EXPECT_NEAR(m.elapsed_s(), 120.0 * 3600.0, 1e-6);
  // Remaining life at the current (level 2) rate: (1 - D) L2.
  EXPECT_NEAR(m.remaining_life_hours(), (1.0 - d_expected) * l2_h, 1e-9 * l2_h);
  // Standing still does no damage and leaves the rate at zero: infinite remaining life.
  m.add(life2, 0.0, 3600.0);
  EXPECT_NEAR(m.damage(), d_expected, 1e-9);
  EXPECT_TRUE(std::isinf(m.remaining_life_s()));
  // No load, infinite life: no damage.
  EXPECT_TRUE(std::isinf(rating_life_million_rev(c, 0.0)));
  m.add(rating_life_million_rev(c, 0.0), w1, 3600.0);
  EXPECT_NEAR(m.damage(), d_expected, 1e-9);
  EXPECT_THROW(m.add(0.0, w1, 1.0), InvalidInputError);
  EXPECT_THROW(m.add(life1, w1, -1.0), InvalidInputError);
}

}  // namespace
}  // namespace bearing_sim
