// Analytic stiffness matrix against central differences of the contact forces (docs/model.md section 5.5).
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {

// K_fd(:, j) = -(F(q + h e_j) - F(q - h e_j)) / (2 h), from the force alone (zero velocity,
// through both force entry points).
Matrix5 finite_difference_stiffness(const BearingModel& model, const Vector5& q, double length_step) {
  Matrix5 k;
  const Vector5 zero = Vector5::Zero();
  for (int j = 0; j < 5; ++j) {
    // Translations step by length_step; tilts by length_step at the pitch radius.
    const double h = j < 3 ? length_step : length_step / model.pitch_radius_m();
    Vector5 qp = q, qm = q;
    qp[j] += h;
    qm[j] -= h;
    k.col(j) = -(model.contact_force(qp, zero, 0.0) - model.contact_force(qm, zero, 0.0)) / (2.0 * h);
    const Vector5 alt =
        -(model.contact_force_and_stiffness(qp, 0.0, nullptr) - model.contact_force_and_stiffness(qm, 0.0, nullptr)) /
        (2.0 * h);
    // The two force paths (with and without damping) agree at zero velocity (rounding).
    EXPECT_LT((alt - k.col(j)).norm(), 1e-9 * k.col(j).norm() + 1e-6);
  }
  return k;
}

// Entry-wise error scaled by sqrt(K_ii K_jj), so translational and tilt entries compare alike.
double scaled_error(const Matrix5& a, const Matrix5& b) {
  double worst = 0.0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      worst = std::max(worst, std::abs(a(i, j) - b(i, j)) / std::sqrt(std::abs(b(i, i) * b(j, j))));
  return worst;
}

void check(const BearingModel& model, const Vector5& load) {
  const StaticSolution s = solve_static(model, load);
  const Vector5& q = s.displacement;
  Matrix5 k;
  model.contact_force_and_stiffness(q, 0.0, &k);
  EXPECT_LT((k - s.stiffness).norm(), 1e-12 * k.norm());
  // Step 1 nm against deflections of micrometres: truncation ~ (h/delta)^2 ~ 1e-6; rounding
  // ~ eps |F| / h ~ 1e-16 * 1e4 / 1e-9 = 1e-3 N/m against K ~ 1e8..1e9 N/m. A ball at the edge
  // of the loaded zone (delta^1.5 has no second derivative at 0) adds at most
  // Kn h^1.5 / h ~ 1e-5 relative. Hence 1e-4.
  const Matrix5 kfd = finite_difference_stiffness(model, q, 1e-9);
  EXPECT_LT(scaled_error(k, kfd), 1e-4) << "analytic\n" << k << "\nfinite differences\n" << kfd;
  // Symmetric (the contact forces derive from a potential): rounding only.
  EXPECT_LT(scaled_error(k, k.transpose()), 1e-12);
  // Positive definite in the loaded directions: the equilibrium is stable.
  for (int i = 0; i < 5; ++i) EXPECT_GE(k(i, i), 0.0);
}
}  // namespace

TEST(Stiffness, CtBearingOperatingPoint) {
  const BearingModel model(ct_bearing());
  check(model, ct_load());
  const StaticSolution s = solve_static(model, ct_load());
  // Two clearance-free angular contact rows carry radial, axial and tilt: all three of the
  // "three-way" stiffnesses are positive and the x-theta_y coupling is present.
  EXPECT_GT(s.stiffness(0, 0), 0.0);
  EXPECT_GT(s.stiffness(2, 2), 0.0);
  EXPECT_GT(s.stiffness(4, 4), 0.0);
  EXPECT_GT(std::abs(s.stiffness(0, 4)), 1e-6 * std::sqrt(s.stiffness(0, 0) * s.stiffness(4, 4)));
  // The Bushing matrix is the 5x5 padded with a zero row and column for rotation about z.
  const Matrix6 b = bushing_matrix(s.stiffness);
  EXPECT_TRUE((b.topLeftCorner(5, 5) - s.stiffness).isZero(0.0));
  EXPECT_EQ(b.row(5).norm(), 0.0);
  EXPECT_EQ(b.col(5).norm(), 0.0);
}

TEST(Stiffness, SingleRowDeepGrooveCombined) {
  const BearingModel model(iso_reference_bearing(0.0));
  check(model, load5(1000.0, 200.0, 300.0, 0.0, 0.0));
}

TEST(Stiffness, SingleRowAngularContactWithClearance) {
  const BearingModel model(single_row(12, 12.7, 65.0, 25.0, 0.52, 0.53, 3.0));
  check(model, load5(1500.0, 0.0, -2000.0, 0.0, 0.0));
}

TEST(Stiffness, InnerRingMovingCtBearing) {
  BearingConfig c = ct_bearing();
  c.rotating_ring = RotatingRing::Inner;
  check(BearingModel(c), ct_load());
}
