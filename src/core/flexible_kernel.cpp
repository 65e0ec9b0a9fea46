// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "flexible_kernel.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "dispatch.hpp"
#include "flexible_kernel.hpp"
#include "padded_balls.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

// Per ball (docs/model.md 18.4): the groove centre moves by the rigid coordinates and by the
// ring's modes at the ball's azimuth phi, u = (q0 + q4 z + w cphi, q1 - q3 z + w sphi,
// q2 + q3 rho sphi - q4 rho cphi + u_ring), w and u_ring the sums of the radial and axial
// modes' (cos n phi, sin n phi) . b; the load acts back on them through the same shapes.

HWY_BEFORE_NAMESPACE();
namespace bearing_sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The shapes at phi = beta + c: (cos n phi, sin n phi) = R(n c) (cos n beta, sin n beta), so
// p . shape(phi) = (R(n c)^T p) . shape(beta) and the force's projection sum_b g_b shape(phi_b)
// = R(n c) sum_b g_b shape(beta_b): the balls' base shapes are constants, the pairs turned
// once per call (the caller's in.mode_position and mode_rate are turned, the modal forces
// come back in the base frame). Pass 1 per vector of balls: displacement, load, rigid sums,
// and each ball's radial and axial force; pass 2 per mode: the projections.
void FlexibleContact(const FlexibleKernelInput& in, double* force) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const int modes = in.modes;
  const double sg = in.sign, rho = in.groove_centre_radius, A = in.groove_centre_distance;
  const double* q = in.q;
  const double* qd = in.q_dot;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V cc = hn::Set(d, in.cos_cage), sc = hn::Set(d, in.sin_cage);
  const V a_ca = hn::Set(d, A * in.cos_a0), a_v = hn::Set(d, A), v_rho = hn::Set(d, rho);
  const V a_g0 = hn::Set(d, A + in.clearance), v_sg = hn::Set(d, sg);
  const V kn = hn::Set(d, in.stiffness), cn = hn::Set(d, in.damping);
  const std::size_t stride = static_cast<std::size_t>(in.stride);
  // Per ball, pass 1 -> 2 (every vector of balls stores its lanes, zero when clear); the
  // work's first 2 stride doubles.
  double* const radial_force = in.work;
  double* const axial_force = in.work + stride;
  V f0 = zero, f1 = zero, f2 = zero, f3 = zero, f4 = zero;
  auto balls = [&](std::size_t b, V cb, V sb, V pz, V nz, V off) HWY_ATTR {
    const V cphi = hn::MulSub(cc, cb, hn::Mul(sc, sb));
    const V sphi = hn::MulAdd(sc, cb, hn::Mul(cc, sb));
    V w = zero, uz_ring = zero, w_dot = zero, uz_dot = zero;
    for (int i = 0; i < modes; ++i) {
      const std::size_t row = static_cast<std::size_t>(in.order[i]) * stride + b;
      const V c = hn::LoadU(d, in.base_cos_n + row), s = hn::LoadU(d, in.base_sin_n + row);
      const double* p = in.mode_position + 2 * i;
      const double* r = in.mode_rate + 2 * i;
      const V shape = hn::MulAdd(hn::Set(d, p[0]), c, hn::Mul(hn::Set(d, p[1]), s));
      const V rate = hn::MulAdd(hn::Set(d, r[0]), c, hn::Mul(hn::Set(d, r[1]), s));
      if (in.radial[i]) {
        w = hn::Add(w, shape);
        w_dot = hn::Add(w_dot, rate);
      } else {
        uz_ring = hn::Add(uz_ring, shape);
        uz_dot = hn::Add(uz_dot, rate);
      }
    }
    const V px = hn::Mul(v_rho, cphi), py = hn::Mul(v_rho, sphi);
    const V ux = hn::MulAdd(w, cphi, hn::MulAdd(hn::Set(d, q[4]), pz, hn::Set(d, q[0])));
    const V uy = hn::MulAdd(w, sphi, hn::NegMulAdd(hn::Set(d, q[3]), pz, hn::Set(d, q[1])));
    const V uz =
        hn::Add(hn::MulAdd(hn::Set(d, q[3]), py, hn::NegMulAdd(hn::Set(d, q[4]), px, hn::Set(d, q[2]))), uz_ring);
    const V vx = hn::NegMulAdd(v_sg, ux, hn::Mul(a_ca, cphi));
    const V vy = hn::NegMulAdd(v_sg, uy, hn::Mul(a_ca, sphi));
    const V vz = hn::NegMulAdd(v_sg, uz, hn::Mul(a_v, nz));
    const V norm = hn::Sqrt(hn::MulAdd(vx, vx, hn::MulAdd(vy, vy, hn::Mul(vz, vz))));
    const V deflection = hn::Add(hn::Sub(norm, a_g0), off);
    const auto touching = hn::Gt(deflection, zero);
    if (hn::AllFalse(d, touching)) {
      hn::StoreU(zero, d, radial_force + b);
      hn::StoreU(zero, d, axial_force + b);
      return;
    }
    const V dp = hn::IfThenElseZero(touching, deflection);
    const V inv_norm = hn::Div(one, norm);
    const V udx = hn::MulAdd(w_dot, cphi, hn::MulAdd(hn::Set(d, qd[4]), pz, hn::Set(d, qd[0])));
    const V udy = hn::MulAdd(w_dot, sphi, hn::NegMulAdd(hn::Set(d, qd[3]), pz, hn::Set(d, qd[1])));
    const V udz =
        hn::Add(hn::MulAdd(hn::Set(d, qd[3]), py, hn::NegMulAdd(hn::Set(d, qd[4]), px, hn::Set(d, qd[2]))), uz_dot);
    const V v_dot_u = hn::MulAdd(vx, udx, hn::MulAdd(vy, udy, hn::Mul(vz, udz)));
    // Q = kn dp^1.5 - cn sign (v . u') / |v|; the contact cannot pull.
    const V load = hn::NegMulAdd(hn::Mul(cn, v_sg), hn::Mul(v_dot_u, inv_norm), hn::Mul(hn::Mul(kn, dp), hn::Sqrt(dp)));
    const auto pressing = hn::And(touching, hn::Gt(load, zero));
    const V s = hn::IfThenElseZero(pressing, hn::Mul(hn::Mul(v_sg, load), inv_norm));
    const V fx = hn::Mul(s, vx), fy = hn::Mul(s, vy), fz = hn::Mul(s, vz);
    f0 = hn::Add(f0, fx);
    f1 = hn::Add(f1, fy);
    f2 = hn::Add(f2, fz);
    f3 = hn::Add(f3, hn::MulSub(py, fz, hn::Mul(pz, fy)));
    f4 = hn::Add(f4, hn::MulSub(pz, fx, hn::Mul(px, fz)));
    hn::StoreU(hn::MulAdd(fx, cphi, hn::Mul(fy, sphi)), d, radial_force + b);
    hn::StoreU(fz, d, axial_force + b);
  };
  const std::size_t n = static_cast<std::size_t>(in.n);
  std::size_t b = 0;
  for (; b + N <= n; b += N)
    balls(b, hn::LoadU(d, in.cos_base + b), hn::LoadU(d, in.sin_base + b), hn::LoadU(d, in.groove_centre_z + b),
          hn::LoadU(d, in.normal_z + b), hn::LoadU(d, in.offset + b));
  if (b < n) {
    // The rest through a padded copy (its padding adds exact zeros; the base shapes' rows
    // are padded to the stride).
    static_assert(HWY_MAX_BYTES / sizeof(double) <= PaddedBalls::kMaxLanes);
    const PaddedBalls p(in.cos_base, in.sin_base, in.groove_centre_z, in.normal_z, in.offset, b, n, N);
    balls(b, hn::LoadU(d, p.cos_base), hn::LoadU(d, p.sin_base), hn::LoadU(d, p.groove_centre_z),
          hn::LoadU(d, p.normal_z), hn::LoadU(d, p.offset));
  }
  force[0] = hn::GetLane(hn::SumOfLanes(d, f0));
  force[1] = hn::GetLane(hn::SumOfLanes(d, f1));
  force[2] = hn::GetLane(hn::SumOfLanes(d, f2));
  force[3] = hn::GetLane(hn::SumOfLanes(d, f3));
  force[4] = hn::GetLane(hn::SumOfLanes(d, f4));
  const std::size_t end = b < n ? b + N : b;  // the padded vector included (zero force there)
  for (int i = 0; i < modes; ++i) {
    const double* g = in.radial[i] ? radial_force : axial_force;
    const double* c = in.base_cos_n + static_cast<std::size_t>(in.order[i]) * stride;
    const double* s = in.base_sin_n + static_cast<std::size_t>(in.order[i]) * stride;
    V sum_c = zero, sum_s = zero;
    for (std::size_t k = 0; k < end; k += N) {
      const V gk = hn::LoadU(d, g + k);
      sum_c = hn::MulAdd(gk, hn::LoadU(d, c + k), sum_c);
      sum_s = hn::MulAdd(gk, hn::LoadU(d, s + k), sum_s);
    }
    force[5 + 2 * i] = hn::GetLane(hn::SumOfLanes(d, sum_c));
    force[6 + 2 * i] = hn::GetLane(hn::SumOfLanes(d, sum_s));
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace bearing_sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace bearing_sim::detail {
HWY_EXPORT(FlexibleContact);

void flexible_contact_simd(const FlexibleKernelInput& in, double* force) {
  // The pairs turned into the balls' base frame, R(n c)^T b, and the modal forces back.
  // The work after the kernel's 2 stride doubles: the turned pairs, cos k c and sin k c.
  double* const position = in.work + 2 * in.stride;
  double* const rate = position + 2 * in.modes;
  double* const cos_k = rate + 2 * in.modes;
  double* const sin_k = cos_k + in.max_order + 1;
  cos_k[0] = 1.0;
  sin_k[0] = 0.0;
  // By the recurrence (k <= max_order: a few ulp).
  for (int k = 1; k <= in.max_order; ++k) {
    cos_k[k] = cos_k[k - 1] * in.cos_cage - sin_k[k - 1] * in.sin_cage;
    sin_k[k] = sin_k[k - 1] * in.cos_cage + cos_k[k - 1] * in.sin_cage;
  }
  for (int i = 0; i < in.modes; ++i) {
    const double c = cos_k[in.order[i]], s = sin_k[in.order[i]];
    const double* p = in.mode_position + 2 * i;
    const double* r = in.mode_rate + 2 * i;
    position[2 * i] = c * p[0] + s * p[1];
    position[2 * i + 1] = -s * p[0] + c * p[1];
    rate[2 * i] = c * r[0] + s * r[1];
    rate[2 * i + 1] = -s * r[0] + c * r[1];
  }
  FlexibleKernelInput turned = in;
  turned.mode_position = position;
  turned.mode_rate = rate;
  BEARING_SIM_DISPATCH(FlexibleContact)(turned, force);
  for (int i = 0; i < in.modes; ++i) {
    const double f_c = force[5 + 2 * i], f_s = force[6 + 2 * i];
    const double c = cos_k[in.order[i]], s = sin_k[in.order[i]];
    force[5 + 2 * i] = c * f_c - s * f_s;
    force[6 + 2 * i] = s * f_c + c * f_s;
  }
}

void flexible_contact_scalar(const FlexibleKernelInput& in, double* force) {
  const double sg = in.sign, rho = in.groove_centre_radius, A = in.groove_centre_distance;
  const double aca = A * in.cos_a0, kn = in.stiffness, cn = in.damping;
  const double* q = in.q;
  const double* qd = in.q_dot;
  std::fill(force, force + 5 + 2 * in.modes, 0.0);
  std::vector<double> cos_n(in.max_order + 1, 1.0), sin_n(in.max_order + 1, 0.0);
  for (int b = 0; b < in.n; ++b) {
    const double cphi = in.cos_cage * in.cos_base[b] - in.sin_cage * in.sin_base[b];
    const double sphi = in.sin_cage * in.cos_base[b] + in.cos_cage * in.sin_base[b];
    if (in.max_order >= 1) {
      cos_n[1] = cphi;
      sin_n[1] = sphi;
    }
    for (int k = 2; k <= in.max_order; ++k) {
      cos_n[k] = cos_n[k - 1] * cphi - sin_n[k - 1] * sphi;
      sin_n[k] = sin_n[k - 1] * cphi + cos_n[k - 1] * sphi;
    }
    double w = 0.0, uz_ring = 0.0, w_dot = 0.0, uz_dot = 0.0;
    for (int i = 0; i < in.modes; ++i) {
      const double c = cos_n[in.order[i]], s = sin_n[in.order[i]];
      const double shape = in.mode_position[2 * i] * c + in.mode_position[2 * i + 1] * s;
      const double rate = in.mode_rate[2 * i] * c + in.mode_rate[2 * i + 1] * s;
      (in.radial[i] ? w : uz_ring) += shape;
      (in.radial[i] ? w_dot : uz_dot) += rate;
    }
    const double pz = in.groove_centre_z[b], nz = in.normal_z[b], px = rho * cphi, py = rho * sphi;
    const double ux = q[0] + q[4] * pz + w * cphi;
    const double uy = q[1] - q[3] * pz + w * sphi;
    const double uz = q[2] + q[3] * py - q[4] * px + uz_ring;
    const double vx = aca * cphi - sg * ux, vy = aca * sphi - sg * uy, vz = A * nz - sg * uz;
    const double norm = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double deflection = norm - A - in.clearance + in.offset[b];
    if (!(deflection > 0.0)) continue;
    const double udx = qd[0] + qd[4] * pz + w_dot * cphi;
    const double udy = qd[1] - qd[3] * pz + w_dot * sphi;
    const double udz = qd[2] + qd[3] * py - qd[4] * px + uz_dot;
    const double load = kn * deflection * std::sqrt(deflection) - cn * sg * (vx * udx + vy * udy + vz * udz) / norm;
    if (!(load > 0.0)) continue;
    const double s = sg * load / norm;
    const double fx = s * vx, fy = s * vy, fz = s * vz, fr = fx * cphi + fy * sphi;
    force[0] += fx;
    force[1] += fy;
    force[2] += fz;
    force[3] += py * fz - pz * fy;
    force[4] += pz * fx - px * fz;
    for (int i = 0; i < in.modes; ++i) {
      const double g = in.radial[i] ? fr : fz;
      force[5 + 2 * i] += g * cos_n[in.order[i]];
      force[6 + 2 * i] += g * sin_n[in.order[i]];
    }
  }
}

}  // namespace bearing_sim::detail
#endif  // HWY_ONCE
