// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "core/contact_kernel.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "contact_kernel.hpp"

#include <cmath>

#ifndef BEARING_SIM_CONTACT_KERNEL_ONCE
#define BEARING_SIM_CONTACT_KERNEL_ONCE
namespace bearing_sim::detail {
namespace {
// The terms of the loaded centre vector v = A e0 - sign u (MODEL.md section 2) and of the
// rate sign G q_dot that do not depend on the ball within a row:
//   v = (a_ca cphi + vx0, a_ca sphi + vy0, vz0 + vz_s sphi + vz_c cphi),
//   w = (wx0, wy0, wz0 + wz_s sphi + wz_c cphi).
struct RowTerms {
  double a_ca, vx0, vy0, vz0, vz_s, vz_c, wx0, wy0, wz0, wz_s, wz_c, a_g0;
};

inline RowTerms row_terms(const ContactKernelInput& in) {
  const double s = in.sign, rho = in.groove_centre_radius, pz = in.groove_centre_z;
  const double* q = in.q;
  const double* d = in.q_dot;
  RowTerms t;
  t.a_ca = in.groove_centre_distance * in.cos_a0;
  t.vx0 = -s * (q[0] + q[4] * pz);
  t.vy0 = -s * (q[1] - q[3] * pz);
  t.vz0 = in.groove_centre_distance * in.normal_z - s * q[2];
  t.vz_s = -s * rho * q[3];
  t.vz_c = s * rho * q[4];
  t.wx0 = s * (d[0] + d[4] * pz);
  t.wy0 = s * (d[1] - d[3] * pz);
  t.wz0 = s * d[2];
  t.wz_s = s * rho * d[3];
  t.wz_c = -s * rho * d[4];
  t.a_g0 = in.groove_centre_distance + in.clearance;
  return t;
}
}  // namespace
}  // namespace bearing_sim::detail
#endif  // BEARING_SIM_CONTACT_KERNEL_ONCE

