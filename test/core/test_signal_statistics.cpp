// Time-domain indicators against closed forms: a sine (RMS A/sqrt 2, crest sqrt 2,
// kurtosis <sin^4>/<sin^2>^2 = (3/8)/(1/4) = 1.5) and Gaussian noise (kurtosis 3).
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/signal_statistics.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

// 50 Hz at 10 kHz: 200 samples per period, so sample 50 of each period is the exact crest.
std::vector<double> sine(double amplitude, double offset, int periods = 20) {
  std::vector<double> x(200 * periods);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = offset + amplitude * std::sin(2.0 * test::kPi * i / 200.0);
  return x;
}

TEST(SignalStatistics, SineHasRmsOverSqrt2AndCrestSqrt2) {
  const SignalStatistics s = signal_statistics(sine(3.0, 0.0));
  // Whole periods: the discrete means of sin^2 and sin^4 are exact, so only rounding remains.
  EXPECT_NEAR(s.rms, 3.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.peak, 3.0, 1e-12);
  EXPECT_NEAR(s.crest_factor, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.kurtosis, 1.5, 1e-12);
  EXPECT_NEAR(crest_factor(sine(1.0, 0.0)), std::sqrt(2.0), 1e-12);
}

TEST(SignalStatistics, OffsetIsRemoved) {
  // An AC-coupled accelerometer would not see the 9.81 m/s^2 offset; neither do the indicators.
  const SignalStatistics s = signal_statistics(sine(3.0, 9.81));
  EXPECT_NEAR(s.mean, 9.81, 1e-12);
  EXPECT_NEAR(s.rms, 3.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(s.crest_factor, std::sqrt(2.0), 1e-12);
}

TEST(SignalStatistics, GaussianNoise) {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n(1.0, 0.5);
  std::vector<double> x(400000);
  for (double& v : x) v = n(rng);
  const SignalStatistics s = signal_statistics(x);
  // Standard errors for N = 4e5: RMS sigma/sqrt(2N) = 0.11%, kurtosis sqrt(24/N) = 0.008.
  EXPECT_NEAR(s.rms, 0.5, 0.5 * 0.005);
  EXPECT_NEAR(s.kurtosis, 3.0, 0.04);
  // The largest of 4e5 Gaussian samples lies near 4.5-5 sigma.
  EXPECT_GT(s.crest_factor, 4.0);
  EXPECT_LT(s.crest_factor, 5.8);
}

TEST(SignalStatistics, ImpulseTrainIsHighlyKurtic) {
  // One unit impulse in every 100 samples: m2 = 1/100 - 1/100^2, kurtosis ~ 1/(p) = 100 for
  // a sparse train (exact: (1 - 3p + 3p^2) / (p (1 - p)) with p = 0.01 -> 97.0).
  std::vector<double> x(10000, 0.0);
  for (std::size_t i = 0; i < x.size(); i += 100) x[i] = 1.0;
  const double p = 0.01;
  EXPECT_NEAR(kurtosis(x), (1.0 - 3.0 * p + 3.0 * p * p) / (p * (1.0 - p)), 1e-9);
}

TEST(SignalStatistics, WindowAndErrors) {
  std::vector<double> x = sine(1.0, 0.0);
  x.insert(x.begin(), 1000, 50.0);  // a constant lead-in left outside the window
  const SignalStatistics s = signal_statistics(x, 1000, x.size());
  EXPECT_NEAR(s.rms, 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(s.samples, 4000u);
  EXPECT_THROW(signal_statistics(x, 5, 5), InvalidInputError);
  EXPECT_THROW(signal_statistics(std::vector<double>{}), InvalidInputError);
  x[2000] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(signal_statistics(x), InvalidInputError);
  // A constant signal: zero RMS, and crest factor and kurtosis reported as 0 (undefined).
  const SignalStatistics c = signal_statistics(std::vector<double>(10, 2.0));
  EXPECT_EQ(c.rms, 0.0);
  EXPECT_EQ(c.crest_factor, 0.0);
}

// One sample at a time gives the two-pass statistics: an impulsive noise signal on a 5 V bias
// (a voltage output), where a one-pass sum of powers of x would lose the moments. The
// updates round differently from the two passes: 1e-9 of each value holds that.
TEST(SignalStatistics, StreamedEqualsTwoPass) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 0.01);
  std::vector<double> x(20000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 5.0 + n(rng) + (i % 500 == 0 ? 0.2 : 0.0);
  StreamedStatistics streamed;
  for (double v : x) streamed.add(v);
  const SignalStatistics a = streamed.statistics(), b = signal_statistics(x);
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_NEAR(a.mean, b.mean, 1e-9 * b.mean);
  EXPECT_NEAR(a.rms, b.rms, 1e-9 * b.rms);
  EXPECT_NEAR(a.peak, b.peak, 1e-9 * b.peak);
  EXPECT_NEAR(a.crest_factor, b.crest_factor, 1e-9 * b.crest_factor);
  EXPECT_NEAR(a.kurtosis, b.kurtosis, 1e-9 * b.kurtosis);
  EXPECT_GT(b.kurtosis, 3.5);  // the impulses show, so the check is not of plain noise
  EXPECT_EQ(StreamedStatistics().statistics().rms, 0.0);
}

}  // namespace
}  // namespace bearing_sim
