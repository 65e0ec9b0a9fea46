#include "bearing_sim/core/ring_modes.hpp"

#include <cmath>

#include "bearing_sim/core/constants.hpp"

namespace bearing_sim {
namespace {
// In-plane, from the energies over the circumference (docs/model.md 18.1):
// T = rho A R / 2 integral (w'^2 + v'^2) dtheta = rho A R pi (1 + 1/n^2) a'^2 / 2;
// U = E I / (2 R^3) integral (w'' + w)^2 dtheta = pi E I (n^2 - 1)^2 / R^3 a^2 / 2;
// the seat, k_r / 2 integral w^2 R dtheta = pi R k_r a^2 / 2.
RingMode in_plane_mode(const FlexibleRingSpec& s, int n) {
  const double R = s.centroid_radius_m, nn = static_cast<double>(n) * n;
  RingMode m;
  m.order = n;
  m.direction = RingModeDirection::Radial;
  m.modal_mass_kg = s.density_kg_m3 * s.area_m2 * R * kPi * (1.0 + 1.0 / nn);
  m.bending_stiffness_N_per_m =
      kPi * s.youngs_modulus_Pa * s.in_plane_second_moment_m4 * (nn - 1.0) * (nn - 1.0) / (R * R * R);
  m.mounting_stiffness_N_per_m = kPi * R * s.mounting_radial_stiffness_N_per_m2;
  return m;
}

// Out-of-plane, axial displacement u = a cos n theta and twist beta = (x / R) cos n theta:
// bending curvature (n^2 a - x) / R^2 and twist rate n (x - a) / R^2 (both zero for the rigid
// tilt n = 1, x = a), U = pi / (2 R^3) (E I (n^2 a - x)^2 + G J n^2 (x - a)^2), minimised
// over x (the twist's inertia neglected); T = rho A R pi a'^2 / 2 (axial motion only).
RingMode out_of_plane_mode(const FlexibleRingSpec& s, int n) {
  const double R = s.centroid_radius_m, nn = static_cast<double>(n) * n;
  const double ei = s.youngs_modulus_Pa * s.out_of_plane_second_moment_m4;
  const double gj = s.shear_modulus_Pa * s.torsion_constant_m4;
  const double x = nn * (ei + gj) / (ei + gj * nn);  // twist amplitude times R, per unit a
  RingMode m;
  m.order = n;
  m.direction = RingModeDirection::Axial;
  m.modal_mass_kg = s.density_kg_m3 * s.area_m2 * R * kPi;
  m.bending_stiffness_N_per_m = kPi / (R * R * R) * (ei * (nn - x) * (nn - x) + gj * nn * (x - 1.0) * (x - 1.0));
  m.mounting_stiffness_N_per_m = kPi * R * s.mounting_axial_stiffness_N_per_m2;
  return m;
}

void set_damping(double ratio, RingMode* m) {
  m->modal_damping_Ns_per_m = 2.0 * ratio * std::sqrt(m->stiffness_N_per_m() * m->modal_mass_kg);
}

}  // namespace

double RingMode::frequency_rad_s() const { return std::sqrt(stiffness_N_per_m() / modal_mass_kg); }

std::vector<RingMode> ring_modes(const FlexibleRingSpec& spec) {
  std::vector<RingMode> modes;
  if (!spec.present) return modes;
  for (int n = 2; n <= spec.in_plane_max_order; ++n) modes.push_back(in_plane_mode(spec, n));
  for (int n = 2; n <= spec.out_of_plane_max_order; ++n) modes.push_back(out_of_plane_mode(spec, n));
  for (RingMode& m : modes) set_damping(spec.modal_damping_ratio, &m);
  return modes;
}

double ring_mass_kg(const FlexibleRingSpec& spec) {
  return 2.0 * kPi * spec.centroid_radius_m * spec.density_kg_m3 * spec.area_m2;
}

}  // namespace bearing_sim
