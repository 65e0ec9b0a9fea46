#pragma once
// The per-ball contact force loop of BearingModel::contact_force (internal to the core),
// over one run of balls of the same row: in a row the groove centres share their axial
// position and contact-normal slope, so the ring's translation and tilt enter as per-row
// constants and the moments follow from two per-row sums (MODEL.md section 2).
// One portable loop that the compiler vectorizes, and, where the CPU has AVX-512, the same
// arithmetic written with its intrinsics: masked loads for the tail and a branch-free
// contact test, about twice as fast as what the compiler makes of the portable loop.
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::detail {

struct ContactKernelInput {
  double cos_cage = 1.0, sin_cage = 0.0;
  double groove_centre_radius = 0.0, cos_a0 = 1.0, groove_centre_distance = 0.0;
  double clearance = 0.0, sign = 1.0, stiffness = 0.0, damping = 0.0;
  double groove_centre_z = 0.0;  // of the row
  double normal_z = 0.0;         // of the row
  const double* q = nullptr;
  const double* q_dot = nullptr;
  const double* cos_base = nullptr;
  const double* sin_base = nullptr;
  const double* offset = nullptr;
  int n = 0;
};

// Sums over the run of s_b v_b (s_b = Q_b / |v_b|), and of s_b v_bz cos(phi_b), s_b v_bz sin(phi_b).
struct ContactSums {
  double x = 0.0, y = 0.0, z = 0.0, z_cos = 0.0, z_sin = 0.0;
};

ContactSums contact_sums_portable(const ContactKernelInput& in);
bool avx512_kernel_available();
ContactSums contact_sums_avx512(const ContactKernelInput& in);  // only if avx512_kernel_available()

}  // namespace bearing_sim::detail
