// Compiled once per Highway target (hwy/foreach_target.h re-includes this file with the
// target's attributes); the dispatcher picks the best one the CPU runs.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "small_products.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

#include "dispatch.hpp"

#include "small_products.hpp"

#include <algorithm>
#include <cstddef>

HWY_BEFORE_NAMESPACE();
namespace bearing_sim::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// out = base + m x, one block of `lanes` rows at a time; the last block overlaps the one
// before where the rows are not a multiple of the lanes (rows computed twice come out the
// same), so that every load and store is a full vector. The columns go into two accumulators
// (half the chain of dependent FMAs), from the last to the first: the Adams step's x is
// (y, r, r_-1, r_-2, r_-3), and y, the corrector's result, is the last entry computed, so
// the sums start on the history while the corrector finishes (7 % faster on the INS pair).
// Sizes are constants: the loops unroll.
template <int kRows, int kCols>
HWY_INLINE void MultiplyAddFixed(const double* HWY_RESTRICT m, const double* HWY_RESTRICT x,
                                 const double* HWY_RESTRICT base, double* HWY_RESTRICT out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const int lanes = static_cast<int>(hn::Lanes(d));
  if (kRows < lanes) {  // one masked block
    const auto mask = hn::FirstN(d, kRows);
    V even = base ? hn::MaskedLoad(mask, d, base) : hn::Zero(d), odd = hn::Zero(d);
    for (int j = kCols - 1; j > 0; j -= 2) {
      even = hn::MulAdd(hn::MaskedLoad(mask, d, m + j * kRows), hn::Set(d, x[j]), even);
      odd = hn::MulAdd(hn::MaskedLoad(mask, d, m + (j - 1) * kRows), hn::Set(d, x[j - 1]), odd);
    }
    if (kCols % 2) even = hn::MulAdd(hn::MaskedLoad(mask, d, m), hn::Set(d, x[0]), even);
    hn::BlendedStore(hn::Add(even, odd), mask, d, out);
    return;
  }
#if !HWY_HAVE_SCALABLE
  // Fixed vector width: the blocks side by side, so that each x[j] is broadcast once for all
  // of them rather than once per block (the 15x30 product on AVX2 was bound by its loads:
  // 4 x 30 broadcasts and 120 matrix columns). The same sums in the same order as below.
  constexpr int kLanes = static_cast<int>(hn::MaxLanes(hn::ScalableTag<double>()));
  if constexpr (kRows >= kLanes) {
    constexpr int kBlocks = (kRows + kLanes - 1) / kLanes;
    int row[kBlocks];
    V even[kBlocks], odd[kBlocks];
#pragma GCC unroll 8
    for (int k = 0; k < kBlocks; ++k) {
      row[k] = (k + 1) * kLanes <= kRows ? k * kLanes : kRows - kLanes;
      even[k] = base ? hn::LoadU(d, base + row[k]) : hn::Zero(d);
      odd[k] = hn::Zero(d);
    }
#pragma GCC unroll 32
    for (int j = kCols - 1; j > 0; j -= 2) {
      const V xe = hn::Set(d, x[j]), xo = hn::Set(d, x[j - 1]);
#pragma GCC unroll 8
      for (int k = 0; k < kBlocks; ++k) {
        even[k] = hn::MulAdd(hn::LoadU(d, m + j * kRows + row[k]), xe, even[k]);
        odd[k] = hn::MulAdd(hn::LoadU(d, m + (j - 1) * kRows + row[k]), xo, odd[k]);
      }
    }
#pragma GCC unroll 8
    for (int k = 0; k < kBlocks; ++k) {
      if (kCols % 2) even[k] = hn::MulAdd(hn::LoadU(d, m + row[k]), hn::Set(d, x[0]), even[k]);
      hn::StoreU(hn::Add(even[k], odd[k]), d, out + row[k]);
    }
    return;
  }
#endif
  for (int block = 0; block < kRows; block += lanes) {
    const int r = block + lanes <= kRows ? block : kRows - lanes;
    V even = base ? hn::LoadU(d, base + r) : hn::Zero(d), odd = hn::Zero(d);
    for (int j = kCols - 1; j > 0; j -= 2) {
      even = hn::MulAdd(hn::LoadU(d, m + j * kRows + r), hn::Set(d, x[j]), even);
      odd = hn::MulAdd(hn::LoadU(d, m + (j - 1) * kRows + r), hn::Set(d, x[j - 1]), odd);
    }
    if (kCols % 2) even = hn::MulAdd(hn::LoadU(d, m + r), hn::Set(d, x[0]), even);
    hn::StoreU(hn::Add(even, odd), d, out + r);
  }
}

