// Virtual accelerometer (docs/sensor.md): each stage against a closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <unsupported/Eigen/FFT>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

// --- independent references -------------------------------------------------------------

// |H| of the base-excited mass-spring-damper (absolute acceleration transmissibility),
// written from the textbook form with r = f/fn.
double transmissibility(double f, double fn, double zeta) {
  const double r = f / fn, two_zeta_r = 2.0 * zeta * r;
  return std::sqrt((1.0 + two_zeta_r * two_zeta_r) / ((1.0 - r * r) * (1.0 - r * r) + two_zeta_r * two_zeta_r));
}

// Butterworth of order n, bilinear with the cut-off pre-warped: the analog magnitude on the
// warped axis tan(pi f/fs).
double butterworth_gain(int n, double fc, double fs, double f) {
  const double r = std::tan(kPi * f / fs) / std::tan(kPi * fc / fs);
  return 1.0 / std::sqrt(1.0 + std::pow(r, 2 * n));
}

double band_mean(const std::vector<double>& psd, double fs, int n, double f_lo, double f_hi) {
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k < static_cast<int>(psd.size()); ++k) {
    const double f = k * fs / n;
    if (f >= f_lo && f <= f_hi) {
      sum += psd[k];
      ++count;
    }
  }
  return sum / count;
}

double rms(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s / x.size());
}

// A clean chain: no noise, 24 bits, path and anti-alias as given.
AccelerometerConfig quiet_config(double output_rate_hz, double path_resonance_hz) {
  AccelerometerConfig c;
  c.output_rate_hz = output_rate_hz;
  c.path_resonance_hz = path_resonance_hz;
  c.noise_density_m_s2_per_sqrt_hz = 0.0;
  return c;
}

std::vector<double> run_axis(VirtualAccelerometer& sensor, const std::vector<double>& input) {
  std::vector<double> out;
  out.reserve(input.size() / sensor.decimation_ratio() + 1);
  double y = 0.0;
  for (double a : input)
    if (sensor.push_axis_acceleration(a, &y)) out.push_back(y);
  return out;
}

std::vector<double> sine(double amplitude, double f, double fs, double seconds) {
  std::vector<double> x(static_cast<std::size_t>(std::lround(seconds * fs)));
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = amplitude * std::sin(2.0 * kPi * f * i / fs);
  return x;
}

std::vector<double> white(double sigma, std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  return x;
}

// Output amplitude at f, over the last `window_s` seconds (a whole number of periods).
double tone_amplitude(const std::vector<double>& out, double fs, double f, double window_s) {
  const std::size_t n = static_cast<std::size_t>(std::lround(window_s * fs));
  return test::dft_amplitude(std::vector<double>(out.end() - n, out.end()), fs, f);
}

// --- transmission path --------------------------------------------------------------------

TEST(VirtualAccelerometer, PathGainMatchesSeismicTransmissibility) {
  // Sines of known amplitude through path + anti-alias; reference |H_path| x |H_aa| in closed
  // form. The discretization is exact at DC and fn by construction (0.5 %: the measurement);
  // elsewhere, for fn <= 0.3 fs, within 1.7 % below fn and 2.1 % up to 1.1 fn (docs/sensor.md).
  struct Case {
    double fs, fn, f, tolerance;
  };
  const double zeta = 0.05;
  for (const Case& c : {Case{10000, 3000, 100, 0.005}, Case{10000, 3000, 1500, 0.02}, Case{10000, 3000, 3000, 0.005},
                        Case{10000, 3000, 3300, 0.03}, Case{51200, 12000, 250, 0.005}, Case{51200, 12000, 12000, 0.005},
                        Case{51200, 12000, 6000, 0.02}}) {
    AccelerometerConfig config = quiet_config(c.fs, c.fn);
    config.path_damping_ratio = zeta;
    VirtualAccelerometer sensor(config, c.fs);
    const double amplitude = 2.0;
    const std::vector<double> out = run_axis(sensor, sine(amplitude, c.f, c.fs, 0.5));
    const double measured = tone_amplitude(out, c.fs, c.f, 0.4) / amplitude;
    const double expected = transmissibility(c.f, c.fn, zeta) * butterworth_gain(8, 0.4 * c.fs, c.fs, c.f);
    EXPECT_NEAR(measured / expected, 1.0, c.tolerance) << "fs " << c.fs << " fn " << c.fn << " f " << c.f;
    std::printf("path fs %.0f fn %.0f f %.0f: |H| closed form %.4f, measured %.4f\n", c.fs, c.fn, c.f, expected,
                measured);
    if (c.f == c.fn) {
      EXPECT_NEAR(measured, 1.0 / (2.0 * zeta), 0.01 / (2.0 * zeta));  // peak ~ 1/(2 zeta)
    }
    if (c.f < 0.03 * c.fn) {
      EXPECT_NEAR(measured, 1.0, 0.005);  // unity at low frequency
    }
  }
}

