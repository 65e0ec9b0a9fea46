// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "contact_kernel.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "dispatch.hpp"
#include "hwy/contrib/math/math-inl.h"

#include "bearing_sim/core/constants.hpp"
#include "contact_kernel.hpp"
#include "padded_balls.hpp"

#include <cmath>

// Per ball b, with z = groove_centre_z[b] (of the moving ring's groove centre), nz = normal_z[b] and
// s = sign (docs/model.md section 5):
//   loaded centre vector v = A e0 - s u = (a_ca cphi + vx0, a_ca sphi + vy0, vz0 + vz_s sphi + vz_c cphi),
//     vx0 = -s (q0 + q4 z), vy0 = -s (q1 - q3 z), vz0 = A nz - s q2;
//   w = s du/dt = (wx0, wy0, wz0 + wz_s sphi + wz_c cphi),
//     wx0 = s (d0 + d4 z), wy0 = s (d1 - d3 z).

HWY_BEFORE_NAMESPACE();
namespace bearing_sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The dip of the balls of `inside` (asin and cos only here, out of line: a vector rarely holds a
// ball in a spall, and inline they would crowd the kernel's registers).
template <class D, class V, class M>
HWY_NOINLINE V WindowDip(D d, V sin_x, M inside, const Imperfections::SpallWindow& w) {
  if (w.sharp_edges) {  // min(depth, geometric_depth (1 - 2|x| / width)^2)
    const V ax = hn::Abs(hn::Asin(d, sin_x));
    const V u = hn::NegMulAdd(ax, hn::Set(d, w.pi_over_width * (2.0 / bearing_sim::kPi)), hn::Set(d, 1.0));
    const V pit = hn::Min(hn::Set(d, w.depth), hn::Mul(hn::Set(d, w.geometric_depth), hn::Mul(u, u)));
    if (w.rim_height == 0.0) return hn::IfThenElseZero(inside, pit);
    // Past the edge, the rim: -h sin^2(pi (|x| - w/2) / r).
    const V half = hn::Set(d, w.half_width);
    const V v = hn::Sin(d, hn::Mul(hn::Sub(ax, half), hn::Set(d, w.rim_pi_over_width)));
    const V rim = hn::Mul(hn::Set(d, -w.rim_height), hn::Mul(v, v));
    if (w.ring_drop == 0.0) return hn::IfThenElseZero(inside, hn::IfThenElse(hn::Lt(ax, half), pit, rim));
    // A round pit's ring: within its crest, ring_drop (crest^2 - x^2) - h, or the pit's dip if smaller.
    const V on_ring =
        hn::MulSub(hn::Set(d, w.ring_drop), hn::NegMulAdd(ax, ax, hn::Set(d, w.ring_crest * w.ring_crest)),
                   hn::Set(d, w.rim_height));
    const V inner = hn::Min(on_ring, hn::IfThenElseZero(hn::Lt(ax, half), pit));
    return hn::IfThenElseZero(inside, hn::IfThenElse(hn::Lt(ax, hn::Set(d, w.ring_crest)), inner, rim));
  }
  return hn::IfThenElseZero(
      inside, hn::Mul(hn::Set(d, w.depth), hn::Cos(d, hn::Mul(hn::Asin(d, sin_x), hn::Set(d, w.pi_over_width)))));
}

// kWindows: the balls may be under race spalls' windows (a separate variant, so that the
// kernel of a bearing without them carries none of their code).
template <bool kWindows>
HWY_INLINE ContactSums Sums(const ContactKernelInput& in) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = hn::Lanes(d);
  const double sg = in.sign, rho = in.groove_centre_radius, A = in.groove_centre_distance;
  const double* q = in.q;
  const double* qd = in.q_dot;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V cc = hn::Set(d, in.cos_cage), sc = hn::Set(d, in.sin_cage);
  const V a_ca = hn::Set(d, A * in.cos_a0), a_v = hn::Set(d, A);
  // The sign folded into the constants (s = +-1: multiplying by it is exact, so the
  // results are bit for bit those of -s (q0 + q4 z) etc.): two multiplies per ball fewer.
  const V ms_q0 = hn::Set(d, -sg * q[0]), ms_q1 = hn::Set(d, -sg * q[1]);
  const V ms_q3 = hn::Set(d, -sg * q[3]), ms_q4 = hn::Set(d, -sg * q[4]);
  const V s_d0 = hn::Set(d, sg * qd[0]), s_d1 = hn::Set(d, sg * qd[1]);
  const V s_d3 = hn::Set(d, sg * qd[3]), s_d4 = hn::Set(d, sg * qd[4]);
  const V ms_q2 = hn::Set(d, -sg * q[2]), wz0 = hn::Set(d, sg * qd[2]);
  const V vz_s = hn::Set(d, -sg * rho * q[3]), vz_c = hn::Set(d, sg * rho * q[4]);
  const V wz_s = hn::Set(d, sg * rho * qd[3]), wz_c = hn::Set(d, -sg * rho * qd[4]);
  const V a_g0 = hn::Set(d, A + in.clearance);
  const V kn = hn::Set(d, in.stiffness), cn = hn::Set(d, in.damping);
  V sx = zero, sy = zero, sz = zero, szc = zero, szs = zero, sxz = zero, syz = zero;
  // `valid`: the lanes that hold a ball not yet summed (the overlapping tail vector).
  using M = decltype(hn::FirstN(d, 0));
  // A race spall's window: x = phi - psi from its sine and cosine; within the window (cos x
  // > 0, |x| < w/2 <= pi/4) x = asin(sin x). Few vectors hold a ball in a spall: only those
  // pay for Asin and Cos. The first window's constants are set once per call.
  const Imperfections::SpallWindow* w0 = in.spalls;
  const V cw0 = hn::Set(d, kWindows ? w0->cos_centre : 0.0), sw0 = hn::Set(d, kWindows ? w0->sin_centre : 0.0);
  const V half0 = hn::Set(d, kWindows ? w0->sin_half_width : 0.0);
  const V row0 = hn::Set(d, kWindows ? w0->row_groove_centre_z : 0.0);
  auto dip = [&](V cphi, V sphi, V pz, V cw, V sw, V half, V row, const Imperfections::SpallWindow& w) HWY_ATTR {
    const V sin_x = hn::MulSub(sphi, cw, hn::Mul(cphi, sw));
    const V cos_x = hn::MulAdd(cphi, cw, hn::Mul(sphi, sw));
    const auto inside = hn::And(hn::And(hn::Gt(cos_x, zero), hn::Lt(hn::Abs(sin_x), half)), hn::Eq(pz, row));
    return hn::AllFalse(d, inside) ? zero : WindowDip(d, sin_x, inside, w);
  };
  auto balls = [&](V cb, V sb, V pz, V nz, V off, M valid) HWY_ATTR {
    const V cphi = hn::MulSub(cc, cb, hn::Mul(sc, sb));
    const V sphi = hn::MulAdd(sc, cb, hn::Mul(cc, sb));
    if constexpr (kWindows) {
      off = hn::Sub(off, dip(cphi, sphi, pz, cw0, sw0, half0, row0, *w0));
      for (int i = 1; i < in.spall_count; ++i) {
        const Imperfections::SpallWindow& w = in.spalls[i];
        off = hn::Sub(off, dip(cphi, sphi, pz, hn::Set(d, w.cos_centre), hn::Set(d, w.sin_centre),
                               hn::Set(d, w.sin_half_width), hn::Set(d, w.row_groove_centre_z), w));
      }
    }
    const V vx = hn::MulAdd(a_ca, cphi, hn::MulAdd(ms_q4, pz, ms_q0));
    const V vy = hn::MulAdd(a_ca, sphi, hn::NegMulAdd(ms_q3, pz, ms_q1));
    const V vz = hn::MulAdd(vz_s, sphi, hn::MulAdd(vz_c, cphi, hn::MulAdd(a_v, nz, ms_q2)));
    const V norm = hn::Sqrt(hn::MulAdd(vx, vx, hn::MulAdd(vy, vy, hn::Mul(vz, vz))));
    const V deflection = hn::Add(hn::Sub(norm, a_g0), off);
    const auto touching = hn::And(valid, hn::Gt(deflection, zero));
    const V dp = hn::IfThenElseZero(touching, deflection);
    const V inv_norm = hn::Div(one, norm);
    // d(delta)/dt = -e . du/dt.
    const V wx = hn::MulAdd(s_d4, pz, s_d0);
    const V wy = hn::NegMulAdd(s_d3, pz, s_d1);
    const V wz = hn::MulAdd(wz_s, sphi, hn::MulAdd(wz_c, cphi, wz0));
    const V v_dot_w = hn::MulAdd(vx, wx, hn::MulAdd(vy, wy, hn::Mul(vz, wz)));
    // Q = kn dp^1.5 - cn (v . w) / |v|, kept only while touching and pressing (damping
    // can pull a leaving ball's load negative: the contact cannot pull).
    const V load = hn::NegMulAdd(cn, hn::Mul(v_dot_w, inv_norm), hn::Mul(hn::Mul(kn, dp), hn::Sqrt(dp)));
    const auto pressing = hn::And(touching, hn::Gt(load, zero));
    const V s = hn::IfThenElseZero(pressing, hn::Mul(load, inv_norm));
    const V s_vx = hn::Mul(s, vx), s_vy = hn::Mul(s, vy), s_vz = hn::Mul(s, vz);
    sx = hn::Add(sx, s_vx);
    sy = hn::Add(sy, s_vy);
    sz = hn::Add(sz, s_vz);
    szc = hn::MulAdd(s_vz, cphi, szc);
    szs = hn::MulAdd(s_vz, sphi, szs);
    sxz = hn::MulAdd(s_vx, pz, sxz);
    syz = hn::MulAdd(s_vy, pz, syz);
  };
  const std::size_t n = static_cast<std::size_t>(in.n);
  const M all = hn::FirstN(d, N);
  std::size_t b = 0;
  for (; b + N <= n; b += N)
    balls(hn::LoadU(d, in.cos_base + b), hn::LoadU(d, in.sin_base + b), hn::LoadU(d, in.groove_centre_z + b),
          hn::LoadU(d, in.normal_z + b), hn::LoadU(d, in.offset + b), all);
  if (b < n && n >= N) {
    // The tail as the last N balls, the lanes already summed masked off (no copy, no read
    // past the arrays; a masked lane adds exact zeros).
    const std::size_t last = n - N;
    balls(hn::LoadU(d, in.cos_base + last), hn::LoadU(d, in.sin_base + last), hn::LoadU(d, in.groove_centre_z + last),
          hn::LoadU(d, in.normal_z + last), hn::LoadU(d, in.offset + last), hn::Not(hn::FirstN(d, b - last)));
  } else if (b < n) {
    // Fewer balls than lanes: through a padded copy (its padding adds exact zeros).
    static_assert(HWY_MAX_BYTES / sizeof(double) <= PaddedBalls::kMaxLanes);
    const PaddedBalls p(in.cos_base, in.sin_base, in.groove_centre_z, in.normal_z, in.offset, b, n, N);
    balls(hn::LoadU(d, p.cos_base), hn::LoadU(d, p.sin_base), hn::LoadU(d, p.groove_centre_z), hn::LoadU(d, p.normal_z),
          hn::LoadU(d, p.offset), all);
  }
  return ContactSums{hn::GetLane(hn::SumOfLanes(d, sx)),  hn::GetLane(hn::SumOfLanes(d, sy)),
                     hn::GetLane(hn::SumOfLanes(d, sz)),  hn::GetLane(hn::SumOfLanes(d, szc)),
                     hn::GetLane(hn::SumOfLanes(d, szs)), hn::GetLane(hn::SumOfLanes(d, sxz)),
                     hn::GetLane(hn::SumOfLanes(d, syz))};
}

