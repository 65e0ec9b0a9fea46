// Where the moving ring's displacement and moment arms are taken (docs/model.md section 5.1):
// at the groove centre of the moving ring, P_i for a moving inner ring. Checked on the INS
// 618/22 DB pair with its inner ring moving, under a combined load that turns the contact
// lines well away from the nominal angle (where P_i and P_o give different moments).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

BearingConfig ins_pair(const std::string& ring) {
  BearingConfig c = load_bearing_config(test::bearing_file("ins_618_22_db.yaml"));
  c.rotating_ring = ring == "inner" ? RotatingRing::Inner : RotatingRing::Outer;
  return c;
}

// 1500 N radial, 600 N axial, 2 N*m tilt: every ball loaded on one row, contact angles from
// about 10 to 20 deg.
const Vector5 kLoad = test::load5(1500.0, 0.0, 600.0, 0.0, 2.0);

// Groove centres of ball b from the bearing file's numbers (section 3.4), independent of the model.
struct Centres {
  Eigen::Vector3d outer, inner;
};
Centres groove_centres(const BearingModel& model, int b, double azimuth) {
  const BearingConfig& c = model.config();
  const int row = model.row_of_ball(b);
  const double d = c.ball_diameter_m, a0 = c.contact_angle_rad, cr = model.row_contact_sign(row);
  const double zr = row == 0 ? c.row_spacing_m / 2.0 : -c.row_spacing_m / 2.0;
  const Eigen::Vector3d e0(std::cos(a0) * std::cos(azimuth), std::cos(a0) * std::sin(azimuth), cr * std::sin(a0));
  const Eigen::Vector3d ball(c.pitch_diameter_m / 2.0 * std::cos(azimuth), c.pitch_diameter_m / 2.0 * std::sin(azimuth),
                             zr);
  // Each centre lies beyond the ball centre on the far side from its own raceway.
  return {ball - (c.outer_groove_curvature - 0.5) * d * e0, ball + (c.inner_groove_curvature - 0.5) * d * e0};
}

TEST(LeverArms, InnerRingMomentIsThatOfTheBallLoadsAtTheInnerGrooveCentres) {
  const BearingModel model(ins_pair("inner"));
  const StaticSolution s = solve_static(model, kLoad);
  const Vector5 f = model.contact_force(s.displacement, Vector5::Zero(), RollingPhase{}, model.balls());
  // Force on the inner ring: -Q e per ball (e from the inner to the outer contact).
  Eigen::Vector3d at_inner = Eigen::Vector3d::Zero(), at_outer = Eigen::Vector3d::Zero();
  double lever_load = 0.0;
  for (int b = 0; b < model.ball_count(); ++b) {
    const BallState& ball = s.balls[b];
    const Centres p = groove_centres(model, b, ball.azimuth_rad);
    at_inner += p.inner.cross(-ball.load_N * ball.normal);
    at_outer += p.outer.cross(-ball.load_N * ball.normal);
    lever_load += ball.load_N * p.inner.norm();
  }
  // Equal up to the rounding of sums of ~20 terms of size Q |P| (1e-12 of their sum).
  const double tolerance = 1e-12 * lever_load;
  EXPECT_NEAR(f[3], at_inner.x(), tolerance);
  EXPECT_NEAR(f[4], at_inner.y(), tolerance);
  // The outer-groove centres give a different moment: the two differ by sum Q A (e0 x e),
  // which the turned contact lines make far larger than the rounding.
  EXPECT_GT((Eigen::Vector2d(f[3], f[4]) - at_outer.head<2>()).norm(), 1e3 * tolerance);
}

