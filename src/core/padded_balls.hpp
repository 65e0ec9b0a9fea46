#pragma once
// The last, partial vector of balls of a SIMD contact kernel (contact_kernel.cpp,
// flexible_kernel.cpp; internal to the core): the balls' per-ball values copied into arrays of
// one vector's lanes, the lanes past the last ball filled with a ball at the cage angle with a
// 1 m gap, out of contact, so that they add exact zeros.
#include <cstddef>

namespace bearing_sim::detail {

struct PaddedBalls {
  static constexpr std::size_t kMaxLanes = 64;  // doubles in any target's vector (4096-bit SVE)
  alignas(64) double cos_base[kMaxLanes];
  alignas(64) double sin_base[kMaxLanes];
  alignas(64) double groove_centre_z[kMaxLanes];
  alignas(64) double normal_z[kMaxLanes];
  alignas(64) double offset[kMaxLanes];

  // Balls first .. first + lanes - 1 of arrays that hold n.
  PaddedBalls(const double* cb, const double* sb, const double* pz, const double* nz, const double* off,
              std::size_t first, std::size_t n, std::size_t lanes) {
    for (std::size_t i = 0; i < lanes; ++i) {
      const bool real = first + i < n;
      cos_base[i] = real ? cb[first + i] : 1.0;
      sin_base[i] = real ? sb[first + i] : 0.0;
      groove_centre_z[i] = real ? pz[first + i] : 0.0;
      normal_z[i] = real ? nz[first + i] : 0.0;
      offset[i] = real ? off[first + i] : -1.0;
    }
  }
};

}  // namespace bearing_sim::detail
