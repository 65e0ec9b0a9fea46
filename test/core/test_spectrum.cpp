// FFT helpers against closed forms: tone amplitudes, band-pass, Hilbert envelope of an
// AM signal, velocity of a sine (a / omega / sqrt 2), the SNR of a tone in white noise.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/spectrum.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

std::vector<double> tone(std::size_t n, double fs, double f, double a, double phase = 0.0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = a * std::cos(2.0 * kPi * f * i / fs + phase);
  return x;
}

TEST(Spectrum, FftFriendlyLength) {
  EXPECT_EQ(fft_friendly_length(32000), 32000u);  // 2^8 5^3
  EXPECT_EQ(fft_friendly_length(31249), 31104u);  // 2^7 3^5; no 2^a 3^b 5^c in 31105..31249
  EXPECT_EQ(fft_friendly_length(1), 1u);
  EXPECT_EQ(fft_friendly_length(97), 96u);  // 97 is prime; 96 = 2^5 3
  EXPECT_EQ(fft_friendly_length(1024), 1024u);
}

TEST(Spectrum, ToneAtBinCentreReadsItsAmplitude) {
  const double fs = 10000.0;
  const std::size_t n = 10000;  // 1 Hz bins
  std::vector<double> x = tone(n, fs, 120.0, 2.5);
  for (double& v : x) v += 4.0;  // DC is removed
  const Spectrum s = amplitude_spectrum(x, fs);
  EXPECT_DOUBLE_EQ(s.resolution_hz, 1.0);
  // Hann window with coherent-gain correction: exact at a bin centre.
  EXPECT_NEAR(s.amplitude[120], 2.5, 1e-9);
  EXPECT_NEAR(s.amplitude[121], 1.25, 1e-9);  // the Hann lobe: half in the neighbours
  EXPECT_NEAR(s.amplitude[0], 0.0, 1e-9);
  EXPECT_NEAR(s.amplitude[200], 0.0, 1e-9);
}

TEST(Spectrum, BandPassKeepsOnlyTheBand) {
  const double fs = 8000.0;
  const std::size_t n = 8000;
  const std::vector<double> low = tone(n, fs, 100.0, 1.0), high = tone(n, fs, 3000.0, 0.3, 0.7);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = low[i] + high[i];
  const std::vector<double> y = band_pass(x, fs, 1000.0, 3500.0);
  // Whole periods of both tones: each sits in one bin pair, so masking is exact.
  for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(y[i], high[i], 1e-9) << i;
  EXPECT_THROW(band_pass(x, fs, 500.0, 400.0), InvalidInputError);
}

TEST(Spectrum, HilbertEnvelopeOfAmSignal) {
  // (1 + m cos(2 pi fm t)) cos(2 pi fc t): the envelope is 1 + m cos(2 pi fm t) exactly
  // when the spectra do not overlap zero frequency (fc > fm) and all lines fall on bins.
  const double fs = 20000.0, fc = 3000.0, fm = 100.0, m = 0.5;
  const std::size_t n = 20000;
  std::vector<double> x(n), expected(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = i / fs;
    expected[i] = 1.0 + m * std::cos(2.0 * kPi * fm * t);
    x[i] = expected[i] * std::cos(2.0 * kPi * fc * t);
  }
  const std::vector<double> e = hilbert_envelope(x);
  for (std::size_t i = 0; i < n; i += 7) ASSERT_NEAR(e[i], expected[i], 1e-9) << i;
  // The envelope spectrum shows the modulation: m at fm.
  const Spectrum s = envelope_spectrum(x, fs, 2000.0, 4000.0);
  EXPECT_NEAR(s.amplitude[100], m, 1e-9);
}

