#pragma once
// The per-ball contact force loop of BearingModel::contact_force (internal to the core).
// One portable loop that the compiler vectorizes, and, where the CPU has AVX-512, the
// same arithmetic written with its reciprocal square root (two Newton steps restore full
// double precision), which replaces the two square roots and the division per ball.
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::detail {

struct ContactKernelInput {
  double cos_cage = 1.0, sin_cage = 0.0;
  double groove_centre_radius = 0.0, cos_a0 = 1.0, groove_centre_distance = 0.0;
  double clearance = 0.0, sign = 1.0, stiffness = 0.0, damping = 0.0;
  const double* q = nullptr;
  const double* q_dot = nullptr;
  const double* cos_base = nullptr;
  const double* sin_base = nullptr;
  const double* groove_centre_z = nullptr;
  const double* normal_z = nullptr;
  const double* offset = nullptr;
  int n = 0;
};

Vector5 contact_force_portable(const ContactKernelInput& in);
bool avx512_kernel_available();
Vector5 contact_force_avx512(const ContactKernelInput& in);  // only if avx512_kernel_available()

}  // namespace bearing_sim::detail