ContactSums ContactSumsAll(const ContactKernelInput& in) { return Sums<false>(in); }
ContactSums ContactSumsWithWindows(const ContactKernelInput& in) { return Sums<true>(in); }

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace bearing_sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace bearing_sim::detail {
HWY_EXPORT(ContactSumsAll);
HWY_EXPORT(ContactSumsWithWindows);
HWY_EXPORT(TargetName);

ContactSums contact_sums_simd(const ContactKernelInput& in) {
  if (in.spall_count > 0) return BEARING_SIM_DISPATCH(ContactSumsWithWindows)(in);
  return BEARING_SIM_DISPATCH(ContactSumsAll)(in);
}

const char* contact_kernel_target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

std::vector<std::int64_t> contact_kernel_compiled_targets() {
  std::vector<std::int64_t> targets;
  for (std::int64_t rest = HWY_TARGETS; rest != 0; rest &= rest - 1) targets.push_back(rest & ~(rest - 1));
  return targets;
}

ContactSums contact_sums_scalar(const ContactKernelInput& in) {
  const double sg = in.sign, rho = in.groove_centre_radius, A = in.groove_centre_distance;
  const double* q = in.q;
  const double* qd = in.q_dot;
  const double cc = in.cos_cage, sc = in.sin_cage, kn = in.stiffness, cn = in.damping;
  ContactSums sum{0, 0, 0, 0, 0, 0, 0};
  for (int b = 0; b < in.n; ++b) {
    const double pz = in.groove_centre_z[b], nz = in.normal_z[b];
    const double cphi = cc * in.cos_base[b] - sc * in.sin_base[b];
    const double sphi = sc * in.cos_base[b] + cc * in.sin_base[b];
    double offset = in.offset[b];
    for (int i = 0; i < in.spall_count; ++i) {
      const Imperfections::SpallWindow& w = in.spalls[i];
      const double sin_x = sphi * w.cos_centre - cphi * w.sin_centre;
      const double cos_x = cphi * w.cos_centre + sphi * w.sin_centre;
      if (cos_x > 0.0 && std::abs(sin_x) < w.sin_half_width && pz == w.row_groove_centre_z) {
        if (w.sharp_edges) {
          const double ax = std::abs(std::asin(sin_x));
          const double u = 1.0 - ax * (w.pi_over_width * (2.0 / bearing_sim::kPi));
          const double pit =
              ax < w.half_width || w.rim_height == 0.0 ? std::min(w.depth, w.geometric_depth * u * u) : 0.0;
          if (w.ring_drop > 0.0 && ax < w.ring_crest) {  // riding a round pit's ring
            offset -= std::min(w.ring_drop * (w.ring_crest * w.ring_crest - ax * ax) - w.rim_height, pit);
          } else if (w.rim_height == 0.0 || ax < w.half_width) {
            offset -= pit;
          } else {  // the rim
            const double v = std::sin((ax - w.half_width) * w.rim_pi_over_width);
            offset += w.rim_height * v * v;
          }
        } else {
          offset -= w.depth * std::cos(std::asin(sin_x) * w.pi_over_width);
        }
      }
    }
    const double vx = A * in.cos_a0 * cphi - sg * (q[0] + q[4] * pz);
    const double vy = A * in.cos_a0 * sphi - sg * (q[1] - q[3] * pz);
    const double vz = A * nz - sg * (q[2] + q[3] * rho * sphi - q[4] * rho * cphi);
    const double norm = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double deflection = norm - (A + in.clearance) + offset;
    if (deflection <= 0.0) continue;
    // d(delta)/dt = -e . du/dt, with w = sign du/dt.
    const double wx = sg * (qd[0] + qd[4] * pz);
    const double wy = sg * (qd[1] - qd[3] * pz);
    const double wz = sg * (qd[2] + qd[3] * rho * sphi - qd[4] * rho * cphi);
    const double rate = -(vx * wx + vy * wy + vz * wz) / norm;
    const double load = kn * deflection * std::sqrt(deflection) + cn * rate;
    if (load <= 0.0) continue;
    const double s = load / norm;
    sum.x += s * vx;
    sum.y += s * vy;
    sum.z += s * vz;
    sum.z_cos += s * vz * cphi;
    sum.z_sin += s * vz * sphi;
    sum.x_z += s * vx * pz;
    sum.y_z += s * vy * pz;
  }
  return sum;
}
}  // namespace bearing_sim::detail
#endif  // HWY_ONCE
