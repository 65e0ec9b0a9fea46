#pragma once
// Standard normal numbers that are the same for a seed on every platform: Box-Muller on
// std::mt19937_64 (fully specified by the standard, unlike std::normal_distribution).
#include <cmath>
#include <cstdint>
#include <random>

#include "bearing_sim/core/constants.hpp"

namespace bearing_sim {

class SeededGaussian {
 public:
  // stream 0: the engine seeded with `seed` itself; stream k > 0: a sequence of its own per
  // (seed, k), through std::seed_seq (specified by the standard).
  explicit SeededGaussian(std::uint64_t seed = 1, std::uint32_t stream = 0) : seed_(seed), stream_(stream) {
    restart();
  }

  // Back to the first number of the sequence.
  void restart() {
    if (stream_ == 0) {
      rng_.seed(seed_);
    } else {
      std::seed_seq sequence{static_cast<std::uint32_t>(seed_), static_cast<std::uint32_t>(seed_ >> 32), stream_};
      rng_.seed(sequence);
    }
    has_spare_ = false;
  }

  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(rng_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = uniform();                                              // [0, 1)
    const double radius = std::sqrt(-2.0 * std::log(u1)), angle = 2.0 * kPi * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

  double uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t seed_;
  std::uint32_t stream_;
  std::mt19937_64 rng_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace bearing_sim
