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
#include <optional>
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
// come back in the base frame). Pass 1 per vector of azimuths: the ring's displacement there,
// once for every row that shares them, then per row its balls' displacement, load, rigid sums
// and radial and axial force; pass 2 per order: the projections of its radial and axial modes.
template <int kRows>
HWY_INLINE void FlexibleContactRows(const FlexibleKernelInput& in, double* force) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const double sg = in.sign, rho = in.groove_centre_radius, A = in.groove_centre_distance;
  const double* q = in.q;
  const double* qd = in.q_dot;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V cc = hn::Set(d, in.cos_cage), sc = hn::Set(d, in.sin_cage);
  const V a_ca = hn::Set(d, A * in.cos_a0), a_v = hn::Set(d, A), v_rho = hn::Set(d, rho);
  const V a_g0 = hn::Set(d, A + in.clearance), v_sg = hn::Set(d, sg);
  const V kn = hn::Set(d, in.stiffness), cn = hn::Set(d, in.damping);
  const std::size_t stride = static_cast<std::size_t>(in.stride);
  const std::size_t row_stride = static_cast<std::size_t>(in.row_stride);
  const std::size_t azimuths = static_cast<std::size_t>(in.azimuths);
  constexpr int rows = kRows;
  // Per ball, pass 1 -> 2 (every vector of balls stores its lanes, zero when clear), row r's
  // from r row_stride; the work's first 2 rows_sharing row_stride doubles.
  double* const radial_force = in.work;
  double* const axial_force = in.work + static_cast<std::size_t>(rows) * row_stride;
  V f0 = zero, f1 = zero, f2 = zero, f3 = zero, f4 = zero;
  // Azimuths j .. j + N - 1 and, per row r, its balls' groove centre height, normal and
  // deflection offset at pz_at[r], nz_at[r], off_at[r]; the last vector through padded copies
  // (their padding adds exact zeros; the base shapes' rows are padded to the stride).
  static_assert(HWY_MAX_BYTES / sizeof(double) <= PaddedBalls::kMaxLanes);
  const double* pz_at[kRows];
  const double* nz_at[kRows];
  const double* off_at[kRows];
  std::optional<PaddedBalls> padded[kRows];
  std::size_t j = 0;
  for (; j < azimuths; j += N) {
    const double* cb_at = in.cos_base + j;
    const double* sb_at = in.sin_base + j;
    for (int row = 0; row < rows; ++row) {
      const std::size_t first = static_cast<std::size_t>(row) * azimuths;
      if (j + N <= azimuths) {
        pz_at[row] = in.groove_centre_z + first + j;
        nz_at[row] = in.normal_z + first + j;
        off_at[row] = in.offset + first + j;
        continue;
      }
      const PaddedBalls& p = padded[row].emplace(in.cos_base + first, in.sin_base + first, in.groove_centre_z + first,
                                                 in.normal_z + first, in.offset + first, j, azimuths, N);
      pz_at[row] = p.groove_centre_z;
      nz_at[row] = p.normal_z;
      off_at[row] = p.offset;
      if (row == 0) {
        cb_at = p.cos_base;
        sb_at = p.sin_base;
      }
    }
    const V cb = hn::LoadU(d, cb_at), sb = hn::LoadU(d, sb_at);
    const V cphi = hn::MulSub(cc, cb, hn::Mul(sc, sb));
    const V sphi = hn::MulAdd(sc, cb, hn::Mul(cc, sb));
    V w = zero, uz_ring = zero, w_dot = zero, uz_dot = zero;
    for (int k = 0; k <= in.max_order; ++k) {
      const int radial = in.radial_mode_of_order[k], axial = in.axial_mode_of_order[k];
      if (radial < 0 && axial < 0) continue;
      const std::size_t at = static_cast<std::size_t>(k) * stride + j;
      const V c = hn::LoadU(d, in.base_cos_n + at), s = hn::LoadU(d, in.base_sin_n + at);
      if (radial >= 0) {
        const double* p = in.mode_position + 2 * radial;
        const double* r = in.mode_rate + 2 * radial;
        w = hn::Add(w, hn::MulAdd(hn::Set(d, p[0]), c, hn::Mul(hn::Set(d, p[1]), s)));
        w_dot = hn::Add(w_dot, hn::MulAdd(hn::Set(d, r[0]), c, hn::Mul(hn::Set(d, r[1]), s)));
      }
      if (axial >= 0) {
        const double* p = in.mode_position + 2 * axial;
        const double* r = in.mode_rate + 2 * axial;
        uz_ring = hn::Add(uz_ring, hn::MulAdd(hn::Set(d, p[0]), c, hn::Mul(hn::Set(d, p[1]), s)));
        uz_dot = hn::Add(uz_dot, hn::MulAdd(hn::Set(d, r[0]), c, hn::Mul(hn::Set(d, r[1]), s)));
      }
    }
    const V px = hn::Mul(v_rho, cphi), py = hn::Mul(v_rho, sphi);
    for (int row = 0; row < rows; ++row) {
      const std::size_t out = static_cast<std::size_t>(row) * row_stride + j;
      const V pz = hn::LoadU(d, pz_at[row]), nz = hn::LoadU(d, nz_at[row]), off = hn::LoadU(d, off_at[row]);
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
        hn::StoreU(zero, d, radial_force + out);
        hn::StoreU(zero, d, axial_force + out);
        continue;
      }
      const V dp = hn::IfThenElseZero(touching, deflection);
      const V inv_norm = hn::Div(one, norm);
      const V udx = hn::MulAdd(w_dot, cphi, hn::MulAdd(hn::Set(d, qd[4]), pz, hn::Set(d, qd[0])));
      const V udy = hn::MulAdd(w_dot, sphi, hn::NegMulAdd(hn::Set(d, qd[3]), pz, hn::Set(d, qd[1])));
      const V udz =
          hn::Add(hn::MulAdd(hn::Set(d, qd[3]), py, hn::NegMulAdd(hn::Set(d, qd[4]), px, hn::Set(d, qd[2]))), uz_dot);
      const V v_dot_u = hn::MulAdd(vx, udx, hn::MulAdd(vy, udy, hn::Mul(vz, udz)));
      // Q = kn dp^1.5 - cn sign (v . u') / |v|; the contact cannot pull.
      const V load =
          hn::NegMulAdd(hn::Mul(cn, v_sg), hn::Mul(v_dot_u, inv_norm), hn::Mul(hn::Mul(kn, dp), hn::Sqrt(dp)));
      const auto pressing = hn::And(touching, hn::Gt(load, zero));
      const V s = hn::IfThenElseZero(pressing, hn::Mul(hn::Mul(v_sg, load), inv_norm));
      const V fx = hn::Mul(s, vx), fy = hn::Mul(s, vy), fz = hn::Mul(s, vz);
      f0 = hn::Add(f0, fx);
      f1 = hn::Add(f1, fy);
      f2 = hn::Add(f2, fz);
      f3 = hn::Add(f3, hn::MulSub(py, fz, hn::Mul(pz, fy)));
      f4 = hn::Add(f4, hn::MulSub(pz, fx, hn::Mul(px, fz)));
      hn::StoreU(hn::MulAdd(fx, cphi, hn::Mul(fy, sphi)), d, radial_force + out);
      hn::StoreU(fz, d, axial_force + out);
    }
  }
  force[0] = hn::GetLane(hn::SumOfLanes(d, f0));
  force[1] = hn::GetLane(hn::SumOfLanes(d, f1));
  force[2] = hn::GetLane(hn::SumOfLanes(d, f2));
  force[3] = hn::GetLane(hn::SumOfLanes(d, f3));
  force[4] = hn::GetLane(hn::SumOfLanes(d, f4));
  const std::size_t end = j;  // the padded vector included (zero force there)
  for (int k = 0; k <= in.max_order; ++k) {
    const int radial = in.radial_mode_of_order[k], axial = in.axial_mode_of_order[k];
    if (radial < 0 && axial < 0) continue;
    const double* c = in.base_cos_n + static_cast<std::size_t>(k) * stride;
    const double* s = in.base_sin_n + static_cast<std::size_t>(k) * stride;
    V radial_c = zero, radial_s = zero, axial_c = zero, axial_s = zero;
    for (std::size_t i = 0; i < end; i += N) {
      V g_radial = hn::LoadU(d, radial_force + i), g_axial = hn::LoadU(d, axial_force + i);
      for (int row = 1; row < rows; ++row) {
        g_radial = hn::Add(g_radial, hn::LoadU(d, radial_force + static_cast<std::size_t>(row) * row_stride + i));
        g_axial = hn::Add(g_axial, hn::LoadU(d, axial_force + static_cast<std::size_t>(row) * row_stride + i));
      }
      const V ck = hn::LoadU(d, c + i), sk = hn::LoadU(d, s + i);
      radial_c = hn::MulAdd(g_radial, ck, radial_c);
      radial_s = hn::MulAdd(g_radial, sk, radial_s);
      axial_c = hn::MulAdd(g_axial, ck, axial_c);
      axial_s = hn::MulAdd(g_axial, sk, axial_s);
    }
    if (radial >= 0) {
      force[5 + 2 * radial] = hn::GetLane(hn::SumOfLanes(d, radial_c));
      force[6 + 2 * radial] = hn::GetLane(hn::SumOfLanes(d, radial_s));
    }
    if (axial >= 0) {
      force[5 + 2 * axial] = hn::GetLane(hn::SumOfLanes(d, axial_c));
      force[6 + 2 * axial] = hn::GetLane(hn::SumOfLanes(d, axial_s));
    }
  }
}

void FlexibleContact(const FlexibleKernelInput& in, double* force) {
  if (in.rows_sharing == 2) FlexibleContactRows<2>(in, force);
  else FlexibleContactRows<1>(in, force);
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
  double* const position = in.work + 2 * in.rows_sharing * in.row_stride;
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
