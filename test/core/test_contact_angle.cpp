// Loaded contact angle (docs/model.md section 5.2): closed form for a0 = 0 under pure axial load,
// and growth with axial load for an angular contact bearing.
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

TEST(ContactAngle, DeepGrooveUnderPureAxialLoadClosedForm) {
  // Zero clearance, a0 = 0, axial force Fa: all Z balls alike. The groove centres, A apart,
  // are pushed axially by u: |v| = sqrt(A^2 + u^2), so cos a = A/(A + delta), u = A tan a and
  // Fa = Z Kn delta^1.5 sin a with delta = A (1/cos a - 1) (Harris's axial-load equation).
  // Solved here by bisection on a.
  const BearingModel model(iso_reference_bearing());
  const double A = (0.52 + 0.53 - 1.0) * 11.1e-3;
  EXPECT_NEAR(model.groove_centre_distance_m(), A, 1e-15);
  const double kn = model.contact_stiffness();
  for (double fa : {100.0, 1000.0, 5000.0}) {
    SCOPED_TRACE(fa);
    double lo = 1e-6, hi = 1.0;
    for (int i = 0; i < 200; ++i) {
      const double a = 0.5 * (lo + hi), delta = A * (1.0 / std::cos(a) - 1.0);
      (6.0 * kn * std::pow(delta, 1.5) * std::sin(a) < fa ? lo : hi) = a;
    }
    const double a = 0.5 * (lo + hi);
    const double delta = A * (1.0 / std::cos(a) - 1.0);
    const StaticSolution s = solve_static(model, load5(0, 0, fa, 0, 0));
    // The solver's residual is 1e-9 N; the closed form is exact: 1e-7 relative.
    EXPECT_NEAR(std::abs(s.displacement[2]), A * std::tan(a), 1e-7 * A * std::tan(a));
    for (const BallState& b : s.balls) {
      EXPECT_NEAR(b.contact_angle_rad, a, 1e-7 * a);
      EXPECT_NEAR(b.deflection_m, delta, 1e-7 * delta);
      EXPECT_NEAR(std::cos(b.contact_angle_rad), A / (A + b.deflection_m), 1e-12);
      EXPECT_NEAR(b.load_N, fa / (6.0 * std::sin(a)), 1e-7 * b.load_N);
    }
  }
}

TEST(ContactAngle, AngularContactAngleGrowsWithAxialLoad) {
  const BearingModel model(single_row(12, 12.7, 65.0, 25.0, 0.52, 0.53));
  const double a0 = 25.0 * kPi / 180.0;
  double previous = a0;
  for (double fa : {100.0, 1000.0, 5000.0, 20000.0}) {
    const StaticSolution s = solve_static(model, load5(0, 0, -fa, 0, 0));
    const double a = s.balls.at(0).contact_angle_rad;
    EXPECT_GT(a, previous) << fa;
    // All balls equal under a pure axial load (rounding of the azimuths only).
    for (const BallState& b : s.balls) EXPECT_NEAR(b.contact_angle_rad, a, 1e-9);
    // Axial balance of a ring of equal balls: Fa = Z Q sin a.
    EXPECT_NEAR(12.0 * s.balls.at(0).load_N * std::sin(a), fa, 1e-7 * fa);
    previous = a;
  }
}

TEST(ContactAngle, UnloadedAngleIsNominal) {
  // With a vanishing load the loaded angle tends to a0 (here 35 deg, the CT bearing).
  const BearingModel model(ct_bearing());
  const StaticSolution s = solve_static(model, load5(0, 0, 1e-3, 0, 0));
  for (const BallState& b : s.balls) {
    if (b.load_N > 0) {
      EXPECT_NEAR(b.contact_angle_rad, 35.0 * kPi / 180.0, 1e-4);
    }
  }
}