HWY_BEFORE_NAMESPACE();
namespace bearing_sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void ContactSumsRuns(const ContactKernelInput* runs, int n_runs, ContactSums* out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  for (int r = 0; r < n_runs; ++r) {
    const ContactKernelInput& in = runs[r];
    const RowTerms t = row_terms(in);
    const V cc = hn::Set(d, in.cos_cage), sc = hn::Set(d, in.sin_cage);
    const V a_ca = hn::Set(d, t.a_ca), vx0 = hn::Set(d, t.vx0), vy0 = hn::Set(d, t.vy0);
    const V vz0 = hn::Set(d, t.vz0), vz_s = hn::Set(d, t.vz_s), vz_c = hn::Set(d, t.vz_c);
    const V wx0 = hn::Set(d, t.wx0), wy0 = hn::Set(d, t.wy0), wz0 = hn::Set(d, t.wz0);
    const V wz_s = hn::Set(d, t.wz_s), wz_c = hn::Set(d, t.wz_c), a_g0 = hn::Set(d, t.a_g0);
    const V kn = hn::Set(d, in.stiffness), cn = hn::Set(d, in.damping);
    V sx = zero, sy = zero, sz = zero, szc = zero, szs = zero;
    auto ball = [&](V cb, V sb, V off) HWY_ATTR {
      const V cphi = hn::MulSub(cc, cb, hn::Mul(sc, sb));
      const V sphi = hn::MulAdd(sc, cb, hn::Mul(cc, sb));
      const V vx = hn::MulAdd(a_ca, cphi, vx0);
      const V vy = hn::MulAdd(a_ca, sphi, vy0);
      const V vz = hn::MulAdd(vz_s, sphi, hn::MulAdd(vz_c, cphi, vz0));
      const V norm = hn::Sqrt(hn::MulAdd(vx, vx, hn::MulAdd(vy, vy, hn::Mul(vz, vz))));
      const V deflection = hn::Add(hn::Sub(norm, a_g0), off);
      const auto touching = hn::Gt(deflection, zero);
      const V dp = hn::IfThenElseZero(touching, deflection);
      const V inv_norm = hn::Div(one, norm);
      // d(delta)/dt = -e . du/dt, with w = sign du/dt.
      const V wz = hn::MulAdd(wz_s, sphi, hn::MulAdd(wz_c, cphi, wz0));
      const V v_dot_w = hn::MulAdd(vx, wx0, hn::MulAdd(vy, wy0, hn::Mul(vz, wz)));
      // Q = kn dp^1.5 - cn (v . w) / |v|, kept only while touching and pressing (damping
      // can pull a leaving ball's load negative: the contact cannot pull).
      const V load = hn::NegMulAdd(cn, hn::Mul(v_dot_w, inv_norm), hn::Mul(hn::Mul(kn, dp), hn::Sqrt(dp)));
      const auto pressing = hn::And(touching, hn::Gt(load, zero));
      const V s = hn::IfThenElseZero(pressing, hn::Mul(load, inv_norm));
      const V s_vz = hn::Mul(s, vz);
      sx = hn::MulAdd(s, vx, sx);
      sy = hn::MulAdd(s, vy, sy);
      sz = hn::Add(sz, s_vz);
      szc = hn::MulAdd(s_vz, cphi, szc);
      szs = hn::MulAdd(s_vz, sphi, szs);
    };
    const std::size_t n = static_cast<std::size_t>(in.n);
    std::size_t b = 0;
    for (; b + N <= n; b += N)
      ball(hn::LoadU(d, in.cos_base + b), hn::LoadU(d, in.sin_base + b), hn::LoadU(d, in.offset + b));
    if (b < n) {
      // The tail through a padded copy (no read past the arrays): padding lanes are a ball
      // at the cage angle with a 1 m gap, out of contact, so they add exact zeros.
      constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
      HWY_ALIGN double cb[kMaxLanes], sb[kMaxLanes], off[kMaxLanes];
      for (std::size_t i = 0; i < N; ++i) {
        const bool real = b + i < n;
        cb[i] = real ? in.cos_base[b + i] : 1.0;
        sb[i] = real ? in.sin_base[b + i] : 0.0;
        off[i] = real ? in.offset[b + i] : -1.0;
      }
      ball(hn::Load(d, cb), hn::Load(d, sb), hn::Load(d, off));
    }
    out[r] = ContactSums{hn::GetLane(hn::SumOfLanes(d, sx)), hn::GetLane(hn::SumOfLanes(d, sy)),
                         hn::GetLane(hn::SumOfLanes(d, sz)), hn::GetLane(hn::SumOfLanes(d, szc)),
                         hn::GetLane(hn::SumOfLanes(d, szs))};
  }
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace bearing_sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace bearing_sim::detail {
HWY_EXPORT(ContactSumsRuns);
HWY_EXPORT(TargetName);

void contact_sums_simd(const ContactKernelInput* runs, int n_runs, ContactSums* out) {
  HWY_DYNAMIC_DISPATCH(ContactSumsRuns)(runs, n_runs, out);
}

const char* contact_kernel_target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

std::vector<std::int64_t> contact_kernel_compiled_targets() {
  std::vector<std::int64_t> targets;
  for (std::int64_t rest = HWY_TARGETS; rest != 0; rest &= rest - 1) targets.push_back(rest & ~(rest - 1));
  return targets;
}

ContactSums contact_sums_scalar(const ContactKernelInput& in) {
  const RowTerms t = row_terms(in);
  const double cc = in.cos_cage, sc = in.sin_cage, kn = in.stiffness, cn = in.damping;
  double sx = 0, sy = 0, sz = 0, szc = 0, szs = 0;
  for (int b = 0; b < in.n; ++b) {
    const double cphi = cc * in.cos_base[b] - sc * in.sin_base[b];
    const double sphi = sc * in.cos_base[b] + cc * in.sin_base[b];
    const double vx = t.a_ca * cphi + t.vx0;
    const double vy = t.a_ca * sphi + t.vy0;
    const double vz = t.vz0 + t.vz_s * sphi + t.vz_c * cphi;
    const double norm = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double deflection = norm - t.a_g0 + in.offset[b];
    if (deflection <= 0.0) continue;
    // d(delta)/dt = -e . du/dt, with w = sign du/dt.
    const double wz = t.wz0 + t.wz_s * sphi + t.wz_c * cphi;
    const double rate = -(vx * t.wx0 + vy * t.wy0 + vz * wz) / norm;
    const double load = kn * deflection * std::sqrt(deflection) + cn * rate;
    if (load <= 0.0) continue;
    const double s = load / norm;
    sx += s * vx;
    sy += s * vy;
    sz += s * vz;
    szc += s * vz * cphi;
    szs += s * vz * sphi;
  }
  return ContactSums{sx, sy, sz, szc, szs};
}
}  // namespace bearing_sim::detail
#endif  // HWY_ONCE