#if !HWY_HAVE_SCALABLE
// kCount blocks of `lanes` rows side by side (rows[k] their first rows), each x[j] broadcast
// once for all of them: the same sums in the same order as one block at a time.
template <int kCount>
HWY_INLINE void MultiplyAddBlocks(int cols, int rows, const int* row, const double* HWY_RESTRICT m,
                                  const double* HWY_RESTRICT x, const double* HWY_RESTRICT base,
                                  double* HWY_RESTRICT out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  V even[kCount], odd[kCount];
#pragma GCC unroll 4
  for (int k = 0; k < kCount; ++k) {
    even[k] = base ? hn::LoadU(d, base + row[k]) : hn::Zero(d);
    odd[k] = hn::Zero(d);
  }
  int j = cols - 1;
  for (; j > 0; j -= 2) {
    const V xe = hn::Set(d, x[j]), xo = hn::Set(d, x[j - 1]);
    const double* me = m + static_cast<std::size_t>(j) * rows;
    const double* mo = me - rows;
#pragma GCC unroll 4
    for (int k = 0; k < kCount; ++k) {
      even[k] = hn::MulAdd(hn::LoadU(d, me + row[k]), xe, even[k]);
      odd[k] = hn::MulAdd(hn::LoadU(d, mo + row[k]), xo, odd[k]);
    }
  }
  if (j == 0) {
    const V x0 = hn::Set(d, x[0]);
#pragma GCC unroll 4
    for (int k = 0; k < kCount; ++k) even[k] = hn::MulAdd(hn::LoadU(d, m + row[k]), x0, even[k]);
  }
#pragma GCC unroll 4
  for (int k = 0; k < kCount; ++k) hn::StoreU(hn::Add(even[k], odd[k]), d, out + row[k]);
}
#endif

void MultiplyAddAnySize(int rows, int cols, const double* HWY_RESTRICT m, const double* HWY_RESTRICT x,
                        const double* HWY_RESTRICT base, double* HWY_RESTRICT out) {
  const hn::ScalableTag<double> d;
  const int lanes = static_cast<int>(hn::Lanes(d));
  if (rows < lanes) {  // fewer rows than one vector: plain sums
    for (int i = 0; i < rows; ++i) {
      double sum = base ? base[i] : 0.0;
      for (int j = 0; j < cols; ++j) sum += m[static_cast<std::size_t>(j) * rows + i] * x[j];
      out[i] = sum;
    }
    return;
  }
#if !HWY_HAVE_SCALABLE
  // Four blocks at a time (8 accumulators): the flexible ring's 50-row products were bound by
  // their loads, a broadcast of x[j] per block and column.
  const int blocks = (rows + lanes - 1) / lanes;
  for (int first = 0; first < blocks; first += 4) {
    int row[4] = {0, 0, 0, 0};
    const int count = std::min(4, blocks - first);
    for (int k = 0; k < count; ++k) {
      const int block = (first + k) * lanes;
      row[k] = block + lanes <= rows ? block : rows - lanes;
    }
    switch (count) {
      case 4:
        MultiplyAddBlocks<4>(cols, rows, row, m, x, base, out);
        break;
      case 3:
        MultiplyAddBlocks<3>(cols, rows, row, m, x, base, out);
        break;
      case 2:
        MultiplyAddBlocks<2>(cols, rows, row, m, x, base, out);
        break;
      default:
        MultiplyAddBlocks<1>(cols, rows, row, m, x, base, out);
        break;
    }
  }
#else
  using V = hn::Vec<decltype(d)>;
  for (int block = 0; block < rows; block += lanes) {
    const int r = block + lanes <= rows ? block : rows - lanes;
    V even = base ? hn::LoadU(d, base + r) : hn::Zero(d), odd = hn::Zero(d);
    int j = cols - 1;
    for (; j > 0; j -= 2) {
      even = hn::MulAdd(hn::LoadU(d, m + static_cast<std::size_t>(j) * rows + r), hn::Set(d, x[j]), even);
      odd = hn::MulAdd(hn::LoadU(d, m + static_cast<std::size_t>(j - 1) * rows + r), hn::Set(d, x[j - 1]), odd);
    }
    if (j == 0) even = hn::MulAdd(hn::LoadU(d, m + r), hn::Set(d, x[0]), even);
    hn::StoreU(hn::Add(even, odd), d, out + r);
  }
#endif
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
HWY_EXPORT(MultiplyAddAnySize);

void multiply_add(int rows, int cols, const double* m, const double* x, const double* base, double* out) {
  BEARING_SIM_DISPATCH(MultiplyAddAnySize)(rows, cols, m, x, base, out);
}

template <>
void multiply_add<10, 5>(const double* m, const double* x, const double* base, double* out) {
  BEARING_SIM_DISPATCH(MultiplyAdd10x5)(m, x, base, out);
}
template <>
void multiply_add<15, 30>(const double* m, const double* x, const double* base, double* out) {
  BEARING_SIM_DISPATCH(MultiplyAdd15x30)(m, x, base, out);
}
template <>
void multiply_add<5, 10>(const double* m, const double* x, const double* base, double* out) {
  BEARING_SIM_DISPATCH(MultiplyAdd5x10)(m, x, base, out);
}
}  // namespace bearing_sim::detail
#endif  // HWY_ONCE
