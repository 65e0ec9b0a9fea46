// The flexible ring's modes (docs/model.md 18.1) against the thin-ring closed forms, and the
// bearing file's flexible_ring block: defaults, and every bad value named by its key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/flexible_bearing.hpp"
#include "bearing_sim/core/ring_modes.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::bearing_file;
using test::kPi;

// Hoppe (1871) / Love, in-plane inextensional bending of a free thin ring.
double hoppe_rad_s(const FlexibleRingSpec& s, int n) {
  const double R = s.centroid_radius_m;
  return std::sqrt(s.youngs_modulus_Pa * s.in_plane_second_moment_m4 / (s.density_kg_m3 * s.area_m2 * std::pow(R, 4))) *
         n * (n * n - 1.0) / std::sqrt(n * n + 1.0);
}

// Soedel, "Vibrations of Shells and Plates": out-of-plane bending with torsion, rotary inertia neglected.
double out_of_plane_rad_s(const FlexibleRingSpec& s, int n) {
  const double R = s.centroid_radius_m, ei = s.youngs_modulus_Pa * s.out_of_plane_second_moment_m4;
  const double gj = s.shear_modulus_Pa * s.torsion_constant_m4;
  return std::sqrt(ei / (s.density_kg_m3 * s.area_m2 * std::pow(R, 4)) * n * n * std::pow(n * n - 1.0, 2) /
                   (n * n + ei / gj));
}

// The free ring's frequencies from the assembled system the dynamics integrate: the
// generalized eigenproblem of the ring's stiffness and mass blocks, no contacts.
Eigen::VectorXd assembled_ring_frequencies(const FlexibleBearing& b) {
  const int m = b.size() - 5;
  const Eigen::MatrixXd k = b.ring_stiffness().tail(m).asDiagonal();
  const Eigen::MatrixXd mass = b.mass_matrix().bottomRightCorner(m, m);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(k, mass);
  return eig.eigenvalues().cwiseSqrt();
}

const double kRel = 1e-12;  // the same formula in different arithmetic: rounding only

TEST(RingModes, TheCtRingsFreeModesAreTheThinRingClosedForms) {
  const BearingConfig c = load_bearing_config(bearing_file("ct_gantry_flexible.yaml"));
  const FlexibleRingSpec& s = c.flexible_ring;
  ASSERT_TRUE(s.present);
  const FlexibleBearing bearing{BearingModel(c)};
  const Eigen::VectorXd assembled = assembled_ring_frequencies(bearing);
  // Expected, ascending with each value twice (cos and sin): in-plane and out-of-plane n = 2..6.
  std::vector<double> expected;
  for (int n = 2; n <= 6; ++n) {
    expected.push_back(hoppe_rad_s(s, n));
    expected.push_back(out_of_plane_rad_s(s, n));
  }
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(assembled.size(), 2 * static_cast<int>(expected.size()));
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(assembled[2 * i], expected[i], kRel * expected[i]);
    EXPECT_NEAR(assembled[2 * i + 1], expected[i], kRel * expected[i]);
  }
  // The figures for this section (46 mm radial x 35 mm axial, 1.2 m ring): n = 2, 3, 4
  // in-plane near 85, 240, 460 Hz (rounded there to 2-3 digits: 1 %).
  for (const auto& [n, hz] : {std::pair{2, 85.0}, {3, 240.0}, {4, 460.0}})
    EXPECT_NEAR(hoppe_rad_s(s, n) / (2 * kPi), hz, 0.01 * hz) << "n = " << n;
  // The ring's mass, 2 pi R rho A: the "about 47 kg", the paper's 46.3 kg ring.
  EXPECT_NEAR(ring_mass_kg(s), 46.6, 0.05);
  for (const RingMode& m : bearing.modes())
    std::cout << (m.direction == RingModeDirection::Radial ? "in-plane" : "out-of-plane") << " n = " << m.order << ": "
              << m.frequency_rad_s() / (2 * kPi) << " Hz\n";
}