TEST(VirtualAccelerometer, ResonanceIsThePeakOfTheWhiteNoiseSpectrum) {
  const double fs = 10000.0, fn = 3000.0, zeta = 0.05;
  AccelerometerConfig config = quiet_config(fs, fn);
  VirtualAccelerometer sensor(config, fs);
  const std::vector<double> out = run_axis(sensor, white(1.0, 400000, 7));
  const int n = 4096;
  const std::vector<double> psd = test::welch_psd(out, fs, n);
  // Peak of the PSD smoothed over 9 bins (22 Hz, against the 300 Hz wide resonance).
  double best = 0.0, f_peak = 0.0;
  for (int k = 4; k + 4 < static_cast<int>(psd.size()); ++k) {
    double s = 0.0;
    for (int j = -4; j <= 4; ++j) s += psd[k + j];
    if (k * fs / n > 500.0 && s > best) {
      best = s;
      f_peak = k * fs / n;
    }
  }
  // Maximum of the closed-form |H|: fn sqrt(sqrt(1 + 8 zeta^2) - 1) / (2 zeta) = 0.9975 fn.
  const double f_expected = fn * std::sqrt(std::sqrt(1.0 + 8.0 * zeta * zeta) - 1.0) / (2.0 * zeta);
  EXPECT_NEAR(f_peak, f_expected, 0.01 * fn);
  std::printf("resonance peak: closed form %.1f Hz, measured %.1f Hz\n", f_expected, f_peak);
  // Height: PSD near fn over PSD at 100..500 Hz equals |H(fn)|^2 / mean |H|^2 (~101).
  const double measured = band_mean(psd, fs, n, fn - 15.0, fn + 15.0) / band_mean(psd, fs, n, 100.0, 500.0);
  double low = 0.0;
  for (double f = 100.0; f <= 500.0; f += 1.0) low += std::pow(transmissibility(f, fn, zeta), 2) / 401.0;
  const double expected = std::pow(transmissibility(fn, fn, zeta), 2) / low;
  EXPECT_NEAR(measured / expected, 1.0, 0.10) << measured << " vs " << expected;
  std::printf("resonance PSD ratio: closed form %.1f, measured %.1f\n", expected, measured);
}

// --- noise floor, anti-alias, decimation ---------------------------------------------------

