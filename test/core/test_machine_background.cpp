// The machine around the bearing in the virtual accelerometer (docs/sensor.md,
// "Installation" and "Transmission path"): each effect read off the sensor's output and
// compared with the configured value or a closed form written here.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "test_support.hpp"

// Every allocation of this test program is counted (PushAllocatesNothing). The replaced
// new and delete are a matched pair (malloc / free), which GCC cannot see once inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
std::atomic<long> g_allocations{0};
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace bearing_sim {
namespace {

using test::kPi;
constexpr double kG = 9.80665;
constexpr double kMg = 1e-3 * kG;

// A clean 12 kHz chain: no sensor noise, no path, 24 bits; the anti-alias cut-off at
// 0.46 f_out leaves |H_aa| within 1e-6 of 1 below 1.2 kHz.
AccelerometerConfig clean_config(double rate_hz = 12000.0) {
  AccelerometerConfig c;
  c.output_rate_hz = rate_hz;
  c.path_resonance_hz = 0.0;
  c.noise_density_m_s2_per_sqrt_hz = 0.0;
  c.anti_alias_cutoff_fraction = 0.46;
  return c;
}

// The output with the ring turning at f_r (the angle wrapped as the dynamics wrap it) and
// the bearing's acceleration on the axis bearing(t); the first `settle_s` dropped.
std::vector<double> run(const AccelerometerConfig& config, double f_r, double seconds, double settle_s = 0.5,
                        double (*bearing)(double) = nullptr) {
  VirtualAccelerometer sensor(config, config.output_rate_hz);
  const double fs = config.output_rate_hz;
  const std::size_t n = static_cast<std::size_t>(std::lround((seconds + settle_s) * fs));
  const std::size_t skip = static_cast<std::size_t>(std::lround(settle_s * fs));
  std::vector<double> out;
  double y = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = i / fs;
    const double angle = std::remainder(2.0 * kPi * f_r * t, 2.0 * kPi);
    if (sensor.push_axis_acceleration(bearing ? bearing(t) : 0.0, angle, &y) && i >= skip) out.push_back(y);
  }
  return out;
}

// Peak amplitude of the line at f (a whole number of periods in the record: no leakage).
double line(const std::vector<double>& x, double fs, double f) { return test::dft_amplitude(x, fs, f); }

// --- speed-locked and time-locked lines ----------------------------------------------------

TEST(MachineBackground, ShaftLinesFollowTheRingAtTheirAmplitude) {
  // Shaft harmonics 2 and 4, half order 1.5, another component's order 5.4; the record (2 s)
  // holds whole periods of every line at both speeds, so the DFT reads amplitudes exactly;
  // 24-bit quantization (6e-5 m/s^2 steps) and |H_aa| move them by < 1e-4.
  AccelerometerConfig c = clean_config();
  c.installation.shaft_harmonics_m_s2 = {0.0, 2.0 * kMg, 0.0, 5.0 * kMg};
  c.installation.half_orders_m_s2 = {0.0, 0.7 * kMg};
  c.installation.speed_locked_orders = {{5.4, 3.0 * kMg}};
  const double fs = c.output_rate_hz;
  for (double f_r : {25.0, 30.0}) {
    const std::vector<double> out = run(c, f_r, 2.0);
    EXPECT_NEAR(line(out, fs, 2.0 * f_r) / (2.0 * kMg), 1.0, 1e-3) << f_r;
    EXPECT_NEAR(line(out, fs, 4.0 * f_r) / (5.0 * kMg), 1.0, 1e-3) << f_r;
    EXPECT_NEAR(line(out, fs, 1.5 * f_r) / (0.7 * kMg), 1.0, 1e-3) << f_r;
    EXPECT_NEAR(line(out, fs, 5.4 * f_r) / (3.0 * kMg), 1.0, 1e-3) << f_r;
    // Nothing where nothing is configured: 1 x, 3 x and 0.5 x f_r.
    EXPECT_LT(line(out, fs, f_r), 1e-3 * kMg);
    EXPECT_LT(line(out, fs, 3.0 * f_r), 1e-3 * kMg);
    EXPECT_LT(line(out, fs, 0.5 * f_r), 1e-3 * kMg);
    // The strongest line is at 4 f_r (searched on the record's 0.5 Hz grid, 20-400 Hz).
    EXPECT_NEAR(test::spectral_peak_hz(out, fs, 20.0, 400.0, 0.5), 4.0 * f_r, 0.01) << f_r;
  }
}

TEST(MachineBackground, ShaftLinesAreLockedToTheRingAngle) {
  // A harmonic k is A cos(k theta + phase), another component's order q likewise: on a
  // run-up, a Hann-weighted least-squares fit of cos / sin (k theta) finds amplitude A in
  // every 0.2 s window, whatever the speed (a line at a fixed frequency would not).
  // Tolerance 1 %: the anti-alias filter's delay (~0.2 ms) turns the phase by < 0.1 rad
  // within a window; its gain below 500 Hz is 1 - 1e-9; the other line, >= 48 Hz (9.6 Hann
  // bins) away, leaks < 0.1 % into the fit.
  AccelerometerConfig c = clean_config();
  c.installation.shaft_harmonics_m_s2 = {0.0, 0.0, 4.0 * kMg};
  c.installation.speed_locked_orders = {{5.4, 3.0 * kMg}};
  const double fs = c.output_rate_hz;
  VirtualAccelerometer sensor(c, fs);
  double angle = 0.0, y = 0.0;
  std::vector<double> out, theta;
  for (int i = 0; i < static_cast<int>(3.0 * fs); ++i) {
    const double f_r = 20.0 + 10.0 * i / fs;  // 20 -> 50 Hz in 3 s
    angle += 2.0 * kPi * f_r / fs;
    sensor.push_axis_acceleration(0.0, std::remainder(angle, 2.0 * kPi), &y);
    out.push_back(y);
    theta.push_back(angle);
  }
  const int window = static_cast<int>(0.2 * fs);
  for (const auto& [order, amplitude] : {std::pair<double, double>{3.0, 4.0 * kMg}, {5.4, 3.0 * kMg}}) {
    for (int start = static_cast<int>(0.2 * fs); start + window <= static_cast<int>(out.size()); start += window) {
      double cc = 0.0, ss = 0.0, cs = 0.0, yc = 0.0, ys = 0.0;
      for (int i = start; i < start + window; ++i) {
        const double w = std::pow(std::sin(kPi * (i - start) / window), 2);
        const double co = std::cos(order * theta[i]), si = std::sin(order * theta[i]);
        cc += w * co * co, ss += w * si * si, cs += w * co * si, yc += w * out[i] * co, ys += w * out[i] * si;
      }
      // Weighted least squares y ~ a cos + b sin.
      const double det = cc * ss - cs * cs, a = (yc * ss - ys * cs) / det, b = (ys * cc - yc * cs) / det;
      EXPECT_NEAR(std::hypot(a, b) / amplitude, 1.0, 0.01) << "order " << order << ", window at " << start / fs << " s";
    }
  }
}

TEST(MachineBackground, LineFamilyIsAtItsFrequenciesWhateverTheSpeed) {
  // 60 Hz mains, 2x, 4x, 6x: the same lines with the ring at 25 or 30 Hz or standing still.
  AccelerometerConfig c = clean_config();
  c.installation.line_frequency_hz = 60.0;
  c.installation.line_harmonics_m_s2 = {0.0, 2.5 * kMg, 0.0, 3.0 * kMg, 0.0, 15.0 * kMg};
  const double fs = c.output_rate_hz;
  for (double f_r : {0.0, 25.0, 30.0}) {
    const std::vector<double> out = run(c, f_r, 2.0);
    EXPECT_NEAR(line(out, fs, 120.0) / (2.5 * kMg), 1.0, 1e-3) << f_r;
    EXPECT_NEAR(line(out, fs, 240.0) / (3.0 * kMg), 1.0, 1e-3) << f_r;
    EXPECT_NEAR(line(out, fs, 360.0) / (15.0 * kMg), 1.0, 1e-3) << f_r;
    EXPECT_LT(line(out, fs, 60.0), 1e-3 * kMg) << f_r;
    EXPECT_NEAR(test::spectral_peak_hz(out, fs, 20.0, 1000.0, 0.5), 360.0, 0.01) << f_r;
  }
}

TEST(MachineBackground, LinesAboveTheInputNyquistAreLeftOut) {
  // At 2 kHz in and out, order 40 of 30 Hz (1.2 kHz) and the 20th harmonic of 60 Hz cannot be
  // sampled: left out, so nothing aliases to 800 Hz; the 3rd harmonic of 60 Hz stays.
  AccelerometerConfig c = clean_config(2000.0);
  c.installation.speed_locked_orders = {{40.0, 10.0 * kMg}};
  c.installation.line_frequency_hz = 60.0;
  std::vector<double> lines(20, 0.0);
  lines[2] = lines[19] = 10.0 * kMg;
  c.installation.line_harmonics_m_s2 = lines;
  const std::vector<double> out = run(c, 30.0, 2.0);
  EXPECT_LT(line(out, 2000.0, 800.0), 1e-3 * kMg);
  EXPECT_NEAR(line(out, 2000.0, 180.0) / (10.0 * kMg), 1.0, 1e-3);
}

// --- shaft-rate modulation of the bearing's signal ------------------------------------------

double carrier_1kHz(double t) { return 1.0 * std::sin(2.0 * kPi * 1000.0 * t); }

TEST(MachineBackground, ShaftRateModulationGivesSidebandsOfHalfTheDepth) {
  // x (1 + m cos(theta + phase)) of a 1 kHz tone: sidebands at 1000 +- f_r, each m / 2 of the
  // carrier (trigonometry); carrier unchanged. |H_aa| at 975..1025 Hz is 1 within 1e-9.
  AccelerometerConfig c = clean_config();
  c.installation.shaft_modulation_depth = 0.3;
  c.installation.shaft_modulation_phase_rad = 0.7;
  const double fs = c.output_rate_hz, f_r = 25.0;
  const std::vector<double> out = run(c, f_r, 2.0, 0.5, carrier_1kHz);
  const double carrier = line(out, fs, 1000.0);
  EXPECT_NEAR(carrier, 1.0, 1e-3);
  EXPECT_NEAR(line(out, fs, 1000.0 - f_r) / carrier, 0.15, 1e-3);
  EXPECT_NEAR(line(out, fs, 1000.0 + f_r) / carrier, 0.15, 1e-3);
  EXPECT_LT(line(out, fs, 1000.0 + 2.0 * f_r) / carrier, 1e-4);
  // The modulation is the bearing's: no lines of its own without a bearing signal.
  const std::vector<double> quiet = run(c, f_r, 2.0);
  EXPECT_LT(line(quiet, fs, f_r), 1e-6);
}

TEST(MachineBackground, ShaftRateModulationPastOneStopsTheSignalForPartOfTheTurn) {
  // m = 2: the gain max(0, 1 + m cos u) is zero where cos u < -1/m, a third of the turn. Its
  // Fourier series (u0 = arccos(-1/m), integrals of (1 + m cos u) cos(k u) over |u| < u0):
  // a0 = (u0 + m sin u0) / pi, a1 = (2 / pi) (sin u0 + m (u0 / 2 + sin(2 u0) / 4)),
  // a2 = (2 / pi) (sin(2 u0) / 2 + m (sin u0 / 2 + sin(3 u0) / 6)). On a 1 kHz tone: the carrier
  // a0, sidebands at +- f_r of a1 / 2, at +- 2 f_r of a2 / 2. Tolerance as above.
  AccelerometerConfig c = clean_config();
  const double m = 2.0;
  c.installation.shaft_modulation_depth = m;
  c.installation.shaft_modulation_phase_rad = 0.7;
  const double fs = c.output_rate_hz, f_r = 25.0;
  const std::vector<double> out = run(c, f_r, 2.0, 0.5, carrier_1kHz);
  const double u0 = std::acos(-1.0 / m);
  const double a0 = (u0 + m * std::sin(u0)) / kPi;
  const double a1 = 2.0 / kPi * (std::sin(u0) + m * (0.5 * u0 + 0.25 * std::sin(2.0 * u0)));
  const double a2 = 2.0 / kPi * (0.5 * std::sin(2.0 * u0) + m * (0.5 * std::sin(u0) + std::sin(3.0 * u0) / 6.0));
  EXPECT_NEAR(line(out, fs, 1000.0), a0, 1e-3);
  EXPECT_NEAR(line(out, fs, 1000.0 - f_r), 0.5 * a1, 1e-3);
  EXPECT_NEAR(line(out, fs, 1000.0 + f_r), 0.5 * a1, 1e-3);
  EXPECT_NEAR(line(out, fs, 1000.0 + 2.0 * f_r), 0.5 * std::abs(a2), 1e-3);
}

TEST(MachineBackground, RollingNoiseDoesNotFollowTheShaftRateModulation) {
  // Rolling noise alone under m = 0.9: were it modulated, its power would go as
  // (1 + m cos u)^2, whose f_r component over its mean is 2 m / (1 + m^2 / 2) = 1.28. It is
  // not: 20 s of 12 kHz give ~240,000 nearly independent squares (chi^2, variance 2 mean^2),
  // so the component's noise is ~2 sqrt(2 / 240000) = 0.006; bound 0.05.
  AccelerometerConfig c = clean_config();
  c.installation.shaft_modulation_depth = 0.9;
  c.installation.rolling_noise_m_s2_per_sqrt_hz = 200e-6 * kG;
  const double fs = c.output_rate_hz, f_r = 25.0;
  const std::vector<double> out = run(c, f_r, 20.0);
  std::complex<double> at_f_r = 0.0;
  double mean = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double power = out[i] * out[i];
    mean += power;
    at_f_r += power * std::polar(1.0, -2.0 * kPi * f_r * static_cast<double>(i) / fs);
  }
  ASSERT_GT(mean, 0.0);
  EXPECT_LT(2.0 * std::abs(at_f_r) / mean, 0.05);
}

