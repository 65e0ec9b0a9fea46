// Stribeck load distribution of a zero-clearance single-row deep groove bearing (docs/model.md section 6.4).
//
// Stribeck's ratio assumes each ball is compressed by x cos(phi). The model's exact
// geometry adds the second-order term x^2 sin^2(phi) / (2A) (the groove centres also move
// apart sideways), so the ratio departs from Stribeck's by O(x/A), A = (fi + fo - 1) d the
// groove-centre distance. The tests therefore compare at light loads (x/A < 0.5%) with a
// tolerance of |x/A|, and check that the departure vanishes in proportion to x/A.
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
// Exact finite-Z Stribeck ratio for a rigid-ring radial displacement along the ball at
// azimuth 0: delta_j = delta_max cos phi_j, Q ~ delta^1.5, so Fr = Qmax sum cos^2.5 phi_j.
double stribeck_exact(int z) {
  double sum = 0.0;
  for (int j = 0; j < z; ++j) {
    const double c = std::cos(2.0 * kPi * j / z);
    if (c > 0.0) sum += std::pow(c, 2.5);
  }
  return z / sum;
}

struct Result {
  double ratio;     // Qmax Z / Fr
  double x_over_a;  // |radial displacement| / A
};

Result solve(const BearingModel& model, double fr) {
  // The load pushes the moving outer ring towards -x, so the loaded zone is centred on the
  // ball at azimuth 0 (cage angle 0).
  const StaticSolution s = solve_static(model, load5(-fr, 0, 0, 0, 0));
  EXPECT_NEAR(s.balls.at(0).azimuth_rad, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.balls.at(0).load_N, s.max_ball_load_N);
  return {s.max_ball_load_N * model.balls_per_row() / fr,
          std::abs(s.displacement[0]) / model.groove_centre_distance_m()};
}
}  // namespace

TEST(Stribeck, FiniteZExactAtLightLoad) {
  for (int z : {7, 8, 9, 12}) {
    SCOPED_TRACE(z);
    const BearingModel model(single_row(z, 11.1, 43.5 + 4.0 * (z - 6), 0.0, 0.52, 0.53));
    const double expected = stribeck_exact(z);
    const Result r = solve(model, 20.0);
    ASSERT_LT(r.x_over_a, 5e-3);
    // Second-order geometry: departure O(x/A); |x/A| (< 0.5%) bounds it.
    EXPECT_NEAR(r.ratio, expected, r.x_over_a * expected);
  }
}

TEST(Stribeck, DepartureVanishesWithLoad) {
  const BearingModel model(single_row(9, 11.1, 55.5, 0.0, 0.52, 0.53));
  const double expected = stribeck_exact(9);
  double previous = 1.0;
  for (double fr : {5000.0, 500.0, 50.0, 5.0, 0.5}) {
    SCOPED_TRACE(fr);
    const Result r = solve(model, fr);
    const double departure = std::abs(r.ratio / expected - 1.0);
    // Linear in x/A with a coefficient of order one (the cos^2.5 weighting of the side
    // balls' sin^2 term): between 0.1 and 1.5 times x/A.
    EXPECT_LT(departure, 1.5 * r.x_over_a);
    EXPECT_GT(departure, 0.1 * r.x_over_a);
    EXPECT_LT(departure, previous);  // monotone approach to Stribeck
    previous = departure;
  }
  EXPECT_LT(previous, 1e-4);  // at 0.5 N (x/A ~ 1e-4) Stribeck's ratio holds to 1e-4
}

TEST(Stribeck, LargeZApproaches437) {
  // Infinite-Z limit: 2 pi / integral_{-pi/2}^{pi/2} cos^2.5 = 4.370 (Beta-function closed form).
  const double limit = 2.0 * kPi / (std::sqrt(kPi) * std::tgamma(1.75) / std::tgamma(2.25));
  EXPECT_NEAR(limit, 4.37, 0.005);
  EXPECT_NEAR(stribeck_exact(60), limit, 1e-3 * limit);  // finite Z = 60 is within 0.1% of the limit
  const BearingModel model(single_row(60, 5.0, 120.0, 0.0, 0.52, 0.53));
  const Result r = solve(model, 100.0);
  ASSERT_LT(r.x_over_a, 5e-3);
  // The brief's 1% on 4.37; the O(x/A) geometric departure is below 0.5% here.
  EXPECT_NEAR(r.ratio, 4.37, 0.01 * 4.37);
  EXPECT_NEAR(r.ratio, stribeck_exact(60), r.x_over_a * stribeck_exact(60));
}
