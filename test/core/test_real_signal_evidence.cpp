// The rules that make the envelope diagnosis hold on real machines (docs/health.md,
// "Evidence", rules 10-13): thresholds that keep their false-alarm rate when the spectrum is
// averaged, the chance that a window holds a line in a dense spectrum, pre-whitening, and
// harmonics shared by two series. Checked against closed forms and Monte Carlo draws.
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <unsupported/Eigen/FFT>

#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/spectrum.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

// One spectrum: the threshold is unchanged.
TEST(RealSignalEvidence, AveragedThresholdOfOneSpectrumIsTheSingleOne) {
  EXPECT_DOUBLE_EQ(averaged_threshold_db(12.0, 1.0), 12.0);
  EXPECT_DOUBLE_EQ(averaged_threshold_db(12.0, 0.5), 12.0);
}

// Monte Carlo: the average of K = 4 exponential powers (the bins of 4 averaged spectra of
// Gaussian noise) exceeds the averaged threshold over its median with the probability with
// which one exponential power exceeds 6 dB over its median, 2^-(10^0.6) = 0.0634. 400,000
// draws: standard error 0.6 %, so 5 % is eight of them.
TEST(RealSignalEvidence, AveragedThresholdKeepsTheFalseAlarmRate) {
  const int k = 4, draws = 400000;
  const double single_db = 6.0;
  const double p_single = std::pow(2.0, -std::pow(10.0, single_db / 10.0));
  const double ratio = std::pow(10.0, averaged_threshold_db(single_db, k) / 10.0);
  std::mt19937_64 rng(5);
  std::exponential_distribution<double> power(1.0);
  std::vector<double> averages(draws);
  for (double& a : averages) {
    a = 0.0;
    for (int j = 0; j < k; ++j) a += power(rng) / k;
  }
  std::vector<double> sorted = averages;
  std::nth_element(sorted.begin(), sorted.begin() + draws / 2, sorted.end());
  const double median = sorted[draws / 2];
  int above = 0;
  for (double a : averages) above += a > ratio * median ? 1 : 0;
  EXPECT_NEAR(static_cast<double>(above) / draws, p_single, 0.05 * p_single);
  EXPECT_LT(averaged_threshold_db(single_db, k), single_db);  // averaging narrows the noise
}

// Welch's equivalent number of averages for Hann segments overlapping by half.
TEST(RealSignalEvidence, EquivalentAveragesOfHalfOverlappedHannSegments) {
  EXPECT_DOUBLE_EQ(equivalent_averages(1), 1.0);
  EXPECT_NEAR(equivalent_averages(19), 19.0 / (1.0 + 2.0 * 0.167 * 0.167), 1e-12);
}

// A flat spectrum with m local maxima as high as the peak in the neighbourhood: the chance
// is 1 - exp(-(m + 1/2) / B x 2 w), B the bins counted (Hz), w the window's half width.
TEST(RealSignalEvidence, LineChanceCountsTheHigherMaximaAround) {
  Spectrum s;
  s.resolution_hz = 1.0;
  s.amplitude.assign(400, 1.0);
  for (std::size_t k = 0; k < s.amplitude.size(); ++k) s.amplitude[k] = 1.0 + 0.01 * std::sin(0.37 * k * k);  // no ties
  const double f0 = 200.0;
  s.amplitude[200] = 5.0;
  PeakSearchOptions o;
  const SpectralPeak peak = find_peak(s, f0, o);
  ASSERT_TRUE(peak.local_maximum);
  const double half = 2.0;  // +-1 % of 200 Hz
  // Neighbourhood +-20 % = 160..240 Hz, less the window and its guard (+-5 bins): 81 - 11 bins.
  const double bins = 81.0 - 11.0;
  EXPECT_NEAR(line_chance(s, peak, half, {}, 0.2, o), 1.0 - std::exp(-0.5 / bins * 2.0 * half), 1e-12);
  for (std::size_t k : {170u, 185u, 220u}) s.amplitude[k] = 6.0;  // three lines as high
  EXPECT_NEAR(line_chance(s, peak, half, {}, 0.2, o), 1.0 - std::exp(-3.5 / bins * 2.0 * half), 1e-12);
  // The same three declared as lines of the tested series: not counted, nor their windows'
  // bins (1 % or 1 bin each, plus the 3-bin guard: 2 x 3 + 1 = 7 bins, one overlapping).
  const double chance_own = line_chance(s, peak, half, {170.0, 185.0, 220.0}, 0.2, o);
  EXPECT_LT(chance_own, 1.0 - std::exp(-1.0 / bins * 2.0 * half));
}

