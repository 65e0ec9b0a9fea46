// Rigid body on Bushing springs (core/modal_analysis.hpp) against closed forms: the
// coupled translation-tilt pair of a body on one spring at an offset (a two-degree-of-
// freedom system), uncoupled axial and tilt modes, and the free rotation about the axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/modal_analysis.hpp"

namespace bearing_sim {
namespace {

constexpr double kTwoPi = 6.283185307179586;

Matrix6 bushing(double kr, double ka, double kt) {
  Matrix6 k = Matrix6::Zero();
  k.diagonal() << kr, kr, ka, kt, kt, 0.0;
  return k;
}

// Roots of m J l^2 - (m (k a^2 + kt) + k J) l + k kt = 0: the x-ry pair of a body (m, J)
// on a radial spring k at axial offset a plus a tilt spring kt.
void two_dof_closed_form(double m, double j, double k, double kt, double a, double* f1, double* f2) {
  const double A = m * j, B = -(m * (k * a * a + kt) + k * j), C = k * kt;
  const double disc = std::sqrt(B * B - 4 * A * C);
  *f1 = std::sqrt((-B - disc) / (2 * A)) / kTwoPi;
  *f2 = std::sqrt((-B + disc) / (2 * A)) / kTwoPi;
}

std::vector<double> frequencies(const ModalResult& r) {
  std::vector<double> f;
  for (const auto& m : r.modes) f.push_back(m.frequency_hz);
  return f;
}

TEST(ModalAnalysis, TwoDofClosedFormOfATranslationTiltPair) {
  const double m = 4.0, jx = 0.017, jy = 0.021, jz = 0.03;
  const double kr = 2.0e8, ka = 9.0e7, kt = 1.8e4, a = 0.05;
  RigidBody body{m, Eigen::Vector3d(jx, jy, jz)};
  const ModalResult r = solve_modes(body, {{bushing(kr, ka, kt), Eigen::Vector3d(0, 0, a)}});
  ASSERT_EQ(r.modes.size(), 6u);
  // x-ry pair (Iyy), y-rx pair (Ixx), axial z, free rz.
  double fx1, fx2, fy1, fy2;
  two_dof_closed_form(m, jy, kr, kt, a, &fx1, &fx2);
  two_dof_closed_form(m, jx, kr, kt, a, &fy1, &fy2);
  std::vector<double> expected{0.0, fx1, fx2, fy1, fy2, std::sqrt(ka / m) / kTwoPi};
  std::sort(expected.begin(), expected.end());
  const auto got = frequencies(r);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(got[i], expected[i], 1e-7 * expected[5]) << "mode " << i + 1;
  EXPECT_TRUE(r.modes[0].free);
  EXPECT_EQ(r.modes[0].dominant_dof, 5);  // rz
  // Mass-normalised, M-orthogonal shapes.
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(r.modes[i].shape.dot(r.mass * r.modes[j].shape), i == j ? 1.0 : 0.0, 1e-9);
}

TEST(ModalAnalysis, TwoBearingsWithoutAngularStiffnessGiveUncoupledClosedForms) {
  const double m = 3.0, j = 0.02, kr = 1.5e8, ka = 5e7, kt = 2e4, a = 0.08;
  RigidBody body{m, Eigen::Vector3d(j, j, 2 * j)};
  std::vector<BushingSupport> two{{bushing(kr, ka, kt), Eigen::Vector3d(0, 0, -a)},
                                  {bushing(kr, ka, kt), Eigen::Vector3d(0, 0, a)}};
  ModalOptions no_angular;
  no_angular.zero_angular_stiffness = true;
  const auto f = frequencies(solve_modes(body, two, no_angular));
  // Symmetric supports: translation sqrt(2 kr / m), tilt sqrt(2 kr a^2 / J), axial sqrt(2 ka / m).
  std::vector<double> expected{0.0,
                               std::sqrt(2 * kr / m) / kTwoPi,
                               std::sqrt(2 * kr / m) / kTwoPi,
                               std::sqrt(2 * kr * a * a / j) / kTwoPi,
                               std::sqrt(2 * kr * a * a / j) / kTwoPi,
                               std::sqrt(2 * ka / m) / kTwoPi};
  std::sort(expected.begin(), expected.end());
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(f[i], expected[i], 1e-7 * expected[5]);
  // With the angular stiffness the tilt modes rise to sqrt((2 kr a^2 + 2 kt) / J).
  const auto g = frequencies(solve_modes(body, two));
  const double tilt = std::sqrt((2 * kr * a * a + 2 * kt) / j) / kTwoPi;
  int found = 0;
  for (double v : g) found += std::abs(v - tilt) < 1e-6 * tilt;
  EXPECT_EQ(found, 2);
}

TEST(ModalAnalysis, OneBearingWithoutAngularStiffnessLeavesTheTiltsFree) {
  RigidBody body{2.0, Eigen::Vector3d(0.01, 0.01, 0.02)};
  ModalOptions no_angular;
  no_angular.zero_angular_stiffness = true;
  const ModalResult r = solve_modes(body, {{bushing(1e8, 5e7, 1e4), Eigen::Vector3d::Zero()}}, no_angular);
  int free = 0;
  for (const auto& m : r.modes) free += m.free;
  EXPECT_EQ(free, 3);  // rx, ry, rz
}

TEST(ModalAnalysis, BadInputIsAClearError) {
  RigidBody body{0.0, Eigen::Vector3d(1, 1, 1)};
  try {
    solve_modes(body, {{bushing(1, 1, 1), Eigen::Vector3d::Zero()}});
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("mass"), std::string::npos) << e.what();
  }
  RigidBody ok{1.0, Eigen::Vector3d(1, 1, 1)};
  EXPECT_THROW(solve_modes(ok, {}), InvalidInputError);
  Matrix6 asym = bushing(1e8, 1e8, 1e4);
  asym(0, 4) = 1e6;
  EXPECT_THROW(solve_modes(ok, {{asym, Eigen::Vector3d::Zero()}}), InvalidInputError);
}

// The message of solve_modes' InvalidInputError ("" when none).
std::string refusal(const RigidBody& body, const Eigen::Vector3d& position) {
  try {
    solve_modes(body, {{bushing(1e8, 1e8, 1e4), position}});
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(ModalAnalysis, ABodyOrPlaceBeyondTheLimitsIsRefusedNamingTheValueGiven) {
  const Eigen::Vector3d centre = Eigen::Vector3d::Zero(), inertia(1, 1, 1);
  // 1e-300 kg was refused naming "a mass of 5e-324 kg".
  std::string why = refusal(RigidBody{1e-300, inertia}, centre);
  EXPECT_NE(why.find("mass 1e-300 kg is outside [0.001, 1e+07] kg"), std::string::npos) << why;
  why = refusal(RigidBody{1.0, Eigen::Vector3d(1, 2e9, 1)}, centre);
  EXPECT_NE(why.find("inertia Iyy 2e+09 kg*m^2 is outside [1e-09, 1e+09]"), std::string::npos) << why;
  why = refusal(RigidBody{1.0, inertia}, Eigen::Vector3d(0, 0, 1e297));
  EXPECT_NE(why.find("support 1 position z 1e+297 m is outside [-100, 100] m"), std::string::npos) << why;
  EXPECT_EQ(why.find("5e-324"), std::string::npos) << why;
  // The limits are bodies and places.
  EXPECT_EQ(refusal(RigidBody{kMinBodyMassKg, Eigen::Vector3d::Constant(kMaxBodyInertiaKgM2)},
                    Eigen::Vector3d(0, 0, -kMaxSupportDistanceM)),
            "");
}

}  // namespace
}  // namespace bearing_sim
