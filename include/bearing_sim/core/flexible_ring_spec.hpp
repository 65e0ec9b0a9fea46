#pragma once
// The bearing file's `flexible_ring:` block (docs/bearing_file.md), in SI units once loaded:
// the rotating ring as a thin elastic ring described by its bending modes (docs/model.md 18).
namespace bearing_sim {

// Why the rigid-ring dynamics (BearingDynamics) refuse a flexible ring: FlexibleDynamics runs
// it, and make_ring_dynamics (ring_dynamics.hpp) chooses between them for every front.
inline constexpr const char* kFlexibleRingNotRigid =
    "the rigid-ring dynamics (BearingDynamics) do not take a flexible ring: FlexibleDynamics runs it "
    "(make_ring_dynamics chooses by this block)";

struct FlexibleRingSpec {
  bool present = false;            // no block: the ring is rigid (the default)
  double centroid_radius_m = 0.0;  // R, of the section's centroid
  double area_m2 = 0.0;            // A
  // Second moments of the section: in-plane bending (about the axial direction, fibres spread
  // radially) and out-of-plane bending (about the radial direction, fibres spread axially).
  double in_plane_second_moment_m4 = 0.0;
  double out_of_plane_second_moment_m4 = 0.0;
  double torsion_constant_m4 = 0.0;  // J, St Venant
  double youngs_modulus_Pa = 0.0;
  double shear_modulus_Pa = 0.0;
  double density_kg_m3 = 0.0;
  int in_plane_max_order = 0;      // modes n = 2..this (>= 2)
  int out_of_plane_max_order = 0;  // modes n = 2..this, or 0: none
  double modal_damping_ratio = 0.0;
  // Seat (mounting) stiffness per unit length of the ring's circumference, N/m^2.
  double mounting_radial_stiffness_N_per_m2 = 0.0;
  double mounting_axial_stiffness_N_per_m2 = 0.0;
};

}  // namespace bearing_sim