// Pre-whitening: every bin of unit magnitude (above the floor), phases kept. A strong tone
// beside a train of impulses that scatter about their period: before, the tone holds nearly
// all the power (kurtosis of a sine, 1.5); after, it is one bin among thousands, and the
// impulses, broadband and not a line comb, dominate.
TEST(RealSignalEvidence, PrewhiteningFlattensLinesAndKeepsImpacts) {
  const double fs = 12000.0;
  const std::size_t n = 12000;
  std::vector<double> x(n);
  // Impulses every 120 samples, each moved by up to +-3 samples at random (a rolling
  // element's slip: without it they are a line comb, which the whitening flattens too).
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> shift(-3, 3);
  for (std::size_t i = 0; i < n; ++i) x[i] = 100.0 * std::sin(2.0 * kPi * 60.0 * i / fs);
  for (std::size_t k = 120; k + 3 < n; k += 120) x[static_cast<std::size_t>(static_cast<long>(k) + shift(rng))] += 5.0;
  std::normal_distribution<double> noise(0.0, 0.01);
  for (double& v : x) v += noise(rng);
  const std::vector<double> y = prewhiten(x);
  const Spectrum sx = amplitude_spectrum(x, fs), sy = amplitude_spectrum(y, fs);
  EXPECT_GT(sx.amplitude[60], 50.0);
  // Whitened, the 60 Hz bin is no larger than the rest (within the Hann window's leakage).
  double mean_y = 0.0;
  for (std::size_t k = 1; k + 1 < sy.amplitude.size(); ++k) mean_y += sy.amplitude[k] / (sy.amplitude.size() - 2);
  EXPECT_LT(sy.amplitude[60], 3.0 * mean_y);
  double m2 = 0.0, m4 = 0.0;
  for (double v : y) {
    m2 += v * v / n;
    m4 += v * v * v * v / n;
  }
  EXPECT_GT(m4 / (m2 * m2), 20.0);  // impulses: 100 per 12000 samples, kurtosis ~ 1/d
}

// A floor above a noise-free signal's rounding leaves those bins as they are (x / floor).
TEST(RealSignalEvidence, PrewhiteningBelowTheFloorIsLinear) {
  std::vector<double> x(1000, 0.0);
  x[10] = 1e-9;
  double share = 0.0;
  const std::vector<double> y = prewhiten(x, 1.0, &share);
  EXPECT_DOUBLE_EQ(share, 1.0);
  EXPECT_NEAR(y[10], (1e-9 - 1e-12), 1e-15);  // mean removed, divided by the floor 1
}

// A noise-free signal of strictly periodic lines with leakage (no whole number of periods
// in the window): the plain transform's leakage falls as 1/distance and fills every bin
// above a 1 ug/sqrt(Hz) floor, but the lines have no broadband floor around them. The share
// below the floor is counted on the Hann-windowed spectrum (leakage 1/distance^3), where
// nearly every bin between the lines is below it: whitening is not run on lines alone.
TEST(RealSignalEvidence, LinesAloneHaveNoBroadbandFloor) {
  const double fs = 10000.0, f0 = 107.36, floor_density = 1e-5;
  const std::size_t n = 20000;
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 1; k <= 20; ++k) x[i] += 0.5 / (k * k) * std::sin(2.0 * kPi * k * f0 * i / fs + 0.3 * k);
  const double floor = white_noise_bin_magnitude(floor_density, n, fs);
  double share = 0.0;
  prewhiten(x, floor, &share);
  EXPECT_GT(share, 0.9);
  // The plain transform's bins, counted as they are, would pass for a floor.
  std::vector<std::complex<double>> plain;
  Eigen::FFT<double> fft;
  fft.fwd(plain, x);
  std::size_t below = 0;
  for (const std::complex<double>& c : plain) below += std::abs(c) < floor ? 1 : 0;
  EXPECT_LT(static_cast<double>(below) / static_cast<double>(plain.size()), 0.5);
}

