// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "harmonic_sums.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "dispatch.hpp"
#include "hwy/contrib/math/math-inl.h"

#include "harmonic_sums.hpp"

#include <algorithm>
#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace bearing_sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Up to four harmonics per pass over the balls, their coefficients held in registers and
// the loop unrolled over them (a pass per harmonic would load and store every offset 2H
// times; an inner loop over a run-time count is a chain of dependent FMAs per ball).
template <int kHarmonics>
HWY_INLINE void AddGroup(const double* HWY_RESTRICT c, const double* HWY_RESTRICT terms, int n, const double* base,
                         double* out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
#if HWY_HAVE_SCALABLE
  // SVE's (and RVV's) vectors are sizeless types, which cannot be array elements: there each
  // coefficient is broadcast where it is used (a loop invariant of the loops over the balls).
  struct Broadcast {
    const double* every_other;
    V operator[](int h) const { return hn::Set(hn::ScalableTag<double>(), every_other[2 * h]); }
  };
  const Broadcast cos_coefficient{c}, sin_coefficient{c + 1};
#else
  V cos_coefficient[kHarmonics], sin_coefficient[kHarmonics];
  for (int h = 0; h < kHarmonics; ++h) {
    cos_coefficient[h] = hn::Set(d, c[2 * h]);
    sin_coefficient[h] = hn::Set(d, c[2 * h + 1]);
  }
#endif
  const auto add = [&](int b, V offset, auto load) HWY_ATTR {
    V sum = hn::Zero(d);
    for (int h = 0; h < kHarmonics; ++h) {
      const double* cosines = terms + 2 * static_cast<long>(h) * n + b;
      sum = hn::MulAdd(cos_coefficient[h], load(cosines), sum);
      sum = hn::NegMulAdd(sin_coefficient[h], load(cosines + n), sum);
    }
    return hn::Add(offset, sum);
  };
  const auto load = [&](const double* p) HWY_ATTR { return hn::LoadU(d, p); };
  int b = 0;
  // base may be out: each vector is loaded before it is stored.
  for (; b + lanes <= n; b += lanes) hn::StoreU(add(b, hn::LoadU(d, base + b), load), d, out + b);
  if (b == n) return;
  if (n >= lanes) {
    // The tail as the last full vector, its lanes already summed kept as they are (no read
    // past the arrays: a masked load may read the whole vector on some targets).
    const int last = n - lanes;
    const auto fresh = hn::Not(hn::FirstN(d, static_cast<std::size_t>(b - last)));
    const V summed = hn::LoadU(d, out + last);
    hn::StoreU(hn::IfThenElse(fresh, add(last, hn::LoadU(d, base + last), load), summed), d, out + last);
    return;
  }
  add_harmonic_sums_scalar(c, kHarmonics, terms, n, base, out);  // fewer balls than lanes
}

void AddHarmonicSums(const double* c, int harmonics, const double* terms, int n, const double* base, double* out) {
  for (int first = 0; first < harmonics; first += 4) {
    const double* group_c = c + 2 * first;
    const double* group_terms = terms + 2 * static_cast<long>(first) * n;
    const double* group_base = first == 0 ? base : out;  // later groups add to the first's sums
    switch (harmonics - first) {
      case 1:
        AddGroup<1>(group_c, group_terms, n, group_base, out);
        break;
      case 2:
        AddGroup<2>(group_c, group_terms, n, group_base, out);
        break;
      case 3:
        AddGroup<3>(group_c, group_terms, n, group_base, out);
        break;
      default:
        AddGroup<4>(group_c, group_terms, n, group_base, out);
        break;
    }
  }
}

// (cos, sin) of a lane of angles with Highway's vector Cos and Sin (a few ulp) where every
// angle is inside their valid range, else each with std::cos and std::sin.
void HarmonicCoefficients(const double* amplitude, const double* angle, int harmonics, double* coefficients) {
  const hn::ScalableTag<double> d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  constexpr double kValidRange = 39000.0;  // of hn::Cos and hn::Sin (hwy/contrib/math)
  constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  HWY_ALIGN double a[kMaxLanes], x[kMaxLanes], c[kMaxLanes], s[kMaxLanes];
  for (int first = 0; first < harmonics; first += lanes) {
    const int count = HWY_MIN(lanes, harmonics - first);
    bool in_range = true;
    for (int i = 0; i < lanes; ++i) {
      a[i] = i < count ? amplitude[first + i] : 0.0;
      x[i] = i < count ? angle[first + i] : 0.0;
      in_range = in_range && std::abs(x[i]) <= kValidRange;
    }
    if (in_range) {
      const auto v = hn::Load(d, x), amp = hn::Load(d, a);
      hn::Store(hn::Mul(amp, hn::Cos(d, v)), d, c);
      hn::Store(hn::Mul(amp, hn::Sin(d, v)), d, s);
    } else {
      for (int i = 0; i < count; ++i) {
        c[i] = a[i] * std::cos(x[i]);
        s[i] = a[i] * std::sin(x[i]);
      }
    }
    for (int i = 0; i < count; ++i) {
      coefficients[2 * (first + i)] = c[i];
      coefficients[2 * (first + i) + 1] = s[i];
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace bearing_sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace bearing_sim::detail {
HWY_EXPORT(AddHarmonicSums);
HWY_EXPORT(HarmonicCoefficients);

void harmonic_coefficients(const double* amplitude, const double* angle, int harmonics, double* coefficients) {
  if (harmonics > 0) BEARING_SIM_DISPATCH(HarmonicCoefficients)(amplitude, angle, harmonics, coefficients);
}

void add_harmonic_sums(const double* coefficients, int harmonics, const double* terms, int n, const double* base,
                       double* out) {
  if (n <= 0) return;
  if (harmonics > 0) BEARING_SIM_DISPATCH(AddHarmonicSums)(coefficients, harmonics, terms, n, base, out);
  else if (base != out) std::copy(base, base + n, out);
}

void add_harmonic_sums_scalar(const double* c, int harmonics, const double* terms, int n, const double* base,
                              double* out) {
  for (int b = 0; b < n; ++b) {
    double sum = 0.0;
    for (int h = 0; h < harmonics; ++h)
      sum += c[2 * h] * terms[2 * h * n + b] - c[2 * h + 1] * terms[(2 * h + 1) * n + b];
    out[b] = base[b] + sum;
  }
}
}  // namespace bearing_sim::detail
#endif  // HWY_ONCE
