// Hertz contact constant (Hamrock-Brewe, docs/model.md section 4) against a hand calculation,
// the exact Hertz theory (complete elliptic integrals) and the Hertz scaling laws.
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/hertz_contact.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
// ISO reference bearing (docs/model.md section 6.4).
constexpr double d = 11.1e-3, dm = 43.5e-3, fi = 0.52, fo = 0.53, E = 210e9, nu = 0.3;

struct Hand {
  double R, ar, k, Ee, F, K;
};

// Hand calculation from the Hamrock-Brewe formulas, with the race radii written as the
// geometry gives them for a0 = 0 (inner race (dm - d)/2 convex, outer (dm + d)/2 concave),
// not as the code writes them.
Hand hamrock_brewe(double inv_rx, double inv_ry) {
  Hand h;
  h.R = 1.0 / (inv_rx + inv_ry);
  h.ar = inv_rx / inv_ry;  // Ry / Rx
  h.k = 1.0339 * std::pow(h.ar, 0.636);
  h.Ee = 1.0003 + 0.5968 / h.ar;
  h.F = 1.5277 + 0.6023 * std::log(h.ar);
  const double Ep = E / (1.0 - nu * nu);
  h.K = kPi * h.k * Ep * std::sqrt(2.0 * h.Ee * h.R / (9.0 * h.F * h.F * h.F));
  return h;
}

// Exact Hertz theory: the eccentricity e of the contact ellipse solves
// Ry/Rx = (E(e)/(1 - e^2) - K(e)) / (K(e) - E(e)); then k = 1/sqrt(1 - e^2) and the same
// closed form for the stiffness with the exact integrals (Hamrock & Dowson).
Hand exact_hertz(double inv_rx, double inv_ry) {
  Hand h;
  h.R = 1.0 / (inv_rx + inv_ry);
  h.ar = inv_rx / inv_ry;
  double lo = 0.0, hi = 1.0 - 1e-14;  // e^2
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (lo + hi), e = std::sqrt(m);
    const double K1 = std::comp_ellint_1(e), E2 = std::comp_ellint_2(e);
    const double r = (E2 / (1.0 - m) - K1) / (K1 - E2);
    (r < h.ar ? lo : hi) = m;
  }
  const double m = 0.5 * (lo + hi), e = std::sqrt(m);
  h.k = 1.0 / std::sqrt(1.0 - m);
  h.Ee = std::comp_ellint_2(e);
  h.F = std::comp_ellint_1(e);
  const double Ep = E / (1.0 - nu * nu);
  h.K = kPi * h.k * Ep * std::sqrt(2.0 * h.Ee * h.R / (9.0 * h.F * h.F * h.F));
  return h;
}

const double inner_inv_rx = 2.0 / d + 1.0 / ((dm - d) / 2.0);
const double inner_inv_ry = 2.0 / d - 1.0 / (fi * d);
const double outer_inv_rx = 2.0 / d - 1.0 / ((dm + d) / 2.0);
const double outer_inv_ry = 2.0 / d - 1.0 / (fo * d);
}  // namespace

TEST(HertzContact, HandCalculationIsoBearing) {
  const HertzContact ci = inner_race_contact(d, dm, 0.0, fi, E, nu);
  const HertzContact co = outer_race_contact(d, dm, 0.0, fo, E, nu);
  const Hand hi = hamrock_brewe(inner_inv_rx, inner_inv_ry);
  const Hand ho = hamrock_brewe(outer_inv_rx, outer_inv_ry);
  // Same formulas, different but algebraically equal arithmetic: rounding only (1e-12).
  EXPECT_NEAR(ci.curvature_sum_per_m, 1.0 / hi.R, 1e-12 / hi.R);
  EXPECT_NEAR(ci.radius_ratio, hi.ar, 1e-12 * hi.ar);
  EXPECT_NEAR(ci.stiffness_N_per_m15, hi.K, 1e-12 * hi.K);
  EXPECT_NEAR(co.radius_ratio, ho.ar, 1e-12 * ho.ar);
  EXPECT_NEAR(co.stiffness_N_per_m15, ho.K, 1e-12 * ho.K);
  // Hand numbers (computed on paper from the formulas above): inner 1/R = 248.84 1/m, ar = 34.90.
  EXPECT_NEAR(1.0 / hi.R, 180.1802 + 61.7284 + 6.9300, 0.01);
  // Inner contact is stiffer than the outer (convex race, tighter groove).
  EXPECT_GT(ci.stiffness_N_per_m15, co.stiffness_N_per_m15);

  // Series combination, written out: delta = delta_i + delta_o at one Q.
  const BearingModel model(iso_reference_bearing());
  const double Q = 500.0;
  const double delta = std::pow(Q / hi.K, 2.0 / 3.0) + std::pow(Q / ho.K, 2.0 / 3.0);
  EXPECT_NEAR(model.contact_stiffness(), Q / std::pow(delta, 1.5), 1e-12 * model.contact_stiffness());
}