// --- coloured floor -------------------------------------------------------------------------

// log-log interpolation between (f, D) points, held outside: written here from its definition.
double loglog(double f, const std::vector<double>& fp, const std::vector<double>& dp) {
  if (f <= fp.front()) return dp.front();
  if (f >= fp.back()) return dp.back();
  std::size_t i = 1;
  while (fp[i] < f) ++i;
  const double slope = std::log(dp[i] / dp[i - 1]) / std::log(fp[i] / fp[i - 1]);
  return dp[i - 1] * std::pow(f / fp[i - 1], slope);
}

TEST(MachineBackground, FloorDensityFollowsItsPoints) {
  // Density points 100 ug/sqrt(Hz) at 100 Hz, 400 at 1 kHz, 200 at 4 kHz; 40 s at 12 kHz.
  // Expected band power: the mean over the Welch bins of D(f)^2 |H_aa(f)|^2 (Butterworth
  // closed form). Statistics: 467 Hann segments of 2048 (about 440 independent), bins 5.9 Hz
  // apart and about 1.5 bins correlated: 300-500 Hz holds ~23 independent bins, so the band
  // mean's relative standard deviation is 1 / sqrt(440 x 23) = 1.0 %, 0.45 % in 2-3 kHz.
  // Tolerance 5 %: 4-5 standard deviations plus ~1 % for the FIR's 10 Hz design grid.
  AccelerometerConfig c = clean_config();
  const std::vector<double> fp = {100.0, 1000.0, 4000.0}, dp = {100.0, 400.0, 200.0};
  c.installation.floor_frequencies_hz = fp;
  for (double d : dp) c.installation.floor_density_m_s2_per_sqrt_hz.push_back(d * 1e-6 * kG);
  const double fs = c.output_rate_hz, fc = 0.46 * fs;
  const std::vector<double> out = run(c, 0.0, 40.0, 0.0);
  const int n = 2048;
  const std::vector<double> psd = test::welch_psd(out, fs, n);
  for (const auto& band : {std::pair<double, double>{300.0, 500.0}, {2000.0, 3000.0}, {5000.0, 5400.0}}) {
    double measured = 0.0, expected = 0.0;
    int bins = 0;
    for (int k = 0; k <= n / 2; ++k) {
      const double f = k * fs / n;
      if (f < band.first || f > band.second) continue;
      const double r = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
      const double d = loglog(f, fp, dp) * 1e-6 * kG;
      expected += d * d / (1.0 + std::pow(r, 16));
      measured += psd[k];
      ++bins;
    }
    EXPECT_NEAR(measured / expected, 1.0, 0.05) << band.first << "-" << band.second << " Hz, " << bins << " bins";
    std::printf("floor %4.0f-%4.0f Hz: configured %.1f ug/sqrt(Hz), measured %.1f\n", band.first, band.second,
                std::sqrt(expected / bins) / (1e-6 * kG), std::sqrt(measured / bins) / (1e-6 * kG));
  }
}

