#pragma once
// The per-ball contact loop of the flexible ring in the load's frame (internal to the core;
// docs/model.md 18.4): the generalized contact force on (q, b), with the ring's modal pairs b
// taken at the balls' own azimuths. One Google Highway kernel for every SIMD target, picked at
// run time, and the scalar loop it is tested against (as contact_kernel.hpp).
#include <vector>

namespace bearing_sim::detail {

struct FlexibleKernelInput {
  double cos_cage, sin_cage;
  double groove_centre_radius, cos_a0, groove_centre_distance;
  double clearance, sign, stiffness, damping;
  const double* q;      // rigid coordinates (5)
  const double* q_dot;  // and their rates
  // Per ring mode: its order, 1 if radial (0: axial), its (cos, sin) pair in the load's frame
  // and the pair's rate as a material point of the ring sees it (b' - n Omega J b).
  int modes, max_order;
  const int* order;
  const int* radial;
  // Per order k = 0..max_order, the index of its radial mode and of its axial mode, -1 if
  // none (the SIMD kernel loads each order's shapes once for both).
  const int* radial_mode_of_order;
  const int* axial_mode_of_order;
  const double* mode_position;  // 2 per mode
  const double* mode_rate;      // 2 per mode
  // cos k beta_b and sin k beta_b of the balls' azimuths at cage angle 0, k = 0..max_order,
  // one row of `stride` (>= n, a multiple of 64, zero past n) per k: the SIMD kernel takes the
  // shapes at phi = beta + cage from them, with the modal pairs turned by the cage angle.
  const double* base_cos_n;
  const double* base_sin_n;
  int stride;
  // Per ball, as BallArrays; offset: deflection offsets with the imperfections at this phase.
  const double* cos_base;
  const double* sin_base;
  const double* groove_centre_z;
  const double* normal_z;
  const double* offset;
  int n;
  // Rows whose balls share azimuths (ball j of each row at row 0's ball j's azimuth: rows in
  // phase, no spacing scatter), 1 or 2: the SIMD kernel takes the ring's displacement at an
  // azimuth once for all of them. azimuths = n / rows_sharing; row_stride >= azimuths, a
  // multiple of 64, the per-ball scratch's row.
  int rows_sharing, azimuths, row_stride;
  // Scratch of flexible_kernel_work_size doubles, the caller's (no thread_local: the core is
  // built with the initial-exec TLS model, whose static block a dlopen'ed nodelet shares).
  double* work;
};

inline int flexible_kernel_work_size(int rows_sharing, int row_stride, int modes, int max_order) {
  return 2 * rows_sharing * row_stride + 4 * modes + 2 * (max_order + 1);
}

// force: 5 + 2 modes generalized forces (forces, moments, modal), overwritten.
void flexible_contact_scalar(const FlexibleKernelInput& in, double* force);
void flexible_contact_simd(const FlexibleKernelInput& in, double* force);

}  // namespace bearing_sim::detail
