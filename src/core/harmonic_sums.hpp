#pragma once
// The waviness offsets of a set of balls (internal to the core): per ball, the sum over the
// harmonics of a_h cos(k_h theta_b + psi_h) with the angle split into its fixed part (per
// ball, stored) and the part that turns with the phase (per harmonic, per call). Google
// Highway kernels compiled for every SIMD target and picked at run time, like the contact
// kernel; and the scalar loop they are tested against.
namespace bearing_sim::detail {

// out[b] = base[b] + sum over h < harmonics of c[2h] terms[2h n + b] - c[2h + 1] terms[(2h + 1) n + b],
// for b < n (terms: per harmonic, the n cosines then the n sines of its fixed angles); base
// may be out. A separate base spares the caller a copy of the constant offsets into out.
void add_harmonic_sums(const double* coefficients, int harmonics, const double* terms, int n, const double* base,
                       double* out);
void add_harmonic_sums_scalar(const double* coefficients, int harmonics, const double* terms, int n, const double* base,
                              double* out);

// The per-call coefficients: coefficients[2h] = amplitude[h] cos(angle[h]) and
// coefficients[2h + 1] = amplitude[h] sin(angle[h]), h < harmonics (a few ulp of std::cos and
// std::sin: Highway's vector functions, which replaced a sincos call per harmonic).
void harmonic_coefficients(const double* amplitude, const double* angle, int harmonics, double* coefficients);

}  // namespace bearing_sim::detail