// --- the transmission path of several modes -------------------------------------------------

// H(f) = 1 + sum_r p_r (T_r(f) - 1), T_r the complex seismic transmissibility
// (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2), written here from the textbook form.
std::complex<double> modal_h(double f, const std::vector<PathMode>& modes) {
  std::complex<double> h = 1.0;
  for (const PathMode& m : modes) {
    const std::complex<double> s(0.0, 2.0 * kPi * f);
    const double w = 2.0 * kPi * m.frequency_hz, z = m.damping_ratio;
    h += m.participation * ((2.0 * z * w * s + w * w) / (s * s + 2.0 * z * w * s + w * w) - 1.0);
  }
  return h;
}

double gain_through(const AccelerometerConfig& c, double f) {
  VirtualAccelerometer sensor(c, c.output_rate_hz);
  const double fs = c.output_rate_hz;
  std::vector<double> out;
  double y = 0.0;
  // 0.15 s to settle (the slowest mode decays by e^-28), then 0.25 s read.
  for (int i = 0; i < static_cast<int>(0.4 * fs); ++i)
    if (sensor.push_axis_acceleration(std::sin(2.0 * kPi * f * i / fs), &y) && i >= static_cast<int>(0.15 * fs))
      out.push_back(y);
  return test::dft_amplitude(out, fs, f);
}

