// A body carried by the rotating ring (the CT gantry's rotor): its mass matrix about the
// bearing centre, the ring's modes with it, and the bearing file's carried_body mapping.
#include <gtest/gtest.h>

#include <Eigen/SVD>

#include <iostream>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::bearing_file;

// Velocity of the body's centre of gravity and its angular velocity for a unit rate of DOF i
// of q = (x, y, z, theta_x, theta_y): v = u' + omega x c with c = (0, 0, z_cg).
void unit_rates(int i, double z_cg, Eigen::Vector3d* v, Eigen::Vector3d* omega) {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();
  *omega = Eigen::Vector3d::Zero();
  if (i < 3) u[i] = 1.0;
  else (*omega)[i - 3] = 1.0;
  *v = u + omega->cross(Eigen::Vector3d(0.0, 0.0, z_cg));
}

// The mass matrix from the kinetic energy, M_ij = m v_i . v_j + J omega_i . omega_j (plus the
// ring's own diagonal), built here with vector algebra rather than the model's closed form.
Matrix5 mass_from_kinetic_energy(const BearingConfig& c) {
  const CarriedBody& b = c.carried_body;
  Matrix5 m = Matrix5::Zero();
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      Eigen::Vector3d vi, wi, vj, wj;
      unit_rates(i, b.centre_of_gravity_axial_m, &vi, &wi);
      unit_rates(j, b.centre_of_gravity_axial_m, &vj, &wj);
      // Transverse inertia only: the model's theta_x, theta_y rates have no z component.
      m(i, j) = b.mass_kg * vi.dot(vj) + b.transverse_inertia_kg_m2 * wi.head<2>().dot(wj.head<2>());
    }
  for (int i = 0; i < 3; ++i) m(i, i) += c.rotating_mass_kg;
  for (int i = 3; i < 5; ++i) m(i, i) += c.tilt_inertia_kg_m2;
  return m;
}

TEST(CarriedBody, ThePhysicalCtFileCarriesTheRotorWhoseWeightIsThePapersLoad) {
  const BearingConfig c = load_bearing_config(bearing_file("ct_gantry_physical.yaml"));
  ASSERT_TRUE(c.carried_body.present());
  // Its weight at its centre of gravity is the paper's load: 6800 N and 2100 N*m (to the
  // file's 4 significant digits).
  const double weight = c.carried_body.mass_kg * 9.80665;
  EXPECT_NEAR(weight, 6800.0, 0.5);
  EXPECT_NEAR(weight * c.carried_body.centre_of_gravity_axial_m, 2100.0, 0.5);
  // Everything else is the paper's bearing.
  const BearingConfig paper = load_bearing_config(bearing_file("ct_gantry_lyc.yaml"));
  EXPECT_FALSE(paper.carried_body.present());
  EXPECT_EQ(c.balls_per_row, paper.balls_per_row);
  EXPECT_EQ(c.rotating_mass_kg, paper.rotating_mass_kg);
  EXPECT_EQ(c.contact_damping_Ns_per_m, paper.contact_damping_Ns_per_m);
}

TEST(CarriedBody, MassMatrixIsTheKineticEnergysOfRingAndBody) {
  const BearingConfig c = load_bearing_config(bearing_file("ct_gantry_physical.yaml"));
  const Matrix5 m = BearingModel(c).mass_matrix();
  const Matrix5 expected = mass_from_kinetic_energy(c);
  // Sums of a few products of numbers of order 1e3: rounding at 1e-12 of the largest entry.
  EXPECT_LT((m - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff()) << m << "\n\n" << expected;
  EXPECT_GT(Eigen::LLT<Matrix5>(m).info() == Eigen::Success, 0) << "not positive definite";
}

// With the centre of gravity at the bearing centre the body only adds to the ring's mass and
// tilt inertia: the modes equal those of a ring that heavy (another code path, diagonal).
TEST(CarriedBody, OnTheBearingCentreTheBodyIsJustMoreMassAndInertia) {
  BearingConfig with = test::ct_bearing();
  with.carried_body.mass_kg = 693.4;
  with.carried_body.centre_of_gravity_axial_m = 0.0;
  with.carried_body.transverse_inertia_kg_m2 = 84.0;
  BearingConfig heavier = test::ct_bearing();
  heavier.rotating_mass_kg += 693.4;
  heavier.tilt_inertia_kg_m2 += 84.0;
  const Vector5 a = BearingDynamics::natural_frequencies_rad_s(BearingModel(with), test::ct_load());
  const Vector5 b = BearingDynamics::natural_frequencies_rad_s(BearingModel(heavier), test::ct_load());
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-9 * b.maxCoeff()) << a.transpose() << "\n" << b.transpose();
}

// Off the centre, every natural frequency makes K - omega^2 M singular with the coupled M
// (checked with a singular value decomposition, not the generalized eigensolver that found
// them); and the rotor brings the lowest mode of the CT ring from the rigid ring's ~1 kHz
// towards the ball-pass frequency: with ~16 times the mass a translation mode falls about
// 4 times (sqrt 16).
TEST(CarriedBody, NaturalFrequenciesSolveTheCoupledEigenproblem) {
  const BearingModel model(load_bearing_config(bearing_file("ct_gantry_physical.yaml")));
  const Vector5 load = test::ct_load();
  const Vector5 omega = BearingDynamics::natural_frequencies_rad_s(model, load);
  const Matrix5 k = solve_static(model, load).stiffness;
  const Matrix5 m = model.mass_matrix();
  for (int i = 0; i < 5; ++i) {
    const Matrix5 d = 0.5 * (k + k.transpose()) - omega[i] * omega[i] * m;
    const double smallest = Eigen::JacobiSVD<Matrix5>(d).singularValues()[4];
    // The eigenvalues are exact to ~1e-15 of the largest; K's entries span 1e8..1e10.
    EXPECT_LT(smallest, 1e-9 * k.norm()) << "mode " << i << " at " << omega[i] / (2 * test::kPi) << " Hz";
  }
  const Vector5 rigid_ring = BearingDynamics::natural_frequencies_rad_s(
      BearingModel(load_bearing_config(bearing_file("ct_gantry_lyc.yaml"))), load);
  std::cout << "lowest mode: ring alone " << rigid_ring.minCoeff() / (2 * test::kPi) << " Hz, with the rotor "
            << omega.minCoeff() / (2 * test::kPi) << " Hz\n";
  EXPECT_LT(omega.minCoeff(), rigid_ring.minCoeff() / 2.0);
}

TEST(CarriedBody, BadMappingsAreNamed) {
  const std::string base = test::read_text(bearing_file("ct_gantry_lyc.yaml"));
  const auto error_of = [&](const std::string& body) {
    try {
      bearing_config_from_string(base + "carried_body: " + body + "\n", "test.yaml");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("{centre_of_gravity_axial_mm: 300, transverse_inertia_kg_m2: 80}").find("carried_body.mass_kg"),
            std::string::npos);
  EXPECT_NE(error_of("{mass_kg: 600, transverse_inertia_kg_m2: -1}").find("carried_body.transverse_inertia_kg_m2"),
            std::string::npos);
  EXPECT_NE(error_of("{mass_kg: 600, transverse_inertia_kg_m2: 80, colour: red}").find("colour"), std::string::npos);
  EXPECT_NE(error_of("{mass_kg: 600, transverse_inertia_kg_m2: 80, centre_of_gravity_axial_mm: 1e9}")
                .find("centre_of_gravity_axial_mm"),
            std::string::npos);
}

}  // namespace
}  // namespace bearing_sim
