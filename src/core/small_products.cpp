// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "small_products.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "small_products.hpp"

HWY_BEFORE_NAMESPACE();
namespace bearing_sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// out = base + m x, one block of `lanes` rows at a time; the last block overlaps the one
// before where the rows are not a multiple of the lanes (rows computed twice come out the
// same), so that every load and store is a full vector. The columns go into two accumulators
// (even and odd: half the chain of dependent FMAs). Sizes are constants: the loops unroll.
template <int kRows, int kCols>
HWY_INLINE void MultiplyAddFixed(const double* HWY_RESTRICT m, const double* HWY_RESTRICT x,
                                 const double* HWY_RESTRICT base, double* HWY_RESTRICT out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
  if (kRows < lanes) {  // one masked block
    const auto mask = hn::FirstN(d, kRows);
    V even = base ? hn::MaskedLoad(mask, d, base) : hn::Zero(d), odd = hn::Zero(d);
    for (int j = 0; j + 1 < kCols; j += 2) {
      even = hn::MulAdd(hn::MaskedLoad(mask, d, m + j * kRows), hn::Set(d, x[j]), even);
      odd = hn::MulAdd(hn::MaskedLoad(mask, d, m + (j + 1) * kRows), hn::Set(d, x[j + 1]), odd);
    }
    if (kCols % 2) even = hn::MulAdd(hn::MaskedLoad(mask, d, m + (kCols - 1) * kRows), hn::Set(d, x[kCols - 1]), even);
    hn::BlendedStore(hn::Add(even, odd), mask, d, out);
    return;
  }
  for (int block = 0; block < kRows; block += lanes) {
    const int r = block + lanes <= kRows ? block : kRows - lanes;
    V even = base ? hn::LoadU(d, base + r) : hn::Zero(d), odd = hn::Zero(d);
    for (int j = 0; j + 1 < kCols; j += 2) {
      even = hn::MulAdd(hn::LoadU(d, m + j * kRows + r), hn::Set(d, x[j]), even);
      odd = hn::MulAdd(hn::LoadU(d, m + (j + 1) * kRows + r), hn::Set(d, x[j + 1]), odd);
    }
    if (kCols % 2) even = hn::MulAdd(hn::LoadU(d, m + (kCols - 1) * kRows + r), hn::Set(d, x[kCols - 1]), even);
    hn::StoreU(hn::Add(even, odd), d, out + r);
  }
}

void MultiplyAdd5x10(const double* m, const double* x, const double* base, double* out) {
  MultiplyAddFixed<5, 10>(m, x, base, out);
}
void MultiplyAdd10x5(const double* m, const double* x, const double* base, double* out) {
  MultiplyAddFixed<10, 5>(m, x, base, out);
}
void MultiplyAdd15x30(const double* m, const double* x, const double* base, double* out) {
  MultiplyAddFixed<15, 30>(m, x, base, out);
}

}  // namespace HWY_NAMESPACE
}  // namespace bearing_sim::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace bearing_sim::detail {
HWY_EXPORT(MultiplyAdd5x10);
HWY_EXPORT(MultiplyAdd10x5);
HWY_EXPORT(MultiplyAdd15x30);

template <>
void multiply_add<10, 5>(const double* m, const double* x, const double* base, double* out) {
  HWY_DYNAMIC_DISPATCH(MultiplyAdd10x5)(m, x, base, out);
}
template <>
void multiply_add<15, 30>(const double* m, const double* x, const double* base, double* out) {
  HWY_DYNAMIC_DISPATCH(MultiplyAdd15x30)(m, x, base, out);
}
template <>
void multiply_add<5, 10>(const double* m, const double* x, const double* base, double* out) {
  HWY_DYNAMIC_DISPATCH(MultiplyAdd5x10)(m, x, base, out);
}
}  // namespace bearing_sim::detail
#endif  // HWY_ONCE