TEST(MachineBackground, PathModesPeakAtTheClosedForm) {
  // Two modes at 48 kHz in (fn / f_in <= 0.07: the digital modes within 0.01 % of the analog
  // near fn, docs/sensor.md); the anti-alias filter (0.46 x 48 kHz) is flat to 1e-9 here.
  // Gains at fn: the closed form within 0.5 % (the DFT of a 0.25 s read: whole periods of
  // every multiple of 4 Hz). Peak frequencies: the maximum of the measured gain on a 4 Hz
  // grid at the closed form's maximum on that grid, within 1 % of fn.
  AccelerometerConfig c = clean_config(48000.0);
  c.path_modes = {{1100.0, 0.03, 0.3}, {3300.0, 0.02, 0.5}};
  for (const PathMode& m : c.path_modes) {
    const double expected = std::abs(modal_h(m.frequency_hz, c.path_modes));
    EXPECT_NEAR(gain_through(c, m.frequency_hz) / expected, 1.0, 0.005) << m.frequency_hz;
    double best_f = 0.0, best = 0.0, analog_f = 0.0, analog = 0.0;
    for (double f = 4.0 * std::round(0.97 * m.frequency_hz / 4.0); f <= 1.03 * m.frequency_hz; f += 4.0) {
      const double g = gain_through(c, f), a = std::abs(modal_h(f, c.path_modes));
      if (g > best) best = g, best_f = f;
      if (a > analog) analog = a, analog_f = f;
    }
    EXPECT_NEAR(best_f, analog_f, 4.0) << m.frequency_hz;
    EXPECT_NEAR(best_f / m.frequency_hz, 1.0, 0.01);
    // ~ p / (2 zeta) + the rest of the path, a rough check of the model's scale.
    EXPECT_GT(best, 0.8 * m.participation / (2.0 * m.damping_ratio));
    std::printf("mode %.0f Hz: |H(fn)| closed form %.3f, measured %.3f; peak at %.0f Hz (closed form %.0f)\n",
                m.frequency_hz, expected, gain_through(c, m.frequency_hz), best_f, analog_f);
  }
  // Unity at low frequency: the structure moves with the ring.
  EXPECT_NEAR(gain_through(c, 48.0), std::abs(modal_h(48.0, c.path_modes)), 1e-3);
  EXPECT_NEAR(gain_through(c, 48.0), 1.0, 0.01);
}

TEST(MachineBackground, ParticipationsAddingUpToMoreThanOneFollowTheClosedForm) {
  // A truncated list carrying more than the whole path at the sensor (the CWRU rig's: about 6):
  // the residual 1 - sum p_r is negative. Gains at fn, at 48 Hz (unity: the structure moves
  // with the ring) and at 12 kHz (above the modes: |1 - sum p_r| and the modes' tails) against
  // the closed form, within 0.5 %.
  AccelerometerConfig c = clean_config(48000.0);
  c.path_modes = {{2900.0, 0.024, 1.6}, {3400.0, 0.048, 3.7}};
  for (double f : {48.0, 2900.0, 3400.0, 12000.0})
    EXPECT_NEAR(gain_through(c, f) / std::abs(modal_h(f, c.path_modes)), 1.0, 0.005) << f;
  EXPECT_NEAR(gain_through(c, 48.0), 1.0, 0.01);
  EXPECT_GT(gain_through(c, 3400.0), 30.0);
}

