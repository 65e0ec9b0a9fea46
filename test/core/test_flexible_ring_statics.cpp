// The flexible ring's contacts and static equilibrium (docs/model.md 18.2): the rigid ring's
// forces when the ring is undeformed, the analytic stiffness against finite differences, and
// the load distribution tending to the rigid ring's as the ring's bending stiffness grows;
// the rigid-ring dynamics, scenarios and sweeps refuse a flexible ring, naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include <Eigen/Eigenvalues>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/flexible_bearing.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/sweep.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::bearing_file;
using test::load5;

BearingConfig ct_flexible() { return load_bearing_config(bearing_file("ct_gantry_flexible.yaml")); }
// The paper's load: the rotor's weight 6800 N along x and 2100 N*m about y.
Vector5 paper_load() { return load5(6800.0, 0.0, 0.0, 0.0, 2100.0); }

TEST(FlexibleRingStatics, AnUndeformedRingLoadsTheBallsAsTheRigidRing) {
  const FlexibleBearing flexible{BearingModel(ct_flexible())};
  const BearingModel& rigid = flexible.model();
  const RollingPhase phase{0.3, 0.0, 1.1, 0.0, 0.0};
  const StaticSolution s = solve_static(rigid, paper_load(), phase);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(flexible.size()), x_dot = Eigen::VectorXd::Zero(flexible.size());
  x.head<5>() = s.displacement;
  x_dot.head<5>() << 1e-4, -2e-4, 5e-5, 1e-4, -1e-4;  // with the contacts' damping
  const Eigen::VectorXd f = flexible.contact_force(x, x_dot, phase);
  const Vector5 expected =
      rigid.contact_force(s.displacement, x_dot.head<5>(), phase, rigid.balls(), BearingModel::ContactKernel::Scalar);
  // Same formulas summed in another order: rounding of a sum of ~200 loads of ~100 N.
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(f[i], expected[i], 1e-9 * expected.norm()) << i;
}

TEST(FlexibleRingStatics, TheDisplayedDeformationIsTheModeTurningWithTheRing) {
  // Only the n = 2 radial mode's cos coordinate set, a = 10 um, and an axial n = 3 sin one,
  // 4 um: the centre line is a cos 2 (phi - psi) outwards and b sin 3 (phi - psi) along the
  // axis, its ovality's long axis at the ring angle psi and turning with it.
  const FlexibleBearing flexible{BearingModel(ct_flexible())};
  const auto& modes = flexible.modes();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(flexible.size());
  const double a = 10e-6, b = 4e-6;
  int set = 0;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    if (modes[i].order == 2 && modes[i].direction == RingModeDirection::Radial) {
      x[5 + 2 * i] = a;
      ++set;
    }
    if (modes[i].order == 3 && modes[i].direction == RingModeDirection::Axial) {
      x[6 + 2 * i] = b;
      ++set;
    }
  }
  ASSERT_EQ(set, 2) << "ct_gantry_flexible.yaml has radial n = 2 and axial n = 3 modes";
  for (const double psi : {0.0, 0.4, 2.5}) {
    RollingPhase phase{};
    phase.outer_ring = psi;  // the CT bearing's rotating ring
    const FlexibleBearing::Deformation d = flexible.deformation(x, phase, 72);
    EXPECT_DOUBLE_EQ(d.ring_angle_rad, psi);
    ASSERT_EQ(d.azimuth_rad.size(), 72u);
    for (int i = 0; i < 72; ++i) {
      const double phi = 2.0 * test::kPi * i / 72;
      EXPECT_NEAR(d.azimuth_rad[i], phi, 1e-15);
      // The sums of cosines of other arguments: rounding of 1e-5 m.
      EXPECT_NEAR(d.radial_m[i], a * std::cos(2.0 * (phi - psi)), 1e-18) << "psi " << psi << ", phi " << phi;
      EXPECT_NEAR(d.axial_m[i], b * std::sin(3.0 * (phi - psi)), 1e-18) << "psi " << psi << ", phi " << phi;
    }
  }
  EXPECT_THROW(flexible.deformation(x, RollingPhase{}, 0), InvalidInputError);
}

TEST(FlexibleRingStatics, TheAnalyticStiffnessIsTheForcesDerivative) {
  const FlexibleBearing flexible{BearingModel(ct_flexible())};
  const RollingPhase phase{0.2, 0.0, 0.7, 0.0, 0.0};
  const FlexibleStaticSolution sol = solve_flexible_static(flexible, paper_load(), phase);
  Eigen::MatrixXd k;
  flexible.contact_force_and_stiffness(sol.coordinates, phase, &k);
  const int n = flexible.size();
  for (int j = 0; j < n; ++j) {
    // A nm of displacement, or the tilt that moves the ring's edge by a nm.
    const double step = (j == 3 || j == 4) ? 1e-9 / flexible.model().pitch_radius_m() : 1e-9;
    Eigen::VectorXd plus = sol.coordinates, minus = sol.coordinates;
    plus[j] += step;
    minus[j] -= step;
    const Eigen::VectorXd column = -(flexible.contact_force_and_stiffness(plus, phase, nullptr) -
                                     flexible.contact_force_and_stiffness(minus, phase, nullptr)) /
                                   (2.0 * step);
    // Central differences over 2 nm of ~10 um deflections: truncation ~1e-8, rounding ~1e-6.
    EXPECT_LT((column - k.col(j)).norm(), 1e-5 * k.col(j).norm() + 1e-3) << "column " << j;
  }
}

// Largest ball load and its difference from the rigid ring's, ball by ball.
struct Distribution {
  double max_load_N = 0.0;
  double max_difference_N = 0.0;  // max over balls of |Q_flexible - Q_rigid|
};

