#include "contact_kernel.hpp"

#include <cmath>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim::detail {
namespace {
// The terms of the loaded centre vector v = A e0 - sign u (MODEL.md section 2) and of the
// rate sign G q_dot that do not depend on the ball within a row:
//   v = (a_ca cphi + vx0, a_ca sphi + vy0, vz0 + vz_s sphi + vz_c cphi),
//   w = (wx0, wy0, wz0 + wz_s sphi + wz_c cphi).
struct RowTerms {
  double a_ca, vx0, vy0, vz0, vz_s, vz_c, wx0, wy0, wz0, wz_s, wz_c, a_g0;
};

RowTerms row_terms(const ContactKernelInput& in) {
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

ContactSums contact_sums_portable(const ContactKernelInput& in) {
  const RowTerms t = row_terms(in);
  const double cc = in.cos_cage, sc = in.sin_cage, kn = in.stiffness, cn = in.damping;
  double sx = 0, sy = 0, sz = 0, szc = 0, szs = 0;
#pragma omp simd reduction(+ : sx, sy, sz, szc, szs)
  for (int b = 0; b < in.n; ++b) {
    const double cphi = cc * in.cos_base[b] - sc * in.sin_base[b];
    const double sphi = sc * in.cos_base[b] + cc * in.sin_base[b];
    const double vx = t.a_ca * cphi + t.vx0;
    const double vy = t.a_ca * sphi + t.vy0;
    const double vz = t.vz0 + t.vz_s * sphi + t.vz_c * cphi;
    const double norm = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double deflection = norm - t.a_g0 + in.offset[b];
    const double dp = deflection > 0.0 ? deflection : 0.0;
    // d(delta)/dt = -e . du/dt, with w = sign du/dt.
    const double wz = t.wz0 + t.wz_s * sphi + t.wz_c * cphi;
    const double inv_norm = 1.0 / norm;
    const double rate = -(vx * t.wx0 + vy * t.wy0 + vz * wz) * inv_norm;
    double load = kn * dp * std::sqrt(dp) + cn * rate;
    load = (deflection > 0.0 && load > 0.0) ? load : 0.0;
    const double s = load * inv_norm;
    const double s_vz = s * vz;
    sx += s * vx;
    sy += s * vy;
    sz += s_vz;
    szc += s_vz * cphi;
    szs += s_vz * sphi;
  }
  return ContactSums{sx, sy, sz, szc, szs};
}

#if defined(__AVX512F__)
bool avx512_kernel_available() { return true; }

ContactSums contact_sums_avx512(const ContactKernelInput& in) {
  const RowTerms t = row_terms(in);
  const __m512d cc = _mm512_set1_pd(in.cos_cage), sc = _mm512_set1_pd(in.sin_cage);
  const __m512d a_ca = _mm512_set1_pd(t.a_ca), vx0 = _mm512_set1_pd(t.vx0), vy0 = _mm512_set1_pd(t.vy0);
  const __m512d vz0 = _mm512_set1_pd(t.vz0), vz_s = _mm512_set1_pd(t.vz_s), vz_c = _mm512_set1_pd(t.vz_c);
  const __m512d wx0 = _mm512_set1_pd(t.wx0), wy0 = _mm512_set1_pd(t.wy0), wz0 = _mm512_set1_pd(t.wz0);
  const __m512d wz_s = _mm512_set1_pd(t.wz_s), wz_c = _mm512_set1_pd(t.wz_c);
  const __m512d a_g0 = _mm512_set1_pd(t.a_g0);
  const __m512d kn = _mm512_set1_pd(in.stiffness), cn = _mm512_set1_pd(in.damping);
  const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
  __m512d sx = zero, sy = zero, sz = zero, szc = zero, szs = zero;
  for (int b = 0; b < in.n; b += 8) {
    const __mmask8 lanes = in.n - b >= 8 ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>((1u << (in.n - b)) - 1u);
    const __m512d cb = _mm512_maskz_loadu_pd(lanes, in.cos_base + b);
    const __m512d sb = _mm512_maskz_loadu_pd(lanes, in.sin_base + b);
    const __m512d off = _mm512_maskz_loadu_pd(lanes, in.offset + b);
    const __m512d cphi = _mm512_fmsub_pd(cc, cb, _mm512_mul_pd(sc, sb));
    const __m512d sphi = _mm512_fmadd_pd(sc, cb, _mm512_mul_pd(cc, sb));
    const __m512d vx = _mm512_fmadd_pd(a_ca, cphi, vx0);
    const __m512d vy = _mm512_fmadd_pd(a_ca, sphi, vy0);
    const __m512d vz = _mm512_fmadd_pd(vz_s, sphi, _mm512_fmadd_pd(vz_c, cphi, vz0));
    const __m512d n2 = _mm512_fmadd_pd(vx, vx, _mm512_fmadd_pd(vy, vy, _mm512_mul_pd(vz, vz)));
    // Masked-off lanes may hold a zero vector: give them a harmless norm.
    const __m512d n2_safe = _mm512_mask_blend_pd(lanes, one, n2);
    const __m512d norm = _mm512_sqrt_pd(n2_safe);
    const __m512d deflection = _mm512_add_pd(norm, _mm512_sub_pd(off, a_g0));
    const __m512d inv_norm = _mm512_div_pd(one, norm);
    const __mmask8 touching = _mm512_mask_cmp_pd_mask(lanes, deflection, zero, _CMP_GT_OQ);
    const __m512d dp = _mm512_max_pd(deflection, zero);
    const __m512d sqrt_dp = _mm512_sqrt_pd(dp);
    const __m512d wz = _mm512_fmadd_pd(wz_s, sphi, _mm512_fmadd_pd(wz_c, cphi, wz0));
    const __m512d v_dot_w = _mm512_fmadd_pd(vx, wx0, _mm512_fmadd_pd(vy, wy0, _mm512_mul_pd(vz, wz)));
    // Q = kn dp^1.5 - cn (v . w) / |v|
    const __m512d load_raw =
        _mm512_fnmadd_pd(cn, _mm512_mul_pd(v_dot_w, inv_norm), _mm512_mul_pd(_mm512_mul_pd(kn, dp), sqrt_dp));
    const __mmask8 pressing = _mm512_mask_cmp_pd_mask(touching, load_raw, zero, _CMP_GT_OQ);
    const __m512d s = _mm512_maskz_mul_pd(pressing, load_raw, inv_norm);
    const __m512d s_vz = _mm512_mul_pd(s, vz);
    sx = _mm512_fmadd_pd(s, vx, sx);
    sy = _mm512_fmadd_pd(s, vy, sy);
    sz = _mm512_add_pd(sz, s_vz);
    szc = _mm512_fmadd_pd(s_vz, cphi, szc);
    szs = _mm512_fmadd_pd(s_vz, sphi, szs);
  }
  return ContactSums{_mm512_reduce_add_pd(sx), _mm512_reduce_add_pd(sy), _mm512_reduce_add_pd(sz),
                     _mm512_reduce_add_pd(szc), _mm512_reduce_add_pd(szs)};
}
#else
bool avx512_kernel_available() { return false; }
ContactSums contact_sums_avx512(const ContactKernelInput&) {
  throw InvalidInputError("the AVX-512 contact kernel is not built for this CPU");
}
#endif

}  // namespace bearing_sim::detail