// Potential of the contacts when the inner ring's groove centres move as points of the inner
// ring, P_i -> P_i + t + theta x P_i (the small-rotation kinematics of section 5.1, applied
// where the groove is): V = sum 2/5 Kn delta^(5/2), delta = |P_i' - P_o| - A - g0.
double potential(const BearingModel& model, const Vector5& q) {
  const Eigen::Vector3d t(q[0], q[1], q[2]), theta(q[3], q[4], 0.0);
  const double a = model.groove_centre_distance_m(), g0 = model.config().clearance_m, kn = model.contact_stiffness();
  double v = 0.0;
  for (int b = 0; b < model.ball_count(); ++b) {
    const Centres p = groove_centres(model, b, model.base_azimuth_rad(b));
    const double delta = (p.inner + t + theta.cross(p.inner) - p.outer).norm() - a - g0;
    if (delta > 0.0) v += 0.4 * kn * std::pow(delta, 2.5);
  }
  return v;
}

TEST(LeverArms, InnerRingForceIsTheGradientOfThePotentialOfItsGrooveCentres) {
  // Virtual work: the generalized force on the moving inner ring is -dV/dq, here by central
  // differences of V. Steps of 1 nm and 1e-7 rad against deflections of ~10 um: truncation
  // (h / delta)^2 ~ 1e-8, rounding eps V / h ~ 1e-9 N; 1e-6 of the load leaves room for both.
  const BearingModel model(ins_pair("inner"));
  const StaticSolution s = solve_static(model, kLoad);
  const Vector5 q = s.displacement;
  const Vector5 f = model.contact_force(q, Vector5::Zero(), RollingPhase{}, model.balls());
  Vector5 gradient;
  for (int i = 0; i < 5; ++i) {
    const double h = i < 3 ? 1e-9 : 1e-7;
    Vector5 up = q, down = q;
    up[i] += h;
    down[i] -= h;
    gradient[i] = (potential(model, up) - potential(model, down)) / (2.0 * h);
  }
  const double force_tolerance = 1e-6 * kLoad.head<3>().norm(), moment_tolerance = 1e-6 * std::abs(kLoad[4]);
  EXPECT_LT((f.head<3>() + gradient.head<3>()).norm(), force_tolerance);
  EXPECT_LT((f.tail<2>() + gradient.tail<2>()).norm(), moment_tolerance);
  // The former formulation (displacement and arms at P_o) is not the gradient of this
  // potential: for a moving inner ring it equals minus the moving-outer-ring model at -q
  // (the same v = A e0 + t + theta x P_o). Its moment is off by far more than the tolerance.
  const BearingModel outer_moves(ins_pair("outer"));
  const Vector5 f_old = -outer_moves.contact_force(-q, Vector5::Zero(), RollingPhase{}, outer_moves.balls());
  EXPECT_GT((f_old.tail<2>() + gradient.tail<2>()).norm(), 100.0 * moment_tolerance);
}

TEST(LeverArms, TiltStiffnessOfTheInnerRingMovingInsPair) {
  // Report and bound the change of the tilt stiffness from taking the arms at P_i: the
  // former formulation's stiffness at load L is that of the outer-moving model at -L (the
  // same v). P_i lies A cos a0 further out than P_o: the arms across the contact lines grow
  // by A / rho (1.2 %), so the geometric stiffness Q / |v| (I - e e^T) of the turning lines,
  // a part of the total, grows by 2 A / rho; the arms along the lines change only by
  // A e0 x e. So the stiffness grows, by less than 2 A / rho.
  const BearingModel inner(ins_pair("inner")), outer(ins_pair("outer"));
  const double a_over_rho = inner.groove_centre_distance_m() / (inner.pitch_radius_m());
  for (const Vector5& load : {test::load5(0, 0, 0, 0, 2.0), kLoad}) {
    const double k_new = solve_static(inner, load).stiffness(4, 4);
    const double k_old = solve_static(outer, -load).stiffness(4, 4);
    const double change = k_new / k_old - 1.0;
    std::printf(
        "INS pair, inner ring moving, load (%g N, %g N, %g N m): tilt stiffness %.6g N m/rad "
        "(arms at P_o: %.6g), change %+.3f %%\n",
        load[0], load[2], load[4], k_new, k_old, 100.0 * change);
    EXPECT_LT(change, 2.0 * a_over_rho);
    EXPECT_GT(change, 0.0);
  }
}

}  // namespace
}  // namespace bearing_sim