TEST(MachineBackground, MountedResonanceIsInSeriesWithThePath) {
  // The sensor on a magnetic base: its mounted resonance multiplies the structure's path,
  // H(f) = H_path(f) x T_m(f), T_m the seismic transmissibility of the mount (written here from
  // the textbook form, as modal_h; a mode of participation 1 is the mount alone). 48 kHz in:
  // every section within 0.01 % of the analog near its fn (docs/sensor.md), the DFT read
  // within 0.1 %: 0.5 %. At the mount's fn alone |T_m| = sqrt(1 + 4 zeta^2) / (2 zeta) =
  // 10.44 for zeta = 0.048; unity at 48 Hz; above fn the mount isolates (|T_m| < 1 at 6 kHz).
  AccelerometerConfig c = clean_config(48000.0);
  c.path_modes = {{1100.0, 0.03, 0.3}, {2900.0, 0.024, 0.6}};
  c.mount_resonance_hz = 3400.0;
  c.mount_damping_ratio = 0.048;
  const std::vector<PathMode> mount = {{3400.0, 0.048, 1.0}};
  for (double f : {48.0, 1100.0, 2900.0, 3400.0, 6000.0}) {
    const double expected = std::abs(modal_h(f, c.path_modes)) * std::abs(modal_h(f, mount));
    EXPECT_NEAR(gain_through(c, f) / expected, 1.0, 0.005) << f;
    EXPECT_NEAR(std::abs(VirtualAccelerometer(c, 48000.0).path_response(f)) / expected, 1.0, 0.005) << f;
  }
  EXPECT_NEAR(gain_through(c, 48.0), 1.0, 0.01);
  AccelerometerConfig alone = clean_config(48000.0);
  alone.mount_resonance_hz = 3400.0;
  alone.mount_damping_ratio = 0.048;
  EXPECT_NEAR(gain_through(alone, 3400.0), std::sqrt(1.0 + 4.0 * 0.048 * 0.048) / (2.0 * 0.048), 0.05);
  EXPECT_LT(gain_through(alone, 6000.0), 1.0);
  // Its peak stands higher than the path's dominant mode's (1 / 0.048 > 0.4 / 0.024): the
  // path as one resonance (an envelope band) is the mount.
  const AccelerometerConfig parsed = accelerometer_config_from_string(
      "sensor:\n"
      "  path_modes: [{frequency_Hz: 2900, damping_ratio: 0.024, participation: 0.4}]\n"
      "  mount_resonance_Hz: 3400\n"
      "  mount_damping_ratio: 0.048\n",
      "inline");
  EXPECT_EQ(parsed.mount_resonance_hz, 3400.0);
  EXPECT_EQ(parsed.mount_damping_ratio, 0.048);
  EXPECT_EQ(parsed.path_resonance_hz, 3400.0);
  // At or above 0.45 x the input rate it is refused, naming the key.
  alone.mount_resonance_hz = 5500.0;
  alone.output_rate_hz = 12000.0;
  try {
    VirtualAccelerometer sensor(alone, 12000.0);
    ADD_FAILURE() << "a mounted resonance above 0.45 f_in was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("mount_resonance_Hz"), std::string::npos) << e.what();
  }
}

TEST(MachineBackground, RollingNoiseTakesThePathAndTheMount) {
  // White acceleration of density D at the ring, through a path of two modes and the mount:
  // at the output its density is D |H_path(f)| |T_m(f)| |H_aa(f)| (a linear filter of white
  // noise), written out from the closed forms. 48 kHz in (each section within 0.01 % of the
  // analog near its fn), 12 kHz out, 40 s. Statistics as FloorDensityFollowsItsPoints: 467
  // Hann segments of 2048, bands of 34-68 bins: the band mean's standard deviation about
  // 1 %; tolerance 5 %.
  AccelerometerConfig c = clean_config();
  c.path_modes = {{1100.0, 0.03, 0.3}, {2900.0, 0.024, 0.6}};
  c.mount_resonance_hz = 3400.0;
  c.mount_damping_ratio = 0.048;
  const double d = 200e-6 * kG;
  c.installation.rolling_noise_m_s2_per_sqrt_hz = d;
  const double f_in = 48000.0, fs = c.output_rate_hz, fc = 0.46 * fs;
  VirtualAccelerometer sensor(c, f_in);
  EXPECT_NEAR(sensor.rolling_noise_sigma_m_s2(), d * std::sqrt(0.5 * f_in), 1e-12);
  std::vector<double> out;
  double y = 0.0;
  for (long i = 0; i < static_cast<long>(40.5 * f_in); ++i)
    if (sensor.push_axis_acceleration(0.0, 0.0, &y) && i >= static_cast<long>(0.5 * f_in)) out.push_back(y);
  const int n = 2048;
  const std::vector<double> psd = test::welch_psd(out, fs, n);
  const std::vector<PathMode> mount = {{3400.0, 0.048, 1.0}};
  for (const auto& band : {std::pair<double, double>{300.0, 700.0}, {2700.0, 3100.0}, {3300.0, 3500.0}}) {
    double measured = 0.0, expected = 0.0;
    for (int k = 0; k <= n / 2; ++k) {
      const double f = k * fs / n;
      if (f < band.first || f > band.second) continue;
      const double r = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
      const double h = std::abs(modal_h(f, c.path_modes)) * std::abs(modal_h(f, mount));
      expected += d * d * h * h / (1.0 + std::pow(r, 16));
      measured += psd[k];
    }
    EXPECT_NEAR(measured / expected, 1.0, 0.05) << band.first << "-" << band.second << " Hz";
    std::printf("rolling noise %4.0f-%4.0f Hz: density measured / closed form %.4f\n", band.first, band.second,
                measured / expected);
  }
  // The other sequences stay as they were (the rolling noise draws from a stream of its own):
  // a rolling noise far below one ADC step moves a sample by at most one step, and only where
  // the sample lay within 1e-10 g of a rounding edge (a chance of ~1e-5 per sample).
  AccelerometerConfig with_floor = clean_config();
  with_floor.noise_density_m_s2_per_sqrt_hz = 5e-6 * kG;
  with_floor.installation.floor_frequencies_hz = {100.0};
  with_floor.installation.floor_density_m_s2_per_sqrt_hz = {100e-6 * kG};
  AccelerometerConfig with_rolling = with_floor;
  with_rolling.installation.rolling_noise_m_s2_per_sqrt_hz = 1e-12 * kG;  // far below one ADC step
  const std::vector<double> a = run(with_floor, 30.0, 0.2, 0.0), b = run(with_rolling, 30.0, 0.2, 0.0);
  ASSERT_EQ(a.size(), b.size());
  const double step = VirtualAccelerometer(with_floor, 12000.0).quantization_step_m_s2();
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_LE(std::abs(a[i] - b[i]), 1.01 * step) << i;
    same += a[i] == b[i];
  }
  EXPECT_GE(same, a.size() - 2);
}

