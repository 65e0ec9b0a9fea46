#pragma once
// The per-ball contact force loop of BearingModel::contact_force (internal to the core),
// over runs of balls of the same row: in a row the groove centres share their axial
// position and contact-normal slope, so the ring's translation and tilt enter as per-row
// constants and the moments follow from two per-row sums (MODEL.md section 2).
// One Google Highway kernel compiled for every SIMD target of the architecture (SSE4, AVX2,
// AVX-512, ...) and picked at run time for the CPU, so that a portable binary package runs
// the widest vectors the machine has; and a plain scalar loop, the reference it is tested
// against.
#include <cstdint>
#include <vector>

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

// The reference: one ball after the other, no SIMD.
ContactSums contact_sums_scalar(const ContactKernelInput& in);
// The SIMD kernel for the best target of this CPU, over n_runs runs in one call (one
// dispatch per force evaluation: for small bearings the per-call cost matters).
void contact_sums_simd(const ContactKernelInput* runs, int n_runs, ContactSums* out);
// Name of the Highway target contact_sums_simd runs on ("AVX2", "AVX3", "SSE4", ...).
const char* contact_kernel_target_name();
// Every Highway target compiled into the kernel (HWY_* bits), whether this CPU runs it or not.
std::vector<std::int64_t> contact_kernel_compiled_targets();

}  // namespace bearing_sim::detail