TEST(VirtualAccelerometer, NoiseFloorDensityAndRms) {
  // Zero input: the output is the sensor noise through the anti-alias filter and the 2:1
  // decimation. 200 000 outputs; Welch with ~200 segments and ~570 bins averaged: the
  // statistical error of the band mean is < 1 %, of the RMS ~0.3 %; tolerance 5 % / 3 %.
  const double fs_in = 20000.0, fs_out = 10000.0, density = 1e-3;
  AccelerometerConfig config;
  config.output_rate_hz = fs_out;
  config.noise_density_m_s2_per_sqrt_hz = density;
  VirtualAccelerometer sensor(config, fs_in);
  EXPECT_DOUBLE_EQ(sensor.noise_sigma_m_s2(), density * std::sqrt(fs_in / 2.0));
  const std::vector<double> out = run_axis(sensor, std::vector<double>(400000, 0.0));
  ASSERT_EQ(out.size(), 200000u);
  const int n = 2048;
  const std::vector<double> psd = test::welch_psd(out, fs_out, n);
  const double measured_density = std::sqrt(band_mean(psd, fs_out, n, 200.0, 3000.0));
  EXPECT_NEAR(measured_density / density, 1.0, 0.05) << measured_density;
  // Variance = D^2 times the noise bandwidth of the filter, B = integral over 0..fs_in/2 of |H|^2.
  const int steps = 20000;  // Simpson
  const double h = 0.5 * fs_in / steps;
  double bandwidth = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double g = i == steps ? 0.0 : butterworth_gain(8, 0.4 * fs_out, fs_in, i * h);
    bandwidth += (i == 0 || i == steps ? 1.0 : (i % 2 ? 4.0 : 2.0)) * g * g * h / 3.0;
  }
  // For orientation: the analog Butterworth's fc (pi/2n)/sin(pi/2n) = 1.0064 fc = 4026 Hz.
  EXPECT_NEAR(bandwidth / (0.4 * fs_out), 1.0, 0.02);
  EXPECT_NEAR(rms(out) / (density * std::sqrt(bandwidth)), 1.0, 0.03) << rms(out);
  std::printf("noise: density %.4g measured %.4g; B %.1f Hz, RMS expected %.4g measured %.4g\n", density,
              measured_density, bandwidth, density * std::sqrt(bandwidth), rms(out));
}

TEST(VirtualAccelerometer, AntiAliasAttenuatesToneAboveOutputNyquist) {
  // 40 kHz in, 10 kHz out: a 7 kHz tone would alias to 3 kHz. Expected attenuation: the
  // 8th-order bilinear Butterworth at 7 kHz, (tan(pi 7/40)/tan(pi 4/40))^-8 -> -44 dB.
  const double fs_in = 40000.0, fs_out = 10000.0, amplitude = 100.0;
  VirtualAccelerometer sensor(quiet_config(fs_out, 0.0), fs_in);
  EXPECT_EQ(sensor.decimation_ratio(), 4);
  const std::vector<double> out = run_axis(sensor, sine(amplitude, 7000.0, fs_in, 0.5));
  const double alias = tone_amplitude(out, fs_out, 3000.0, 0.4) / amplitude;
  const double expected = butterworth_gain(8, 4000.0, fs_in, 7000.0);
  EXPECT_NEAR(alias / expected, 1.0, 0.03) << 20.0 * std::log10(alias) << " dB";
  EXPECT_LT(20.0 * std::log10(alias), -40.0);
  std::printf("anti-alias at 7 kHz: closed form %.2f dB, measured %.2f dB\n", 20.0 * std::log10(expected),
              20.0 * std::log10(alias));
  // An in-band tone passes with the Butterworth gain (~1).
  sensor.reset();
  const std::vector<double> in_band = run_axis(sensor, sine(amplitude, 1000.0, fs_in, 0.5));
  EXPECT_NEAR(tone_amplitude(in_band, fs_out, 1000.0, 0.4) / amplitude, butterworth_gain(8, 4000.0, fs_in, 1000.0),
              1e-3);
}

TEST(VirtualAccelerometer, DecimationKeepsOneSampleInRatio) {
  AccelerometerConfig config;
  config.output_rate_hz = 10240.0;
  VirtualAccelerometer sensor(config, 51200.0);
  EXPECT_EQ(sensor.decimation_ratio(), 5);
  EXPECT_EQ(run_axis(sensor, std::vector<double>(1003, 0.0)).size(), 200u);
  config.output_rate_hz = 51200.0;
  VirtualAccelerometer full_rate(config, 51200.0);
  EXPECT_EQ(full_rate.decimation_ratio(), 1);
  EXPECT_EQ(run_axis(full_rate, std::vector<double>(1003, 0.0)).size(), 1003u);
  // Block version on dynamics samples: same count.
  std::vector<DynamicSample> block(1003);
  std::vector<double> out;
  out.reserve(1003);
  sensor.reset();
  sensor.push_block(block, &out);
  EXPECT_EQ(out.size(), 200u);
}

// --- ADC -----------------------------------------------------------------------------------