TEST(Spectrum, VelocityOfASineInAndOutOfBand) {
  const double fs = 20000.0;
  const std::size_t n = 30000;  // 1.5 s: 0.667 Hz bins; 123.4 Hz is between bins
  const double a = 5.0, f = 123.4;
  const double expected = a / (2.0 * kPi * f) / std::sqrt(2.0);  // a / omega / sqrt 2
  // Windowed Parseval: the whole Hann lobe is summed, so no scalloping loss; 0.5% covers
  // the variation of 1/omega^2 over the lobe and the lobe's far tails.
  EXPECT_NEAR(band_velocity_rms(tone(n, fs, f, a, 0.3), fs, 10.0, 1000.0), expected, 0.005 * expected);
  // The same sine at 3 kHz is outside 10-1000 Hz: nothing of it may leak in, even though
  // dividing by the small omega of 10 Hz would magnify any leakage 300-fold.
  const double out = band_velocity_rms(tone(n, fs, 3000.3, a, 0.3), fs, 10.0, 1000.0);
  EXPECT_LT(out, 1e-4 * a / (2.0 * kPi * 3000.3));
  // The time signal: integral of a cos(w t) is (a/w) sin(w t) (whole periods: exact).
  const double fw = 100.0;
  const std::vector<double> v = integrate_to_velocity(tone(20000, fs, fw, a), fs, 10.0, 1000.0);
  const double w = 2.0 * kPi * fw;
  for (std::size_t i = 0; i < v.size(); i += 13) ASSERT_NEAR(v[i], a / w * std::sin(w * i / fs), 1e-9 * a / w);
}

TEST(Spectrum, PeakSnrOfAToneInWhiteNoise) {
  const double fs = 16384.0;
  const std::size_t n = 16384;
  std::vector<double> x = tone(n, fs, 1000.0, 1.0);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (double& v : x) v += noise(rng);
  const Spectrum s = amplitude_spectrum(x, fs);
  const SpectralPeak p = find_peak(s, 1003.0);  // 0.3% off: inside the 1% search range
  ASSERT_TRUE(p.searched);
  EXPECT_TRUE(p.local_maximum);
  EXPECT_NEAR(p.frequency_hz, 1000.0, 0.1);
  // Theory: Hann-windowed white noise of variance s^2 gives complex bins of variance
  // 6 s^2 / N after the amplitude scaling 4/N; their magnitude is Rayleigh with median
  // sqrt(6 ln2 / N) s = 0.01593. The tone reads 1 (plus noise): SNR = 35.96 dB.
  const double median = std::sqrt(6.0 * std::log(2.0) / n);
  EXPECT_NEAR(p.noise_floor, median, 0.15 * median);  // median of 54 bins: ~10% scatter
  EXPECT_NEAR(p.snr_db, 20.0 * std::log10(1.0 / median), 1.5);
  // Between bins the Gaussian interpolation finds the frequency to a tenth of a bin.
  const SpectralPeak q = find_peak(amplitude_spectrum(tone(n, fs, 2000.37, 1.0), fs), 2000.0);
  EXPECT_NEAR(q.frequency_hz, 2000.37, 0.1);
  // Outside the spectrum nothing is searched.
  EXPECT_FALSE(find_peak(s, 9000.0).searched);
}

// A line within the +-1 % window whose largest bin lies just outside it (1 Hz bins; expected
// 1000.7 Hz: window 990.69-1010.71 Hz, bins 991-1010): a tone at 1010.6 Hz has its largest
// bin at 1011, and bin 1010 inside is its flank. The line's interpolated frequency lies in the
// window, so it is the line found (a local maximum, at 1010.6 Hz); a tone at 1011.0 Hz, out of
// the window, is still not found (the search sees its flank at bin 1010).
TEST(Spectrum, PeakOfALineJustInsideTheWindowWithItsLargestBinOutside) {
  const double fs = 4096.0;
  const std::size_t n = 4096;  // 1 Hz bins
  const SpectralPeak in = find_peak(amplitude_spectrum(tone(n, fs, 1010.6, 1.0), fs), 1000.7);
  ASSERT_TRUE(in.searched);
  EXPECT_TRUE(in.local_maximum);
  EXPECT_NEAR(in.frequency_hz, 1010.6, 0.1);
  EXPECT_NEAR(in.amplitude, 0.90, 0.02);  // Hann, 0.4 bin off the line: sinc(0.4) / (1 - 0.4^2)
  const SpectralPeak out = find_peak(amplitude_spectrum(tone(n, fs, 1011.0, 1.0), fs), 1000.7);
  ASSERT_TRUE(out.searched);
  EXPECT_FALSE(out.local_maximum);
  EXPECT_LE(out.frequency_hz, 1010.5 + 1e-9);  // a flank bin, at most half a bin from 1010
}

}  // namespace
}  // namespace bearing_sim