Distribution distribution(double modulus_factor, const StaticSolution& rigid) {
  BearingConfig c = ct_flexible();
  c.flexible_ring.youngs_modulus_Pa *= modulus_factor;
  c.flexible_ring.shear_modulus_Pa *= modulus_factor;
  const FlexibleBearing flexible{BearingModel(c)};
  const FlexibleStaticSolution sol = solve_flexible_static(flexible, paper_load());
  Distribution d;
  d.max_load_N = sol.rigid_coordinates.max_ball_load_N;
  for (std::size_t b = 0; b < rigid.balls.size(); ++b)
    d.max_difference_N =
        std::max(d.max_difference_N, std::abs(sol.rigid_coordinates.balls[b].load_N - rigid.balls[b].load_N));
  return d;
}

TEST(FlexibleRingStatics, TheLoadDistributionTendsToTheRigidRingsAsTheRingStiffens) {
  const BearingConfig c = ct_flexible();
  const StaticSolution rigid = solve_static(BearingModel(c), paper_load());
  const Distribution real = distribution(1.0, rigid), e3 = distribution(1e3, rigid), e6 = distribution(1e6, rigid);
  std::cout << "peak ball load: rigid " << rigid.max_ball_load_N << " N, flexible " << real.max_load_N
            << " N (largest per-ball difference " << real.max_difference_N << " N), E x 1e3: " << e3.max_difference_N
            << " N, E x 1e6: " << e6.max_difference_N << " N\n";
  // The real section changes the distribution visibly: more than 5 % of the peak load.
  EXPECT_GT(real.max_difference_N, 0.05 * rigid.max_ball_load_N);
  // The ring's compliance scales as 1/E, and so does the first-order change of the loads: a
  // thousand times stiffer, a thousand times closer (within 20 % for the remaining curvature
  // of the Hertz law and of the load zone's edge).
  EXPECT_NEAR(e3.max_difference_N / e6.max_difference_N, 1e3, 200.0);
  // At E x 1e6 the ring is rigid to the balls: the 1/E law from E x 1e3 puts the difference
  // near 1e-3 of that one (~0.01 N, 1e-4 of the peak); below 1e-4 of the peak load.
  EXPECT_LT(e6.max_difference_N, 1e-4 * rigid.max_ball_load_N);
  EXPECT_NEAR(e6.max_load_N, rigid.max_ball_load_N, 1e-4 * rigid.max_ball_load_N);
}

TEST(FlexibleRingStatics, TheRigidRingDynamicsRefuseAFlexibleRingNamingTheKey) {
  const BearingModel model(ct_flexible());
  try {
    BearingDynamics dynamics(model, paper_load(), test::kCtSpeedRadS);
    ADD_FAILURE() << "the rigid-ring dynamics took a flexible ring";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'flexible_ring'"), std::string::npos) << e.what();
  }
}

TEST(FlexibleRingStatics, AScenarioTakesAFlexibleRing) {
  // Scenarios run the flexible ring (make_ring_dynamics); the file is read as any other.
  const std::string yaml = "name: x\nduration_s: 1\nbearing_file: " + bearing_file("ct_gantry_flexible.yaml") +
                           "\nspeed: {initial_speed_rpm: 180}\n";
  const Scenario sc = Scenario::from_string(yaml, "flexible_scenario.yaml");
  EXPECT_TRUE(load_bearing_config(sc.bearing_file()).flexible_ring.present);
}

TEST(FlexibleRingStatics, ASweepsStaticCaseIsTheFlexibleRingsEquilibrium) {
  // A sweep over a flexible base file: each static case solves the flexible equilibrium, so
  // its peak ball load is the flexible ring's (not the rigid ring's, which differs by more
  // than 1 % here), and the rigid-body modes come from the stiffness condensed onto them.
  const std::string yaml =
      "bearing: ct_gantry_flexible.yaml\nanalysis: static\noperating_point: {force_N: [6800, 0, 0], "
      "moment_Nm: [0, 2100]}\nstudies:\n  - parameter: radial_load_N\n    values: [6800]\n";
  const SweepDefinition d = sweep_definition_from_string(yaml, "flexible_sweep.yaml", test::config_path("bearings"));
  const std::vector<SweepCase> cases = sweep_cases(d);
  ASSERT_EQ(cases.size(), 1u);
  const SweepResult r = run_sweep_case(cases[0], false);
  ASSERT_TRUE(r.ok) << r.error;
  const FlexibleBearing flexible{BearingModel(ct_flexible())};
  const FlexibleStaticSolution expected = solve_flexible_static(flexible, paper_load());
  const StaticSolution rigid = solve_static(flexible.model(), paper_load());
  EXPECT_NEAR(r.statics.max_ball_load_N, expected.rigid_coordinates.max_ball_load_N,
              1e-9 * expected.rigid_coordinates.max_ball_load_N);
  ASSERT_GT(std::abs(expected.rigid_coordinates.max_ball_load_N - rigid.max_ball_load_N), 0.01 * rigid.max_ball_load_N);
  // The condensed stiffness is softer than the rigid ring's (the ring gives way): the lowest
  // rigid-body mode lies below the rigid ring's.
  const Matrix5 k = 0.5 * (rigid.stiffness + rigid.stiffness.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix5> eig(k, flexible.model().mass_matrix(), Eigen::EigenvaluesOnly);
  EXPECT_LT(r.ring_modes_hz[0], std::sqrt(eig.eigenvalues()[0]) / (2.0 * test::kPi));
}

}  // namespace
}  // namespace bearing_sim
