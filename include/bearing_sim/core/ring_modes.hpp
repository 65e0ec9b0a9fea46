#pragma once
// Bending modes of a free thin circular ring (docs/model.md section 18.1): in-plane
// inextensional modes (radial displacement w = a cos n theta, tangential v = -(a/n) sin n theta:
// the centre line does not stretch) and out-of-plane modes (axial displacement, with the
// section's twist that minimises the strain energy). Each order n >= 2 has a cos and a sin
// coordinate with the same modal mass, stiffness and damping; n = 0 and 1 are the rigid
// ring's motion, which the rigid-body coordinates already carry.
#include <vector>

#include "bearing_sim/core/flexible_ring_spec.hpp"

namespace bearing_sim {

enum class RingModeDirection { Radial, Axial };

struct RingMode {
  int order = 2;  // n
  RingModeDirection direction = RingModeDirection::Radial;
  // Per coordinate a, the amplitude (m) of the centre line's radial (in-plane) or axial
  // (out-of-plane) displacement: kinetic energy m a'^2 / 2, strain energy k a^2 / 2.
  double modal_mass_kg = 0.0;
  double bending_stiffness_N_per_m = 0.0;   // of the free ring
  double mounting_stiffness_N_per_m = 0.0;  // of the seat
  double modal_damping_Ns_per_m = 0.0;      // 2 zeta sqrt(k m), k with the seat
  double stiffness_N_per_m() const { return bending_stiffness_N_per_m + mounting_stiffness_N_per_m; }
  double frequency_rad_s() const;  // sqrt(k / m), on its seat, without the balls
};

// The modes the spec asks for: in-plane n = 2..in_plane_max_order, then out-of-plane
// n = 2..out_of_plane_max_order. The ring's generalized coordinates are (cos, sin) per mode,
// in this order: coordinate 2 i is mode i's cos, 2 i + 1 its sin.
std::vector<RingMode> ring_modes(const FlexibleRingSpec& spec);

// Mass of the whole ring, 2 pi R rho A, kg.
double ring_mass_kg(const FlexibleRingSpec& spec);

}  // namespace bearing_sim