TEST(RingModes, ASeatStiffnessAddsItsShareOfEachModesKineticEnergy) {
  // A seat k_m (N/m^2) on the radial displacement: omega^2 = omega_free^2 + k_m / (rho A) times
  // the radial share of the mode's kinetic energy, n^2 / (n^2 + 1) in-plane (the tangential
  // motion v = -(a/n) sin n theta carries the rest); out-of-plane modes move axially only, so an
  // axial seat adds k_m / (rho A) itself.
  BearingConfig c = load_bearing_config(bearing_file("ct_gantry_flexible.yaml"));
  FlexibleRingSpec& s = c.flexible_ring;
  s.mounting_radial_stiffness_N_per_m2 = 5e8;
  s.mounting_axial_stiffness_N_per_m2 = 2e8;
  const double rho_a = s.density_kg_m3 * s.area_m2;
  for (const RingMode& m : ring_modes(s)) {
    const int n = m.order;
    const double expected =
        m.direction == RingModeDirection::Radial
            ? std::sqrt(std::pow(hoppe_rad_s(s, n), 2) +
                        s.mounting_radial_stiffness_N_per_m2 / rho_a * n * n / (n * n + 1.0))
            : std::sqrt(std::pow(out_of_plane_rad_s(s, n), 2) + s.mounting_axial_stiffness_N_per_m2 / rho_a);
    EXPECT_NEAR(m.frequency_rad_s(), expected, kRel * expected) << "n = " << n;
    // Damping: the file's ratio of each mounted mode, c = 2 zeta sqrt(k m).
    EXPECT_NEAR(m.modal_damping_Ns_per_m / (2.0 * m.modal_mass_kg * m.frequency_rad_s()), s.modal_damping_ratio, 1e-12);
  }
}

// A valid file with a flexible_ring block whose lines are `ring_lines`.
std::string with_ring(const std::string& ring_lines) {
  return "name: t\nballs_per_row: 16\nball_diameter_mm: 10\npitch_diameter_mm: 200\n"
         "inner_groove_curvature: 0.52\nouter_groove_curvature: 0.52\nrotating_mass_kg: 2\n"
         "flexible_ring:\n" +
         ring_lines;
}

void expect_key_error(const std::string& ring_lines, const std::string& key) {
  test::expect_config_error([&] { bearing_config_from_string(with_ring(ring_lines), "ring.yaml"); },
                            {"ring.yaml: key 'flexible_ring." + key + "'"}, ring_lines);
}

TEST(RingModes, TheBlocksDefaultsFollowTheRingsEnvelopeAndMaterial) {
  const BearingConfig c = bearing_config_from_string(
      with_ring("  section_width_mm: 15\n  section_height_mm: 10\n  in_plane_max_order: 4\n"), "ring.yaml");
  const FlexibleRingSpec& s = c.flexible_ring;
  // Outer diameter dm + 2 d = 220 mm: the centroid half the 10 mm height inside it.
  EXPECT_NEAR(s.centroid_radius_m, 0.105, 1e-15);
  EXPECT_NEAR(s.area_m2, 150e-6, 1e-18);
  EXPECT_NEAR(s.in_plane_second_moment_m4, 15e-3 * 1e-6 / 12.0, 1e-24);  // b h^3 / 12
  EXPECT_EQ(s.youngs_modulus_Pa, c.material.youngs_modulus_Pa);
  EXPECT_EQ(s.density_kg_m3, c.material.density_kg_m3);
  EXPECT_EQ(s.out_of_plane_max_order, 0);
  EXPECT_EQ(s.modal_damping_ratio, 0.01);
  EXPECT_EQ(ring_modes(s).size(), 3u);
  // Without the block the ring is rigid.
  EXPECT_FALSE(load_bearing_config(bearing_file("ct_gantry_physical.yaml")).flexible_ring.present);
}

TEST(RingModes, BadValuesAreErrorsNamingTheKey) {
  const std::string ok = "  section_width_mm: 15\n  section_height_mm: 10\n";
  expect_key_error(ok + "  in_plane_max_order: 4\n  youngs_modulus_GPa: -200\n", "youngs_modulus_GPa");
  expect_key_error(ok + "  in_plane_max_order: 0\n", "in_plane_max_order");
  expect_key_error(ok + "  in_plane_max_order: 1\n", "in_plane_max_order");
  expect_key_error(ok, "in_plane_max_order");  // required
  expect_key_error(ok + "  in_plane_max_order: 4\n  density_kg_m3: .nan\n", "density_kg_m3");
  expect_key_error(ok + "  in_plane_max_order: 4\n  out_of_plane_max_order: 1\n", "out_of_plane_max_order");
  expect_key_error(ok + "  in_plane_max_order: 4\n  modal_damping_ratio: 2\n", "modal_damping_ratio");
  expect_key_error(ok + "  in_plane_max_order: 4\n  mounting_radial_stiffness_N_per_m2: -1\n",
                   "mounting_radial_stiffness_N_per_m2");
  expect_key_error(ok + "  in_plane_max_order: 4\n  ring: fixed\n", "ring");
  expect_key_error(ok + "  in_plane_max_order: 4\n  stiffness: 3\n", "stiffness");
  expect_key_error("  section_width_mm: 15\n  section_height_mm: -10\n  in_plane_max_order: 4\n", "section_height_mm");
  expect_key_error("  section_width_mm: 15\n  in_plane_max_order: 4\n", "section_height_mm");
  expect_key_error(ok + "  in_plane_max_order: 4\n  centroid_radius_mm: 12\n", "centroid_radius_mm");
}

}  // namespace
}  // namespace bearing_sim