// --- the one-resonance case, as before ------------------------------------------------------

TEST(MachineBackground, OneResonanceIsTheChainAsBefore) {
  // The pre-installation chain written out here (seismic biquad, Box-Muller noise on
  // mt19937_64 seeded with the seed, Butterworth sections, decimation, ADC): the legacy keys
  // and one mode with participation 1 give it bit for bit.
  AccelerometerConfig legacy;
  legacy.output_rate_hz = 10000.0;
  legacy.seed = 7;
  const double fs = 20000.0;
  AccelerometerConfig one_mode = legacy;
  one_mode.path_modes = {{legacy.path_resonance_hz, legacy.path_damping_ratio, 1.0}};

  Biquad path = design_seismic_path(legacy.path_resonance_hz, legacy.path_damping_ratio, fs);
  std::vector<Biquad> aa = design_butterworth_lowpass(8, 0.4 * legacy.output_rate_hz, fs);
  std::mt19937_64 rng(7);
  bool spare_ready = false;
  double spare = 0.0;
  auto gaussian = [&]() {
    if (spare_ready) {
      spare_ready = false;
      return spare;
    }
    const double u1 = (static_cast<double>(rng() >> 11) + 1.0) * 0x1.0p-53;
    const double u2 = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    const double radius = std::sqrt(-2.0 * std::log(u1)), angle = 2.0 * kPi * u2;
    spare = radius * std::sin(angle);
    spare_ready = true;
    return radius * std::cos(angle);
  };
  const double sigma = legacy.noise_density_m_s2_per_sqrt_hz * std::sqrt(0.5 * fs);
  const double q = 2.0 * legacy.range_m_s2 / std::ldexp(1.0, legacy.adc_bits);

  VirtualAccelerometer a(legacy, fs), b(one_mode, fs);
  int outputs = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = 3.0 * std::sin(0.37 * i) + (i % 997 == 0 ? 50.0 : 0.0);
    double y = path.process(x) + sigma * gaussian();
    for (Biquad& s : aa) y = s.process(y);
    double ya = 0.0, yb = 0.0;
    const bool due_a = a.push_axis_acceleration(x, 0.3, &ya), due_b = b.push_axis_acceleration(x, &yb);
    ASSERT_EQ(due_a, i % 2 == 1);
    ASSERT_EQ(due_b, due_a);
    if (!due_a) continue;
    ++outputs;
    const double expected = std::floor(y / q + 0.5) * q;
    ASSERT_EQ(ya, expected) << "sample " << i;
    ASSERT_EQ(yb, expected) << "sample " << i;
  }
  EXPECT_EQ(outputs, 10000);
}

TEST(MachineBackground, SameSeedSameMachineOtherSeedOtherPhases) {
  AccelerometerConfig c = clean_config();
  c.installation.shaft_harmonics_m_s2 = {1.0 * kMg, 2.0 * kMg};
  c.installation.speed_locked_orders = {{3.3, 1.0 * kMg}};
  c.installation.line_harmonics_m_s2 = {0.0, 3.0 * kMg};
  c.installation.floor_frequencies_hz = {100.0};
  c.installation.floor_density_m_s2_per_sqrt_hz = {1e-6 * kG};
  const std::vector<double> a = run(c, 25.0, 2.0), b = run(c, 25.0, 2.0);
  EXPECT_EQ(a, b);
  c.seed = 2;
  const std::vector<double> other = run(c, 25.0, 2.0);
  double difference = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) difference = std::max(difference, std::abs(a[i] - other[i]));
  EXPECT_GT(difference, 1.0 * kMg);
  // The phases differ, the amplitudes do not: the floor in the DFT's 0.5 Hz bin, 1 ug/sqrt(Hz)
  // x sqrt(0.5 Hz) ~ 7e-6 m/s^2 rms, moves a 2 mg line by ~0.05 %; 0.5 % allowed.
  EXPECT_NEAR(line(other, 12000.0, 50.0) / line(a, 12000.0, 50.0), 1.0, 0.005);
  EXPECT_NEAR(line(other, 12000.0, 100.0) / line(a, 12000.0, 100.0), 1.0, 0.005);
  // reset() gives the run again.
  VirtualAccelerometer sensor(c, 12000.0);
  std::vector<double> first, second;
  double y = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < 1000; ++i) {
      sensor.push_axis_acceleration(0.0, std::remainder(0.01 * i, 2.0 * kPi), &y);
      (pass == 0 ? first : second).push_back(y);
    }
    sensor.reset();
  }
  EXPECT_EQ(first, second);
}

