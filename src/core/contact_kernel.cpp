#include "contact_kernel.hpp"

#include <cmath>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim::detail {

Vector5 contact_force_portable(const ContactKernelInput& in) {
  const double cc = in.cos_cage, sc = in.sin_cage, rho = in.groove_centre_radius, ca = in.cos_a0;
  const double A = in.groove_centre_distance, g0 = in.clearance, sign = in.sign, kn = in.stiffness, cn = in.damping;
  const double* q = in.q;
  const double* qd = in.q_dot;
  double fx = 0, fy = 0, fz = 0, mx = 0, my = 0;
#pragma omp simd reduction(+ : fx, fy, fz, mx, my)
  for (int b = 0; b < in.n; ++b) {
    // MODEL.md section 2, as in bearing_model.cpp's kinematics().
    const double cphi = cc * in.cos_base[b] - sc * in.sin_base[b];
    const double sphi = sc * in.cos_base[b] + cc * in.sin_base[b];
    const double px = rho * cphi, py = rho * sphi, pz = in.groove_centre_z[b];
    const double vx = A * ca * cphi - sign * (q[0] + q[4] * pz);
    const double vy = A * ca * sphi - sign * (q[1] - q[3] * pz);
    const double vz = A * in.normal_z[b] - sign * (q[2] + q[3] * py - q[4] * px);
    const double norm = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double deflection = norm - A - g0 + in.offset[b];
    const double dp = deflection > 0.0 ? deflection : 0.0;
    // Rate of deflection from the ring velocity: d(delta)/dt = -e . du/dt.
    const double wx = sign * (qd[0] + qd[4] * pz);
    const double wy = sign * (qd[1] - qd[3] * pz);
    const double wz = sign * (qd[2] + qd[3] * py - qd[4] * px);
    const double inv_norm = 1.0 / norm;
    const double rate = -(vx * wx + vy * wy + vz * wz) * inv_norm;
    double load = kn * dp * std::sqrt(dp) + cn * rate;
    load = (deflection > 0.0 && load > 0.0) ? load : 0.0;
    const double s = sign * load * inv_norm;
    fx += s * vx;
    fy += s * vy;
    fz += s * vz;
    mx += s * (py * vz - pz * vy);
    my += s * (pz * vx - px * vz);
  }
  Vector5 f;
  f << fx, fy, fz, mx, my;
  return f;
}

#if defined(__AVX512F__)
bool avx512_kernel_available() { return true; }

namespace {
// 1/sqrt(x) to full double precision: 14-bit estimate, two Newton steps.
inline __m512d rsqrt(__m512d x) {
  const __m512d half = _mm512_set1_pd(0.5), three_halves = _mm512_set1_pd(1.5);
  __m512d y = _mm512_rsqrt14_pd(x);
  const __m512d hx = _mm512_mul_pd(half, x);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hx, _mm512_mul_pd(y, y), three_halves));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(hx, _mm512_mul_pd(y, y), three_halves));
  return y;
}
}  // namespace

