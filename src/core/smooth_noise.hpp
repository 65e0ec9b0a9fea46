#pragma once
// A smooth, stationary random function of time that is a pure function of (key, time): the
// same value for any evaluation order, trial state or thread, so that the force evaluations
// of an integrator step (which need not come in time order) all see one realisation.
#include <cmath>
#include <cstdint>

#include "bearing_sim/core/constants.hpp"

namespace bearing_sim::detail {

// SplitMix64 (Steele, Lea and Flood 2014): a well-mixed 64-bit hash of a 64-bit input.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A standard normal value for (key, knot), by Box-Muller from two hashed uniforms.
inline double knot_normal(std::uint64_t key, std::int64_t knot) {
  const std::uint64_t h1 = mix64(key ^ mix64(static_cast<std::uint64_t>(knot)));
  const std::uint64_t h2 = mix64(h1);
  const double u1 = (static_cast<double>(h1 >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
  const double u2 = static_cast<double>(h2 >> 11) * 0x1.0p-53;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

// Unit-variance Gaussian process in x = time / correlation time: independent standard
// normal values at the integers, linearly interpolated and divided by the interpolation's
// standard deviation sqrt((1 - f)^2 + f^2), so the variance is 1 at every x. Values one knot
// apart or more are independent; within a knot the function moves by O(1) over x ~ 1.
inline double smooth_normal(std::uint64_t key, double x) {
  const double knot = std::floor(x);
  const double f = x - knot;
  const auto k = static_cast<std::int64_t>(knot);
  return ((1.0 - f) * knot_normal(key, k) + f * knot_normal(key, k + 1)) / std::sqrt((1.0 - f) * (1.0 - f) + f * f);
}

}  // namespace bearing_sim::detail
