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

// A zero-mean, unit-variance value for (key, knot): the sum of the four 16-bit uniforms of one
// hash (Irwin-Hall, within +-2 sqrt 3), a near-normal value at a tenth of Box-Muller's cost,
// where sums of many of them make the law and only the variance has to be exact.
inline double knot_unit(std::uint64_t key, std::int64_t knot) {
  const std::uint64_t h = mix64(key ^ mix64(static_cast<std::uint64_t>(knot)));
  const double sum = static_cast<double>((h & 0xffff) + ((h >> 16) & 0xffff) + ((h >> 32) & 0xffff) + (h >> 48));
  // Four uniforms on [0, 1) in steps of 2^-16: mean 2 - 2^-15, variance (1 - 2^-32) / 3.
  constexpr double kMean = 2.0 * 65535.0, kScale = 1.7320508075688772 / 65536.0 / 0.99999999988358467;
  return (sum - kMean) * kScale;
}

// A random walk at step n: the sum of |n| steps of zero mean and unit variance, uncorrelated
// (n < 0: the walk run backwards from 0), a pure function of (key, n) for |n| <= 2^39. Built
// by Levy's construction: the ends of [0, 2^39] and [-2^39, 0] drawn first, then the middle
// of the half holding n, given its ends (their mean plus sqrt(length) / 2 times a unit
// value), down to n: 40 values at most, each dyadic point's keyed by the point itself. The
// construction is linear, so any two steps' covariance is the walk's, min(|m|, |n|) on one
// side of 0, in whatever order they are asked; with knot_unit's values the steps are nearly
// normal (each a sum of ~40 of them).
inline double random_walk(std::uint64_t key, std::int64_t n) {
  constexpr std::int64_t kHalfSpan = std::int64_t{1} << 39;
  if (n > kHalfSpan) n = kHalfSpan;
  if (n < -kHalfSpan) n = -kHalfSpan;
  if (n == 0) return 0.0;
  std::int64_t lo = n > 0 ? 0 : -kHalfSpan, hi = n > 0 ? kHalfSpan : 0;
  const double end = std::sqrt(static_cast<double>(kHalfSpan)) * knot_unit(key, n > 0 ? hi : lo);
  double w_lo = n > 0 ? 0.0 : end, w_hi = n > 0 ? end : 0.0;
  while (n != lo && n != hi) {
    const std::int64_t mid = lo + (hi - lo) / 2;
    const double w_mid = 0.5 * (w_lo + w_hi) + 0.5 * std::sqrt(static_cast<double>(hi - lo)) * knot_unit(key, mid);
    if (n < mid) {
      hi = mid;
      w_hi = w_mid;
    } else {
      lo = mid;
      w_lo = w_mid;
    }
  }
  return n == lo ? w_lo : w_hi;
}

}  // namespace bearing_sim::detail
