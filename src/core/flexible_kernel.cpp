// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "flexible_kernel.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "dispatch.hpp"
#include "flexible_kernel.hpp"

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

void FlexibleContact(const FlexibleKernelInput& in, double* force) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const int modes = in.modes, max_order = in.max_order;
  const double sg = in.sign, rho = in.groove_centre_radius, A = in.groove_centre_distance;
  const double* q = in.q;
  const double* qd = in.q_dot;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V cc = hn::Set(d, in.cos_cage), sc = hn::Set(d, in.sin_cage);
  const V a_ca = hn::Set(d, A * in.cos_a0), a_v = hn::Set(d, A), v_rho = hn::Set(d, rho);
  const V a_g0 = hn::Set(d, A + in.clearance), v_sg = hn::Set(d, sg);
  const V kn = hn::Set(d, in.stiffness), cn = hn::Set(d, in.damping);
  // Per-lane buffers (vectors are not kept in arrays: sizeless on some targets): the shapes
  // cos n phi, sin n phi of the vector's balls, and the modal force sums.
  thread_local std::vector<double> cos_n, sin_n, sums;
  cos_n.resize((max_order + 1) * N);
  sin_n.resize((max_order + 1) * N);
  sums.assign((5 + 2 * modes) * N, 0.0);
  std::fill(cos_n.begin(), cos_n.begin() + N, 1.0);  // order 0
  std::fill(sin_n.begin(), sin_n.begin() + N, 0.0);
  auto balls = [&](V cb, V sb, V pz, V nz, V off) HWY_ATTR {
    const V cphi = hn::MulSub(cc, cb, hn::Mul(sc, sb));
    const V sphi = hn::MulAdd(sc, cb, hn::Mul(cc, sb));
    hn::StoreU(cphi, d, cos_n.data() + N);
    hn::StoreU(sphi, d, sin_n.data() + N);
    V ck = cphi, sk = sphi;
    for (int k = 2; k <= max_order; ++k) {
      const V c2 = hn::MulSub(ck, cphi, hn::Mul(sk, sphi));
      sk = hn::MulAdd(sk, cphi, hn::Mul(ck, sphi));
      ck = c2;
      hn::StoreU(ck, d, cos_n.data() + k * N);
      hn::StoreU(sk, d, sin_n.data() + k * N);
    }
    V w = zero, uz_ring = zero, w_dot = zero, uz_dot = zero;
    for (int i = 0; i < modes; ++i) {
      const V c = hn::LoadU(d, cos_n.data() + in.order[i] * N), s = hn::LoadU(d, sin_n.data() + in.order[i] * N);
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
    if (hn::AllFalse(d, touching)) return;
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
    const V fr = hn::MulAdd(fx, cphi, hn::Mul(fy, sphi));
    const auto add = [&](int k, V v) HWY_ATTR {
      hn::StoreU(hn::Add(hn::LoadU(d, sums.data() + k * N), v), d, sums.data() + k * N);
    };
    add(0, fx);
    add(1, fy);
    add(2, fz);
    add(3, hn::MulSub(py, fz, hn::Mul(pz, fy)));
    add(4, hn::MulSub(pz, fx, hn::Mul(px, fz)));
    for (int i = 0; i < modes; ++i) {
      const V g = in.radial[i] ? fr : fz;
      add(5 + 2 * i, hn::Mul(g, hn::LoadU(d, cos_n.data() + in.order[i] * N)));
      add(6 + 2 * i, hn::Mul(g, hn::LoadU(d, sin_n.data() + in.order[i] * N)));
    }
  };
  const std::size_t n = static_cast<std::size_t>(in.n);
  std::size_t b = 0;
  for (; b + N <= n; b += N)
    balls(hn::LoadU(d, in.cos_base + b), hn::LoadU(d, in.sin_base + b), hn::LoadU(d, in.groove_centre_z + b),
          hn::LoadU(d, in.normal_z + b), hn::LoadU(d, in.offset + b));
  if (b < n) {
    // The rest through a padded copy: padding lanes are balls with a 1 m gap, out of contact.
    constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
    HWY_ALIGN double cb[kMaxLanes], sb[kMaxLanes], pz[kMaxLanes], nz[kMaxLanes], off[kMaxLanes];
    for (std::size_t i = 0; i < N; ++i) {
      const bool real = b + i < n;
      cb[i] = real ? in.cos_base[b + i] : 1.0;
      sb[i] = real ? in.sin_base[b + i] : 0.0;
      pz[i] = real ? in.groove_centre_z[b + i] : 0.0;
      nz[i] = real ? in.normal_z[b + i] : 0.0;
      off[i] = real ? in.offset[b + i] : -1.0;
    }
    balls(hn::Load(d, cb), hn::Load(d, sb), hn::Load(d, pz), hn::Load(d, nz), hn::Load(d, off));
  }
  for (int k = 0; k < 5 + 2 * modes; ++k) force[k] = hn::GetLane(hn::SumOfLanes(d, hn::LoadU(d, sums.data() + k * N)));
}

}  // namespace HWY_NAMESPACE
}  // namespace bearing_sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace bearing_sim::detail {
HWY_EXPORT(FlexibleContact);

void flexible_contact_simd(const FlexibleKernelInput& in, double* force) {
  BEARING_SIM_DISPATCH(FlexibleContact)(in, force);
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