Vector5 contact_force_avx512(const ContactKernelInput& in) {
  const __m512d cc = _mm512_set1_pd(in.cos_cage), sc = _mm512_set1_pd(in.sin_cage);
  const __m512d rho = _mm512_set1_pd(in.groove_centre_radius);
  const __m512d a_ca = _mm512_set1_pd(in.groove_centre_distance * in.cos_a0);
  const __m512d A = _mm512_set1_pd(in.groove_centre_distance);
  const __m512d a_g0 = _mm512_set1_pd(in.groove_centre_distance + in.clearance);
  const __m512d sign = _mm512_set1_pd(in.sign), kn = _mm512_set1_pd(in.stiffness), cn = _mm512_set1_pd(in.damping);
  const __m512d zero = _mm512_setzero_pd(), tiny = _mm512_set1_pd(1e-300);
  const __m512d q0 = _mm512_set1_pd(in.q[0]), q1 = _mm512_set1_pd(in.q[1]), q2 = _mm512_set1_pd(in.q[2]);
  const __m512d q3 = _mm512_set1_pd(in.q[3]), q4 = _mm512_set1_pd(in.q[4]);
  const __m512d d0 = _mm512_set1_pd(in.q_dot[0]), d1 = _mm512_set1_pd(in.q_dot[1]), d2 = _mm512_set1_pd(in.q_dot[2]);
  const __m512d d3 = _mm512_set1_pd(in.q_dot[3]), d4 = _mm512_set1_pd(in.q_dot[4]);
  __m512d fx = zero, fy = zero, fz = zero, mx = zero, my = zero;
  for (int b = 0; b < in.n; b += 8) {
    const __mmask8 lanes = in.n - b >= 8 ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>((1u << (in.n - b)) - 1u);
    const __m512d cb = _mm512_maskz_loadu_pd(lanes, in.cos_base + b);
    const __m512d sb = _mm512_maskz_loadu_pd(lanes, in.sin_base + b);
    const __m512d pz = _mm512_maskz_loadu_pd(lanes, in.groove_centre_z + b);
    const __m512d nz = _mm512_maskz_loadu_pd(lanes, in.normal_z + b);
    const __m512d off = _mm512_maskz_loadu_pd(lanes, in.offset + b);
    const __m512d cphi = _mm512_fmsub_pd(cc, cb, _mm512_mul_pd(sc, sb));
    const __m512d sphi = _mm512_fmadd_pd(sc, cb, _mm512_mul_pd(cc, sb));
    const __m512d px = _mm512_mul_pd(rho, cphi), py = _mm512_mul_pd(rho, sphi);
    const __m512d ux = _mm512_fmadd_pd(q4, pz, q0);
    const __m512d uy = _mm512_fnmadd_pd(q3, pz, q1);
    const __m512d uz = _mm512_fnmadd_pd(q4, px, _mm512_fmadd_pd(q3, py, q2));
    const __m512d vx = _mm512_fnmadd_pd(sign, ux, _mm512_mul_pd(a_ca, cphi));
    const __m512d vy = _mm512_fnmadd_pd(sign, uy, _mm512_mul_pd(a_ca, sphi));
    const __m512d vz = _mm512_fnmadd_pd(sign, uz, _mm512_mul_pd(A, nz));
    const __m512d n2 = _mm512_fmadd_pd(vx, vx, _mm512_fmadd_pd(vy, vy, _mm512_mul_pd(vz, vz)));
    // Masked-off lanes hold zeros: give them a harmless norm.
    const __m512d inv_norm = rsqrt(_mm512_mask_blend_pd(lanes, _mm512_set1_pd(1.0), n2));
    const __m512d norm = _mm512_mul_pd(n2, inv_norm);
    const __m512d deflection = _mm512_add_pd(_mm512_sub_pd(norm, a_g0), off);
    const __mmask8 touching = _mm512_mask_cmp_pd_mask(lanes, deflection, zero, _CMP_GT_OQ);
    const __m512d dp = _mm512_maskz_mov_pd(touching, deflection);
    const __m512d sqrt_dp = _mm512_mul_pd(dp, rsqrt(_mm512_max_pd(dp, tiny)));
    const __m512d wx = _mm512_mul_pd(sign, _mm512_fmadd_pd(d4, pz, d0));
    const __m512d wy = _mm512_mul_pd(sign, _mm512_fnmadd_pd(d3, pz, d1));
    const __m512d wz = _mm512_mul_pd(sign, _mm512_fnmadd_pd(d4, px, _mm512_fmadd_pd(d3, py, d2)));
    const __m512d v_dot_w = _mm512_fmadd_pd(vx, wx, _mm512_fmadd_pd(vy, wy, _mm512_mul_pd(vz, wz)));
    const __m512d rate = _mm512_mul_pd(_mm512_sub_pd(zero, v_dot_w), inv_norm);
    const __m512d load_raw = _mm512_fmadd_pd(cn, rate, _mm512_mul_pd(kn, _mm512_mul_pd(dp, sqrt_dp)));
    const __mmask8 pressing = _mm512_mask_cmp_pd_mask(touching, load_raw, zero, _CMP_GT_OQ);
    const __m512d load = _mm512_maskz_mov_pd(pressing, load_raw);
    const __m512d s = _mm512_mul_pd(sign, _mm512_mul_pd(load, inv_norm));
    fx = _mm512_fmadd_pd(s, vx, fx);
    fy = _mm512_fmadd_pd(s, vy, fy);
    fz = _mm512_fmadd_pd(s, vz, fz);
    mx = _mm512_fmadd_pd(s, _mm512_fmsub_pd(py, vz, _mm512_mul_pd(pz, vy)), mx);
    my = _mm512_fmadd_pd(s, _mm512_fmsub_pd(pz, vx, _mm512_mul_pd(px, vz)), my);
  }
  Vector5 f;
  f << _mm512_reduce_add_pd(fx), _mm512_reduce_add_pd(fy), _mm512_reduce_add_pd(fz), _mm512_reduce_add_pd(mx),
      _mm512_reduce_add_pd(my);
  return f;
}
#else
bool avx512_kernel_available() { return false; }
Vector5 contact_force_avx512(const ContactKernelInput&) {
  throw InvalidInputError("the AVX-512 contact kernel is not built for this CPU");
}
#endif

}  // namespace bearing_sim::detail