TEST(HertzContact, HamrockBreweAgainstExactHertz) {
  // Hamrock & Brewe (1983) state their fits within about 3% of the exact solution for
  // 1 <= ar <= 100; at ball/raceway ratios (ar ~ 10-40) the stiffness is closer (measured
  // well under 2%); 3% is the published accuracy.
  for (auto [irx, iry] : {std::pair{inner_inv_rx, inner_inv_ry}, std::pair{outer_inv_rx, outer_inv_ry}}) {
    const HertzContact c = hertz_contact(irx, iry, E, nu);
    const Hand x = exact_hertz(irx, iry);
    SCOPED_TRACE(x.ar);
    EXPECT_NEAR(c.ellipticity, x.k, 0.03 * x.k);
    EXPECT_NEAR(c.elliptic_E, x.Ee, 0.01 * x.Ee);
    EXPECT_NEAR(c.elliptic_F, x.F, 0.01 * x.F);
    EXPECT_NEAR(c.stiffness_N_per_m15, x.K, 0.03 * x.K);
  }
}

TEST(HertzContact, CircularLimitMatchesSphereOnFlat) {
  // Sphere of diameter d on a flat: Q = (4/3) E* sqrt(d/2) delta^1.5, E* = E'/2. The
  // Hamrock-Brewe fit at ar = 1 has k = 1.0339 and F = 1.5277 instead of 1 and pi/2, which
  // puts the stiffness about 9% high: the check is 12%, i.e. "right formula, right units".
  const HertzContact c = hertz_contact(2.0 / d, 2.0 / d, E, nu);
  const double exact = 4.0 / 3.0 * (E / (1.0 - nu * nu) / 2.0) * std::sqrt(d / 2.0);
  EXPECT_NEAR(c.stiffness_N_per_m15, exact, 0.12 * exact);
  EXPECT_GT(c.stiffness_N_per_m15, exact);
}

TEST(HertzContact, PressureAndSemiAxesConsistentWithLoadDeflection) {
  const HertzContact c = inner_race_contact(d, dm, 0.0, fi, E, nu);
  for (double Q : {10.0, 300.0, 5000.0}) {
    SCOPED_TRACE(Q);
    const double a = c.semi_major_m(Q), b = c.semi_minor_m(Q);
    // a/b is the ellipticity k (rounding only).
    EXPECT_NEAR(a / b, c.ellipticity, 1e-12 * c.ellipticity);
    // Mean pressure over the ellipse is 2/3 of the peak: p0 = 3Q / (2 pi a b).
    EXPECT_NEAR(c.max_pressure_Pa(Q), 3.0 * Q / (2.0 * kPi * a * b), 1e-12 * c.max_pressure_Pa(Q));
    // Hertz: the approach is delta = F b^2 / (2 E R) (for a sphere on a flat, b^2 / Reff);
    // it must give back Q = K delta^1.5 (rounding only).
    const double R = 1.0 / c.curvature_sum_per_m;
    const double delta = c.elliptic_F * b * b / (2.0 * c.elliptic_E * R);
    EXPECT_NEAR(c.stiffness_N_per_m15 * std::pow(delta, 1.5), Q, 1e-10 * Q);
    // p0 scales as Q^(1/3).
    EXPECT_NEAR(c.max_pressure_Pa(8.0 * Q), 2.0 * c.max_pressure_Pa(Q), 1e-12 * c.max_pressure_Pa(Q));
  }
  // Order of magnitude check against a familiar number: a ball bearing's inner contact at a
  // few kN is at 2-4 GPa.
  EXPECT_GT(c.max_pressure_Pa(2000.0), 2.0e9);
  EXPECT_LT(c.max_pressure_Pa(2000.0), 4.5e9);
  EXPECT_EQ(c.max_pressure_Pa(0.0), 0.0);
}