TEST(VirtualAccelerometer, ClipsAtTheRange) {
  AccelerometerConfig config = quiet_config(10000.0, 0.0);
  config.range_m_s2 = 9.80665;  // 1 g
  config.adc_bits = 16;
  VirtualAccelerometer sensor(config, 10000.0);
  const double step = 2.0 * 9.80665 / 65536.0;
  EXPECT_DOUBLE_EQ(sensor.quantization_step_m_s2(), step);
  const std::vector<double> out = run_axis(sensor, sine(30.0, 200.0, 10000.0, 0.1));
  const auto [lo, hi] = std::minmax_element(out.begin(), out.end());
  EXPECT_DOUBLE_EQ(*hi, 9.80665 - step);  // the top code of a two's-complement ADC
  EXPECT_DOUBLE_EQ(*lo, -9.80665);
  EXPECT_GT(sensor.clipped_sample_count(), 0u);
}

TEST(VirtualAccelerometer, QuantizationStepAndNoise) {
  // 8 bits over +-10 m/s^2: step 20/256. A busy signal (sigma 2 m/s^2 >> step) makes the
  // rounding error uniform: RMS step/sqrt(12); 20 000 samples -> ~0.5 % statistical error.
  AccelerometerConfig config = quiet_config(10000.0, 0.0);
  config.range_m_s2 = 10.0;
  config.adc_bits = 8;
  VirtualAccelerometer coarse(config, 10000.0);
  config.adc_bits = 32;
  VirtualAccelerometer fine(config, 10000.0);
  const double step = 20.0 / 256.0;
  EXPECT_DOUBLE_EQ(coarse.quantization_step(), step);
  const std::vector<double> input = white(2.0, 20000, 11);
  const std::vector<double> q = run_axis(coarse, input), ideal = run_axis(fine, input);
  double error_power = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    ASSERT_NEAR(q[i] / step, std::round(q[i] / step), 1e-9) << i;
    error_power += (q[i] - ideal[i]) * (q[i] - ideal[i]);
  }
  EXPECT_EQ(coarse.clipped_sample_count(), 0u);
  EXPECT_NEAR(std::sqrt(error_power / q.size()) / (step / std::sqrt(12.0)), 1.0, 0.03);
  std::printf("quantization error RMS: step/sqrt(12) %.5f, measured %.5f\n", step / std::sqrt(12.0),
              std::sqrt(error_power / q.size()));
}

// --- geometry and scaling -------------------------------------------------------------------

TEST(VirtualAccelerometer, MountingPointPicksUpTiltTimesLever) {
  AccelerometerConfig config = quiet_config(10000.0, 0.0);
  config.mount_point_m = Eigen::Vector3d(0.3, -0.2, 0.05);
  const double ax = 3.0, ay = -2.0;  // theta_x'', theta_y''
  Vector5 tilt;
  tilt << 0.0, 0.0, 0.0, ax, ay;
  // alpha x r written out by components: (ay rz, -ax rz, ax ry - ay rx).
  const double rx = 0.3, ry = -0.2, rz = 0.05;
  const Eigen::Vector3d alpha_cross_r(ay * rz, -ax * rz, ax * ry - ay * rx);
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0)}) {
    config.axis = axis;
    VirtualAccelerometer sensor(config, 10000.0);
    EXPECT_NEAR(sensor.ideal_axis_acceleration(tilt, 1.0), alpha_cross_r.dot(axis.normalized()), 1e-12);
  }
  // Through the chain: a 100 Hz tilt oscillation on the axial sensor gives |ax ry - ay rx| A.
  config.axis = Eigen::Vector3d(0, 0, 1);
  VirtualAccelerometer sensor(config, 10000.0);
  std::vector<double> out;
  double y = 0.0;
  for (int i = 0; i < 5000; ++i)
    if (sensor.push(tilt * std::sin(2.0 * kPi * 100.0 * i / 10000.0), 0.0, &y)) out.push_back(y);
  EXPECT_NEAR(tone_amplitude(out, 10000.0, 100.0, 0.4), std::abs(ax * ry - ay * rx), 1e-3);
  // Translation along the axis passes unchanged; across it, nothing.
  Vector5 translation;
  translation << 0.7, -0.4, 1.5, 0.0, 0.0;
  EXPECT_NEAR(sensor.ideal_axis_acceleration(translation, 0.0), 1.5, 1e-15);
}

