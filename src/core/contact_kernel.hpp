#pragma once
// The per-ball contact force loop of BearingModel::contact_force (internal to the core):
// the force and the moments on the ring follow from seven sums over the balls
// (docs/model.md section 5.4).
// One Google Highway kernel compiled for every SIMD target of the architecture (SSE4, AVX2,
// AVX-512, ...) and picked at run time for the CPU, so that a portable binary package runs
// the widest vectors the machine has; and a plain scalar loop, the reference it is tested
// against.
#include <cstdint>
#include <vector>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::detail {

// Every ball of a set (both rows in one pass: for small bearings a call per row costs as
// much as the balls). Plain aggregates, no default member initializers: the force
// evaluation fills them on the stack for every call.
struct ContactKernelInput {
  double cos_cage, sin_cage;
  double groove_centre_radius, cos_a0, groove_centre_distance;  // radius: of the moving ring's groove centre
  double clearance, sign, stiffness, damping;
  const double* q;
  const double* q_dot;
  const double* cos_base;
  const double* sin_base;
  const double* groove_centre_z;  // per ball (of its row); groove centre of the moving ring
  const double* normal_z;         // per ball (of its row)
  const double* offset;           // deflection offsets (without the race spalls given as windows)
  int n;
  // The race spalls (in the kernel, so that a bearing whose offsets vary only under them
  // needs no per-call offsets: docs/model.md 10.7).
  const Imperfections::SpallWindow* spalls;
  int spall_count;
};

// Sums over the balls of s_b v_b (s_b = Q_b / |v_b|), of s_b v_bz cos(phi_b), s_b v_bz sin(phi_b),
// and of s_b v_bx z_b, s_b v_by z_b (z_b: axial coordinate of the ball's groove centre in the
// moving ring, where its displacement and moment arm are taken).
struct ContactSums {
  double x, y, z, z_cos, z_sin, x_z, y_z;
};

// The reference: one ball after the other, no SIMD.
ContactSums contact_sums_scalar(const ContactKernelInput& in);
// The SIMD kernel for the best target of this CPU.
ContactSums contact_sums_simd(const ContactKernelInput& in);
// Name of the Highway target contact_sums_simd runs on ("AVX2", "AVX3", "SSE4", ...).
const char* contact_kernel_target_name();
// Every Highway target compiled into the kernel (HWY_* bits), whether this CPU runs it or not.
std::vector<std::int64_t> contact_kernel_compiled_targets();

}  // namespace bearing_sim::detail