// The band's spectral kurtosis with a sensor floor added in closed form, SK (P / (P + P_n))^2
// (Antoni 2006), against the same band of the signal with that noise actually added: bursts
// of a 3 kHz resonance every 1/107 s, noise of a density that carries about the bursts' band
// power. The Monte Carlo kurtosis of 8 draws has a standard error of about
// 2 / sqrt(8 x 2000 bins) = 0.016 each; 0.1 is six of them.
TEST(RealSignalEvidence, SensorFloorLowersTheBandKurtosisAsAddedNoiseDoes) {
  const double fs = 10000.0, period_s = 1.0 / 107.0, low = 2000.0, high = 4000.0;
  const std::size_t n = 20000;
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = std::fmod(static_cast<double>(i) / fs, period_s);
    x[i] = std::exp(-t / 3e-4) * std::sin(2.0 * kPi * 3000.0 * t);
  }
  const double density = 2e-3;  // units/sqrt(Hz): a band noise of 0.09 RMS
  const BandKurtosis clean = band_spectral_kurtosis(x, fs, low, high);
  const BandKurtosis floored = band_spectral_kurtosis(x, fs, low, high, density);
  ASSERT_TRUE(clean.valid && floored.valid);
  EXPECT_GT(clean.kurtosis, 5.0);  // bursts filling about a tenth of each period
  double noisy = 0.0;
  std::mt19937_64 rng(17);
  std::normal_distribution<double> noise(0.0, density * std::sqrt(0.5 * fs));
  for (int draw = 0; draw < 8; ++draw) {
    std::vector<double> y = x;
    for (double& v : y) v += noise(rng);
    noisy += band_spectral_kurtosis(y, fs, low, high).kurtosis / 8.0;
  }
  EXPECT_LT(floored.kurtosis, 0.6 * clean.kurtosis);  // the floor matters here ...
  EXPECT_NEAR(floored.kurtosis, noisy, 0.1);          // ... exactly as real noise would
}

// The 6205 of the CWRU rig: 3 x BPFO and 2 x BPFI lie 0.7 % apart. An outer-race impact
// train (inner ring at 29.95 Hz, BPFO 107.4 Hz) in noise: its 3rd harmonic stands where the
// inner race's 2nd is searched. The outer race is present (its fundamental found), so that
// line is shared, no evidence for the inner race; the inner race is absent, so it stays the
// outer race's own. The outer race is named alone.
TEST(RealSignalEvidence, SharedHarmonicIsEvidenceForNeither) {
  const double fs = 12000.0, fr = 29.95, bpfo = 3.5848 * fr;
  BearingFrequencies f;
  f.ball_pass_outer_race_hz = bpfo;
  f.ball_pass_inner_race_hz = 5.4152 * fr;
  f.ball_spin_hz = 0.5 * 4.7135 * fr;
  f.cage_hz = 0.39828 * fr;
  f.inner_ring_hz = fr;
  f.relative_ring_hz = fr;
  f.varying_compliance_hz = bpfo;
  // Impacts ringing a 3.5 kHz resonance, each at its place on the period grid with a random
  // scatter of 1 % of the period (a rolling element's slip; not accumulating).
  const double wn = 2.0 * kPi * 3500.0, a = 0.03 * wn;
  std::vector<double> x(static_cast<std::size_t>(10.0 * fs));
  std::mt19937_64 rng(8);
  std::normal_distribution<double> noise(0.0, 0.1), scatter(0.0, 0.01 / bpfo);
  std::vector<double> impacts;
  for (int k = 0; k < 10.0 * bpfo + 1; ++k) impacts.push_back(k / bpfo + scatter(rng));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / fs;
    const auto next = std::upper_bound(impacts.begin(), impacts.end(), t);
    const double since = next == impacts.begin() ? 1.0 : t - *(next - 1);
    x[i] = std::exp(-a * since) * std::sin(wn * since) + noise(rng);
  }
  const ConditionIndicators c = analyze_vibration(x, fs, f);
  EXPECT_GT(c.envelope_segments, 10u);  // 10 s in 1 s segments overlapping by half
  const FaultIndicator& outer = c.faults[0];
  const FaultIndicator& inner = c.faults[1];
  EXPECT_TRUE(outer.suspected) << c.diagnosis.reason << " | " << outer.note;
  EXPECT_FALSE(outer.harmonics[2].shared);  // no inner-race fundamental: 3 x BPFO is its own
  EXPECT_TRUE(inner.harmonics[1].shared);   // 2 x BPFI on the present 3 x BPFO
  EXPECT_FALSE(inner.suspected);
  EXPECT_EQ(c.diagnosis.verdict.outcome, VerdictOutcome::Fault);
  ASSERT_EQ(c.diagnosis.verdict.kinds.size(), 1u);
  EXPECT_EQ(c.diagnosis.verdict.kinds[0], FaultKind::OuterRace);
}

}  // namespace
}  // namespace bearing_sim