TEST(VirtualAccelerometer, SensorOnTheMovingRingTurnsWithIt) {
  AccelerometerConfig config = quiet_config(10000.0, 0.0);
  config.mount = SensorMount::MovingRing;
  config.mount_point_m = Eigen::Vector3d(0.5, 0.0, 0.0);
  config.axis = Eigen::Vector3d(1, 0, 0);  // radial at ring angle 0
  VirtualAccelerometer sensor(config, 10000.0);
  Vector5 ax, ay, tilt_y;
  ax << 1, 0, 0, 0, 0;
  ay << 0, 1, 0, 0, 0;
  tilt_y << 0, 0, 0, 0, 2.0;
  EXPECT_NEAR(sensor.ideal_axis_acceleration(ax, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(sensor.ideal_axis_acceleration(ax, kPi / 2), 0.0, 1e-15);
  EXPECT_NEAR(sensor.ideal_axis_acceleration(ay, kPi / 2), 1.0, 1e-15);
  EXPECT_NEAR(sensor.ideal_axis_acceleration(ax, kPi), -1.0, 1e-15);
  // Axial sensor at ring angle 90 deg sits at (0, 0.5, 0): theta_y'' moves it by -ay rx = 0,
  // theta_x'' by ax ry = 0.5 ax.
  config.axis = Eigen::Vector3d(0, 0, 1);
  VirtualAccelerometer axial(config, 10000.0);
  Vector5 tilt_x;
  tilt_x << 0, 0, 0, 2.0, 0;
  EXPECT_NEAR(axial.ideal_axis_acceleration(tilt_y, kPi / 2), 0.0, 1e-15);
  EXPECT_NEAR(axial.ideal_axis_acceleration(tilt_x, kPi / 2), 1.0, 1e-15);
  EXPECT_NEAR(axial.ideal_axis_acceleration(tilt_y, 0.0), -1.0, 1e-15);
}

TEST(VirtualAccelerometer, CrossAxisCouplingReadsTheRadialAccelerationAcrossTheAxis) {
  // Read along n + k (z x n): for n = x the across direction is y, for n = -x it is -y; the
  // axial direction and the tilt lever (taken along n alone) are not coupled.
  AccelerometerConfig config = quiet_config(10000.0, 0.0);
  config.mount_point_m = Eigen::Vector3d(-0.026, 0.0, 0.0);
  config.cross_axis_coupling = 0.6;
  Vector5 ax, ay, az, tilt_y;
  ax << 1, 0, 0, 0, 0;
  ay << 0, 1, 0, 0, 0;
  az << 0, 0, 1, 0, 0;
  tilt_y << 0, 0, 0, 0, 2.0;
  config.axis = Eigen::Vector3d(1, 0, 0);
  VirtualAccelerometer down(config, 10000.0);
  EXPECT_NEAR(down.ideal_axis_acceleration(ax, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(down.ideal_axis_acceleration(ay, 0.0), 0.6, 1e-15);
  EXPECT_NEAR(down.ideal_axis_acceleration(az, 0.0), 0.0, 1e-15);
  // alpha x r = (0, 0, -theta_y'' r_x): along z only, which a radial sensor does not read.
  EXPECT_NEAR(down.ideal_axis_acceleration(tilt_y, 0.0), 0.0, 1e-15);
  config.axis = Eigen::Vector3d(-2, 0, 0);  // normalized on use
  VirtualAccelerometer up(config, 10000.0);
  EXPECT_NEAR(up.ideal_axis_acceleration(ax, 0.0), -1.0, 1e-15);
  EXPECT_NEAR(up.ideal_axis_acceleration(ay, 0.0), -0.6, 1e-15);
  // Through the chain (linear): a 200 Hz tone across the axis comes out at 0.6 x its amplitude.
  std::vector<double> out;
  double y = 0.0;
  for (int i = 0; i < 5000; ++i)
    if (down.push(ay * std::sin(2.0 * kPi * 200.0 * i / 10000.0), 0.0, &y)) out.push_back(y);
  EXPECT_NEAR(tone_amplitude(out, 10000.0, 200.0, 0.4), 0.6, 1e-3);
  // On the moving ring the coupled direction turns too: at 90 deg n = y, z x n = -x.
  config.axis = Eigen::Vector3d(1, 0, 0);
  config.mount = SensorMount::MovingRing;
  VirtualAccelerometer turning(config, 10000.0);
  EXPECT_NEAR(turning.ideal_axis_acceleration(ay, kPi / 2), 1.0, 1e-15);
  EXPECT_NEAR(turning.ideal_axis_acceleration(ax, kPi / 2), -0.6, 1e-15);
}

TEST(VirtualAccelerometer, SensitivityScalesToVolts) {
  AccelerometerConfig config;  // default noise on: the same seed gives the same noise
  config.noise_density_m_s2_per_sqrt_hz = 1e-2;
  VirtualAccelerometer accel(config, 10000.0);
  config.output_unit = SensorOutputUnit::Voltage_V;
  VirtualAccelerometer volts(config, 10000.0);
  const std::vector<double> input = sine(5.0, 440.0, 10000.0, 0.2);
  const std::vector<double> a = run_axis(accel, input), v = run_axis(volts, input);
  ASSERT_EQ(a.size(), v.size());
  const double sensitivity = 0.100 / 9.80665;  // 100 mV/g
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(v[i], a[i] * sensitivity, 1e-15) << i;
  EXPECT_NEAR(volts.quantization_step(), 10.0 / std::ldexp(1.0, 24), 1e-18);  // +-5 V over 24 bits
}

TEST(VirtualAccelerometer, NoiseIsDeterministicPerSeed) {
  AccelerometerConfig config;
  config.noise_density_m_s2_per_sqrt_hz = 1e-3;
  VirtualAccelerometer a(config, 10000.0), b(config, 10000.0);
  config.seed = 2;
  VirtualAccelerometer c(config, 10000.0);
  const std::vector<double> zeros(20000, 0.0);
  const std::vector<double> xa = run_axis(a, zeros), xb = run_axis(b, zeros), xc = run_axis(c, zeros);
  EXPECT_EQ(xa, xb);
  double cross = 0.0;
  for (std::size_t i = 0; i < xa.size(); ++i) cross += xa[i] * xc[i];
  // Independent noises: correlation ~ N(0, 1/sqrt(N_eff)); 0.1 is > 5 sigma.
  EXPECT_LT(std::abs(cross / (xa.size() * rms(xa) * rms(xc))), 0.1);
  a.reset();
  EXPECT_EQ(run_axis(a, zeros), xb);
}

// --- configuration ---------------------------------------------------------------------------

TEST(VirtualAccelerometer, ParsesSensorFile) {
  const AccelerometerConfig c = load_accelerometer_config(std::string(BEARING_SIM_SOURCE_DIR) +
                                                          "/config/sensors/ct_gantry_housing_accelerometer.yaml");
  EXPECT_EQ(c.mount, SensorMount::Housing);
  EXPECT_NEAR(c.sensitivity_V_per_m_s2, 0.1 / 9.80665, 1e-12);
  EXPECT_NEAR(c.range_m_s2, 50.0 * 9.80665, 1e-9);
  EXPECT_NEAR(c.axis.norm(), 1.0, 1e-12);
  EXPECT_NO_THROW(VirtualAccelerometer(c, 10000.0));

  const AccelerometerConfig d = accelerometer_config_from_string(
      "sensor:\n  mount: moving_ring\n  mount_point_mm: [555.5, 0, 20]\n  axis: [0, 0, 2]\n"
      "  noise_density_ug_per_sqrt_Hz: 50\n  output_rate_Hz: 51200\n  output_unit: V\n  seed: 42\n",
      "inline");
  EXPECT_EQ(d.mount, SensorMount::MovingRing);
  EXPECT_NEAR(d.mount_point_m.x(), 0.5555, 1e-12);
  EXPECT_NEAR(d.noise_density_m_s2_per_sqrt_hz, 50e-6 * 9.80665, 1e-15);
  EXPECT_EQ(d.output_unit, SensorOutputUnit::Voltage_V);
  EXPECT_EQ(d.seed, 42u);
}

void expect_sensor_error(const std::string& body, const std::string& key) {
  test::expect_config_error([&] { accelerometer_config_from_string(body, "bad_sensor.yaml"); },
                            {"bad_sensor.yaml", "'" + key + "'"}, key);
}

TEST(VirtualAccelerometer, BadConfigNamesTheKey) {
  expect_sensor_error("sensor:\n  sensitivity_V_per_g: 0.1\n", "sensor.sensitivity_V_per_g");
  expect_sensor_error("sensor:\n  adc_bits: many\n", "sensor.adc_bits");
  expect_sensor_error("sensor:\n  adc_bits: 4\n", "sensor.adc_bits");
  expect_sensor_error("sensor:\n  path_damping_ratio: 1.5\n", "sensor.path_damping_ratio");
  expect_sensor_error("sensor:\n  output_rate_Hz: 60000\n", "sensor.output_rate_Hz");
  expect_sensor_error("sensor:\n  anti_alias_order: 5\n", "sensor.anti_alias_order");
  expect_sensor_error("sensor:\n  anti_alias_cutoff_fraction: 0.5\n", "sensor.anti_alias_cutoff_fraction");
  expect_sensor_error("sensor:\n  axis: [0, 0, 0]\n", "sensor.axis");
  expect_sensor_error("sensor:\n  axis: [1, 0]\n", "sensor.axis");
  expect_sensor_error("sensor:\n  mount: shaft\n", "sensor.mount");
  expect_sensor_error("sensor:\n  cross_axis_coupling: 1.5\n", "sensor.cross_axis_coupling");
  expect_sensor_error("sensor:\n  cross_axis_coupling: .nan\n", "sensor.cross_axis_coupling");
  expect_sensor_error("sensor:\n  noise_density_ug_per_sqrt_Hz: -1\n", "sensor.noise_density_ug_per_sqrt_Hz");
  expect_sensor_error("sensor:\n  output_unit: g\n", "sensor.output_unit");
  expect_sensor_error("sensor: {}\nbearing: x\n", "bearing");
  expect_sensor_error("name: x\n", "name");  // a bare mapping, not under sensor:
}

TEST(VirtualAccelerometer, InconsistentRatesAreRejected) {
  auto message = [](const AccelerometerConfig& c, double input_rate_hz) {
    try {
      VirtualAccelerometer sensor(c, input_rate_hz);
    } catch (const InvalidInputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  AccelerometerConfig c;
  c.output_rate_hz = 3000.0;
  EXPECT_NE(message(c, 10000.0).find("does not divide"), std::string::npos);
  c.output_rate_hz = 20000.0;
  EXPECT_NE(message(c, 10000.0).find("exceeds the input"), std::string::npos);
  c.output_rate_hz = 10000.0;
  c.path_resonance_hz = 4800.0;
  EXPECT_NE(message(c, 10000.0).find("path_resonance_Hz"), std::string::npos);
  c.path_resonance_hz = 3000.0;
  c.output_rate_hz = 102400.0;
  EXPECT_NE(message(c, 102400.0).find("output_rate_Hz"), std::string::npos);
  // Numbers at the edges of floating point: a denormal damping ratio gave an all-NaN signal,
  // a denormal output rate an overflowing decimation ratio (SIGFPE).
  c.output_rate_hz = 1e-320;
  EXPECT_NE(message(c, 10000.0).find("output_rate_Hz"), std::string::npos);
  c.output_rate_hz = 10000.0;
  c.path_damping_ratio = 5e-324;
  EXPECT_NE(message(c, 10000.0).find("path_damping_ratio"), std::string::npos);
  c.path_damping_ratio = 0.05;
  EXPECT_EQ(message(c, 10000.0), "no error");
  VirtualAccelerometer sensor(c, 10000.0);
  double y = 0.0;
  EXPECT_THROW(sensor.push_axis_acceleration(std::nan(""), &y), InvalidInputError);
}

}  // namespace
}  // namespace bearing_sim