TEST(MachineBackground, PushAllocatesNothing) {
  // The CWRU file's whole installation, on a run-up (the rotations recomputed) for 1 s.
  const AccelerometerConfig c =
      load_accelerometer_config(test::config_path("sensors/cwru_drive_end_accelerometer.yaml"));
  VirtualAccelerometer sensor(c, 12000.0);
  Vector5 a = Vector5::Zero();
  double y = 0.0, angle = 0.0;
  const long before = g_allocations.load();
  for (int i = 0; i < 12000; ++i) {
    angle += 2.0 * kPi * (29.0 + i / 12000.0) / 12000.0;
    a(0) = std::sin(0.3 * i);
    sensor.push(a, std::remainder(angle, 2.0 * kPi), &y);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

// --- files and keys -------------------------------------------------------------------------

TEST(MachineBackground, ParsesTheInstallationAndPathModes) {
  const AccelerometerConfig c = accelerometer_config_from_string(
      "sensor:\n"
      "  path_modes:\n"
      "    - {frequency_Hz: 1100, damping_ratio: 0.03, participation: 0.2}\n"
      "    - {frequency_Hz: 2900, damping_ratio: 0.02, participation: 0.6}\n"
      "  installation:\n"
      "    shaft_harmonics_mg: [1, 2.5]\n"
      "    half_orders_mg: [0.1]\n"
      "    speed_locked_orders: [{order: 5.4, amplitude_mg: 10}]\n"
      "    line_frequency_Hz: 60\n"
      "    line_harmonics_mg: [0, 3]\n"
      "    shaft_modulation_depth: 0.1\n"
      "    shaft_modulation_phase_deg: 90\n"
      "    floor: {frequencies_Hz: [100, 1000], density_ug_per_sqrt_Hz: [150, 300]}\n"
      "    rolling_noise_ug_per_sqrt_Hz: 250\n",
      "inline");
  ASSERT_EQ(c.path_modes.size(), 2u);
  EXPECT_EQ(c.path_modes[1].frequency_hz, 2900.0);
  // The dominant mode (p / zeta 30 against 6.7) stands for the path as one resonance.
  EXPECT_EQ(c.path_resonance_hz, 2900.0);
  EXPECT_EQ(c.path_damping_ratio, 0.02);
  EXPECT_NEAR(c.installation.shaft_harmonics_m_s2[1], 2.5e-3 * kG, 1e-15);
  EXPECT_NEAR(c.installation.speed_locked_orders[0].amplitude_m_s2, 10e-3 * kG, 1e-15);
  EXPECT_NEAR(c.installation.shaft_modulation_phase_rad, kPi / 2.0, 1e-15);
  EXPECT_NEAR(c.installation.floor_density_m_s2_per_sqrt_hz[1], 300e-6 * kG, 1e-15);
  EXPECT_NEAR(c.installation.rolling_noise_m_s2_per_sqrt_hz, 250e-6 * kG, 1e-15);
  EXPECT_NO_THROW(VirtualAccelerometer(c, 10000.0));

  // The shipped files: the CT sensor has no installation; the CWRU one loads at 12 kHz.
  const AccelerometerConfig ct =
      load_accelerometer_config(test::config_path("sensors/ct_gantry_housing_accelerometer.yaml"));
  EXPECT_TRUE(ct.installation.empty());
  EXPECT_TRUE(ct.path_modes.empty());
  const AccelerometerConfig cwru =
      load_accelerometer_config(test::config_path("sensors/cwru_drive_end_accelerometer.yaml"));
  EXPECT_FALSE(cwru.installation.empty());
  EXPECT_GE(cwru.path_modes.size(), 4u);
  EXPECT_GT(cwru.mount_resonance_hz, 0.0);  // the magnetic base's
  EXPECT_EQ(cwru.output_rate_hz, 12000.0);
  EXPECT_NO_THROW(VirtualAccelerometer(cwru, 12000.0));
}

void expect_background_error(const std::string& body, const std::string& key) {
  test::expect_config_error([&] { accelerometer_config_from_string("sensor:\n" + body, "bad_sensor.yaml"); },
                            {"bad_sensor.yaml", "'" + key + "'"}, key);
}

TEST(MachineBackground, BadKeysAreRefusedNamingThem) {
  const std::string mode = "  path_modes:\n    - {frequency_Hz: 1000, damping_ratio: 0.03, participation: 0.5";
  expect_background_error(mode + ", q: 1}\n", "sensor.path_modes[0].q");
  expect_background_error("  path_modes:\n    - {frequency_Hz: 1000, damping_ratio: 0.03}\n",
                      "sensor.path_modes[0].participation");
  expect_background_error(mode + "}\n    - {frequency_Hz: 2000, damping_ratio: 0.03, participation: 9.6}\n",
                      "sensor.path_modes");  // participations add up to 10.1
  expect_background_error("  path_modes:\n    - {frequency_Hz: 1000, damping_ratio: 0, participation: 0.5}\n",
                      "sensor.path_modes[0].damping_ratio");
  expect_background_error("  path_modes:\n    - {frequency_Hz: .nan, damping_ratio: 0.03, participation: 0.5}\n",
                      "sensor.path_modes[0].frequency_Hz");
  expect_background_error("  path_modes:\n    - {frequency_Hz: 1000, damping_ratio: 0.03, participation: 10.5}\n",
                      "sensor.path_modes[0].participation");
  expect_background_error("  path_modes: 3\n", "sensor.path_modes");
  expect_background_error("  mount_resonance_Hz: -1\n", "sensor.mount_resonance_Hz");
  expect_background_error("  mount_damping_ratio: 0\n", "sensor.mount_damping_ratio");
  expect_background_error("  mount_resonance_Hz: .inf\n", "sensor.mount_resonance_Hz");
  expect_background_error("  path_resonance_Hz: 2000\n" + mode + "}\n", "sensor.path_modes");
  expect_background_error("  installation: [1]\n", "sensor.installation");
  expect_background_error("  installation: {shaft_harmonic_mg: [1]}\n", "sensor.installation.shaft_harmonic_mg");
  expect_background_error("  installation: {shaft_harmonics_mg: [1, -2]}\n", "sensor.installation.shaft_harmonics_mg[1]");
  expect_background_error("  installation: {shaft_harmonics_mg: [1, x]}\n", "sensor.installation.shaft_harmonics_mg[1]");
  expect_background_error("  installation: {shaft_harmonics_mg: 1}\n", "sensor.installation.shaft_harmonics_mg");
  expect_background_error("  installation: {half_orders_mg: [.inf]}\n", "sensor.installation.half_orders_mg[0]");
  expect_background_error("  installation: {line_harmonics_mg: [1e9]}\n", "sensor.installation.line_harmonics_mg[0]");
  expect_background_error("  installation: {line_frequency_Hz: 0}\n", "sensor.installation.line_frequency_Hz");
  expect_background_error("  installation: {line_frequency_Hz: sixty}\n", "sensor.installation.line_frequency_Hz");
  expect_background_error("  installation: {speed_locked_orders: [{order: -1, amplitude_mg: 1}]}\n",
                      "sensor.installation.speed_locked_orders[0].order");
  expect_background_error("  installation: {speed_locked_orders: [{order: 2}]}\n",
                      "sensor.installation.speed_locked_orders[0].amplitude_mg");
  expect_background_error("  installation: {speed_locked_orders: [{order: 2, amplitude_mg: 1, phase: 0}]}\n",
                      "sensor.installation.speed_locked_orders[0].phase");
  expect_background_error("  installation: {speed_locked_orders: [3]}\n", "sensor.installation.speed_locked_orders[0]");
  expect_background_error("  installation: {shaft_modulation_depth: 4.5}\n", "sensor.installation.shaft_modulation_depth");
  expect_background_error("  installation: {shaft_modulation_phase_deg: 400}\n",
                      "sensor.installation.shaft_modulation_phase_deg");
  expect_background_error("  installation: {floor: {frequencies_Hz: [100, 50], density_ug_per_sqrt_Hz: [1, 2]}}\n",
                      "sensor.installation.floor.frequencies_Hz[1]");
  expect_background_error("  installation: {floor: {frequencies_Hz: [100, 200], density_ug_per_sqrt_Hz: [1, 0]}}\n",
                      "sensor.installation.floor.density_ug_per_sqrt_Hz[1]");
  expect_background_error("  installation: {floor: {frequencies_Hz: [100, 200], density_ug_per_sqrt_Hz: [1]}}\n",
                      "sensor.installation.floor");
  expect_background_error("  installation: {floor: {frequencies_Hz: [100]}}\n",
                      "sensor.installation.floor.density_ug_per_sqrt_Hz");
  expect_background_error("  installation: {floor: {frequencies_Hz: [100], density_ug_per_sqrt_Hz: [1], slope: 2}}\n",
                      "sensor.installation.floor.slope");
  expect_background_error("  installation: {rolling_noise_ug_per_sqrt_Hz: -1}\n",
                          "sensor.installation.rolling_noise_ug_per_sqrt_Hz");
  expect_background_error("  installation: {rolling_noise_ug_per_sqrt_Hz: .nan}\n",
                          "sensor.installation.rolling_noise_ug_per_sqrt_Hz");
  expect_background_error("  installation: {floor: {frequencies_Hz: [], density_ug_per_sqrt_Hz: []}}\n",
                      "sensor.installation.floor.frequencies_Hz");
}

TEST(MachineBackground, ConfigBuiltInCodeIsCheckedToo) {
  AccelerometerConfig c = clean_config();
  c.path_modes = {{7000.0, 0.03, 0.5}};  // above 0.45 x 12 kHz
  EXPECT_THROW(VirtualAccelerometer(c, 12000.0), InvalidInputError);
  c.path_modes.clear();
  c.installation.shaft_modulation_depth = -0.1;
  try {
    VirtualAccelerometer sensor(c, 12000.0);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("installation.shaft_modulation_depth"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bearing_sim
