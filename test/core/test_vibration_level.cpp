// Vibration acceleration level (JB/T 5314) and RMS statistics against direct computation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

TEST(VibrationLevel, SineOfKnownAmplitude) {
  // 1 m/s^2 amplitude sine at 313 Hz sampled at 10 kHz for an integer number of periods
  // (313 x 0.1 s is not integer, 100 Hz is): RMS = A / sqrt 2 exactly in the discrete sum.
  const double amplitude = 1.0;
  std::vector<double> x(10000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.3 + amplitude * std::sin(2.0 * kPi * 100.0 * i / 1e4);
  const double rms = rms_about_mean(x, 0, x.size());
  EXPECT_NEAR(rms, amplitude / std::sqrt(2.0), 1e-12);  // exact for whole periods: rounding only
  EXPECT_NEAR(mean(x, 0, x.size()), 0.3, 1e-12);
  // L = 20 lg(0.7071 / 9.81e-3) = 37.156 dB (hand: lg 72.08 = 1.8578).
  EXPECT_NEAR(vibration_level_db(rms), 37.156, 1e-3);
  EXPECT_NEAR(vibration_level_db(9.81e-3), 0.0, 1e-12);
  EXPECT_NEAR(vibration_level_db(9.81e-2), 20.0, 1e-12);
  // docs/model.md section 11.2: the smooth CT bearing at ~1e-4 m/s^2 is at about -40 dB.
  EXPECT_NEAR(vibration_level_db(1e-4), -39.83, 0.01);
  EXPECT_EQ(vibration_level_db(0.0), -std::numeric_limits<double>::infinity());
  EXPECT_THROW(vibration_level_db(-1.0), InvalidInputError);
  EXPECT_THROW(vibration_level_db(std::nan("")), InvalidInputError);
}

TEST(VibrationLevel, RunningRmsMatchesDirect) {
  // Pseudo-random signal with a large offset (stresses the sum-of-squares update).
  std::vector<double> x;
  unsigned s = 12345;
  for (int i = 0; i < 5000; ++i) {
    s = s * 1103515245u + 12345u;
    x.push_back(1000.0 + ((s >> 8) % 10000) / 10000.0 - 0.5);
  }
  const std::size_t window = 777;
  RunningRms r(window);
  for (std::size_t i = 0; i < x.size(); ++i) {
    r.add(x[i]);
    const std::size_t begin = i + 1 >= window ? i + 1 - window : 0;
    if (i % 97 == 0 || i + 1 == x.size()) {
      const double direct = rms_about_mean(x, begin, i + 1);
      // Running sums in long double about an offset of 1000: 1e-6 relative is ample.
      EXPECT_NEAR(r.rms(), direct, 1e-6 * direct) << i;
      EXPECT_EQ(r.size(), std::min(i + 1, window));
    }
  }
  // Uniform noise of width 1: RMS 1/sqrt 12 (statistical, 5% with 777 samples).
  EXPECT_NEAR(r.rms(), 1.0 / std::sqrt(12.0), 0.05 / std::sqrt(12.0));
  EXPECT_THROW(RunningRms(0), InvalidInputError);
  RunningRms c(10);
  for (int i = 0; i < 25; ++i) c.add(5.0);
  EXPECT_NEAR(c.rms(), 0.0, 1e-9);  // constant signal: zero RMS about the mean
}
