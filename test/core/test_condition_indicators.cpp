// analyze_vibration on synthetic signals with known answers: a sine of known velocity,
// Gaussian noise, and an outer-race impact train exciting a 3 kHz resonance.
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/errors.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

// Fault frequencies of a made-up bearing, far apart so each test line is unambiguous.
BearingFrequencies frequencies() {
  BearingFrequencies f;
  f.ball_pass_outer_race_hz = 87.0;
  f.ball_pass_inner_race_hz = 133.0;
  f.ball_spin_hz = 55.5;  // 2 x = 111 Hz
  f.cage_hz = 9.7;
  f.relative_ring_hz = 23.0;
  return f;
}

TEST(ConditionIndicators, ZoneBoundaries) {
  const VelocityZoneBoundaries b;  // ISO 20816-3 group 2, rigid: 1.4 / 2.8 / 4.5 mm/s
  EXPECT_EQ(velocity_zone(1.39, b), VelocityZone::A);
  EXPECT_EQ(velocity_zone(1.4, b), VelocityZone::B);
  EXPECT_EQ(velocity_zone(2.79, b), VelocityZone::B);
  EXPECT_EQ(velocity_zone(2.8, b), VelocityZone::C);
  EXPECT_EQ(velocity_zone(4.5, b), VelocityZone::D);
  const VelocityZoneBoundaries flexible{2.3, 4.5, 7.1};  // group 2, flexible foundation
  EXPECT_EQ(velocity_zone(4.0, flexible), VelocityZone::B);
}

TEST(ConditionIndicators, SineOfKnownVelocity) {
  // omega = 1000 rad/s (159.155 Hz); acceleration amplitude a = v_rms sqrt2 omega for 3.5 mm/s.
  const double fs = 20000.0, omega = 1000.0, v_rms = 3.5e-3;
  const double a = v_rms * std::sqrt(2.0) * omega;  // 4.95 m/s^2
  std::vector<double> x(40000);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = a * std::sin(omega * i / fs);
  const ConditionIndicators c = analyze_vibration(x, fs, frequencies());
  // Partial period at the end: crest and RMS of a sampled sine within 0.1%.
  EXPECT_NEAR(c.acceleration.rms, a / std::sqrt(2.0), 1e-3 * a);
  EXPECT_NEAR(c.acceleration.crest_factor, std::sqrt(2.0), 2e-3);
  EXPECT_NEAR(c.level_db, 20.0 * std::log10(a / std::sqrt(2.0) / 9.81e-3), 0.01);  // JB/T 5314 L
  EXPECT_NEAR(c.velocity_rms_mm_s, 3.5, 0.01 * 3.5);  // windowed Parseval, see test_spectrum
  EXPECT_EQ(c.zone, VelocityZone::C);
  EXPECT_EQ(c.diagnosis.level, HealthLevel::Warn);
  EXPECT_NE(c.diagnosis.reason.find("zone C"), std::string::npos) << c.diagnosis.reason;
  // Zone D at 5 mm/s: ERROR.
  for (double& v : x) v *= 5.0 / 3.5;
  const ConditionIndicators d = analyze_vibration(x, fs, frequencies());
  EXPECT_EQ(d.zone, VelocityZone::D);
  EXPECT_EQ(d.diagnosis.level, HealthLevel::Error);
}

TEST(ConditionIndicators, VelocityBandFollowsTheMachineSpeed) {
  // ISO 20816-3: 2-1000 Hz below 600 rpm, 10-1000 Hz above. A 5 Hz acceleration sine of
  // 1 mm/s RMS velocity (a = v sqrt2 omega) counts on a 180 rpm machine (the CT gantry)
  // and not on a 1380 rpm one (23 Hz): there only the 1/f^2-weighted leakage of the
  // Hann window's main lobe, far below 5 %, is left.
  EXPECT_DOUBLE_EQ(iso20816_velocity_low_hz(3.0), 2.0);
  EXPECT_DOUBLE_EQ(iso20816_velocity_low_hz(-3.0), 2.0);
  EXPECT_DOUBLE_EQ(iso20816_velocity_low_hz(10.0), 10.0);
  const double fs = 2000.0, omega = 2.0 * kPi * 5.0, v_rms = 1e-3;
  std::vector<double> x(40000);  // 20 s, 100 periods
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = v_rms * std::sqrt(2.0) * omega * std::sin(omega * i / fs);
  BearingFrequencies slow = frequencies();
  slow.relative_ring_hz = 3.0;
  const ConditionIndicators c_slow = analyze_vibration(x, fs, slow);
  EXPECT_DOUBLE_EQ(c_slow.velocity_low_hz, 2.0);
  EXPECT_DOUBLE_EQ(c_slow.velocity_high_hz, 1000.0);
  EXPECT_NEAR(c_slow.velocity_rms_mm_s, 1.0, 0.01);
  const ConditionIndicators c_fast = analyze_vibration(x, fs, frequencies());
  EXPECT_DOUBLE_EQ(c_fast.velocity_low_hz, 10.0);
  EXPECT_LT(c_fast.velocity_rms_mm_s, 0.05);
  // An explicit band wins.
  AnalysisOptions o;
  o.velocity_low_hz = 10.0;
  EXPECT_LT(analyze_vibration(x, fs, slow, o).velocity_rms_mm_s, 0.05);
}

TEST(ConditionIndicators, GaussianNoiseIsOk) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n(0.0, 0.5);
  std::vector<double> x(200000);
  for (double& v : x) v = n(rng);
  AnalysisOptions fixed;
  fixed.envelope_band = EnvelopeBand::Fixed;
  const ConditionIndicators c = analyze_vibration(x, 20000.0, frequencies(), fixed);
  // White noise of 0.5 m/s^2 at 20 kHz: v^2 = S/(4 pi^2) (1/10 - 1/1000) with
  // S = 0.25/10000 (m/s^2)^2/Hz: 0.25 mm/s, zone A. 15%: the 1/f^2 weight leaves some
  // 150 independent bins near 10 Hz in 10 s, a standard error of about 4% in v.
  EXPECT_NEAR(c.velocity_rms_mm_s, 1e3 * std::sqrt(0.25 / 10000.0 / (4 * kPi * kPi) * 0.099), 0.15 * 0.25);
  EXPECT_EQ(c.diagnosis.level, HealthLevel::Ok) << c.diagnosis.reason;
  for (const FaultIndicator& f : c.faults) EXPECT_FALSE(f.suspected) << fault_frequency_label(f.kind);
  // Default envelope band: 4 x the highest fault frequency (133 Hz -> 532 Hz) up to 0.4 fs.
  EXPECT_DOUBLE_EQ(c.envelope_low_hz, 532.0);
  EXPECT_DOUBLE_EQ(c.envelope_high_hz, 8000.0);
  EXPECT_EQ(c.envelope_band_source, "fixed");
  // The default, the kurtogram's band: in white noise every band is Gaussian (SK about 0;
  // the estimate of a band of B Hz over 10 s scatters by ~sqrt(4/(10 B)), < 0.1 here).
  const ConditionIndicators k = analyze_vibration(x, 20000.0, frequencies());
  EXPECT_EQ(k.envelope_band_source, "kurtogram");
  EXPECT_NEAR(k.envelope_band_kurtosis, 0.0, 0.3);
  EXPECT_GE(k.envelope_low_hz, 532.0);
  EXPECT_GE(k.envelope_high_hz - k.envelope_low_hz, 3.0 * 133.0);
  EXPECT_EQ(k.diagnosis.level, HealthLevel::Ok) << k.diagnosis.reason;
}

TEST(ConditionIndicators, KurtogramFindsTheImpulsiveBand) {
  // Bursts at BPFO of a 6 kHz tone under a Gaussian of 0.4 ms (a band-limited impulse: its
  // spectrum is a Gaussian of 1/(2 pi 0.4 ms) = 400 Hz around 6 kHz), RMS 0.18 m/s^2,
  // buried under Gaussian noise low-passed to 3 kHz (RMS ~1.6, nine times larger) and a weak
  // white floor (0.05). The band of the largest spectral kurtosis must hold the bursts'
  // band and none of the strong noise.
  const double fs = 20000.0, bpfo = frequencies().ball_pass_outer_race_hz;
  const double fn = 6000.0, wn = 2.0 * kPi * fn;
  std::mt19937_64 rng(8);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> loud(40000), x(40000);
  for (double& v : loud) v = 3.0 * n(rng);
  loud = band_pass(loud, fs, 0.0, 3000.0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double since = std::fmod(i / fs, 1.0 / bpfo);
    const double g = (since - 2e-3) / 0.4e-3;
    x[i] = std::exp(-0.5 * g * g) * std::sin(wn * since) + loud[i] + 0.05 * n(rng);
  }
  const Kurtogram k = fast_kurtogram(x, fs, 300.0);
  EXPECT_LE(k.best.low_hz, fn);
  EXPECT_GE(k.best.high_hz, fn);
  EXPECT_GE(k.best.low_hz, 3000.0);
  EXPECT_GT(k.best.kurtosis, 3.0);  // impulsive (Gaussian: 0; measured 9)
  // The whole band [0, fs/2] is dominated by the loud Gaussian noise: SK near 0.
  ASSERT_FALSE(k.bands.empty());
  EXPECT_EQ(k.bands.front().bands_in_level, 1);
  EXPECT_LT(k.bands.front().kurtosis, 0.3);
  // analyze_vibration's default takes that band and finds the outer race series.
  const ConditionIndicators c = analyze_vibration(x, fs, frequencies());
  EXPECT_EQ(c.envelope_band_source, "kurtogram");
  EXPECT_LE(c.envelope_low_hz, fn);
  EXPECT_GE(c.envelope_high_hz, fn);
  EXPECT_TRUE(c.faults[0].suspected) << c.diagnosis.reason;
  for (std::size_t j = 1; j < 4; ++j) EXPECT_FALSE(c.faults[j].suspected) << fault_frequency_label(c.faults[j].kind);
}

// A slow tone that does not fill the window with whole periods jumps between the window's
// last and first sample; the kurtogram's band filters are circular, so before the taper that
// jump was a click ringing at both ends of every band's envelope and, above the noise's
// 8 kHz anti-alias cut-off where nothing else is left, it scored an SK in the hundreds.
// With nothing impulsive in the signal every band must read as Gaussian: SK 0, scattering
// by about sqrt(4 / N) for N independent envelope samples (the narrowest band here, 156 Hz
// over 2 s, has ~600; the largest of ~200 bands stays well under 1).
TEST(ConditionIndicators, KurtogramSeesNoClickAtTheWindowsEnds) {
  const double fs = 20000.0;
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<double> noise(40000), x(40000);
  for (double& v : noise) v = 0.1 * n(rng);
  noise = band_pass(noise, fs, 0.0, 8000.0);  // the sensor's anti-alias band
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = 10.0 * std::sin(2.0 * kPi * 7.3 * i / fs) + noise[i] + 1e-4 * n(rng);
  const Kurtogram k = fast_kurtogram(x, fs, 100.0);
  EXPECT_LT(k.best.kurtosis, 1.0) << "band " << k.best.low_hz << "-" << k.best.high_hz << " Hz";
}

TEST(ConditionIndicators, OuterRaceImpactTrain) {
  // Impacts at BPFO ringing a 3 kHz resonance (5% damping), in noise: the textbook outer
  // race signal. The diagnosis must name the outer race and the BPFO line.
  const double fs = 20000.0, bpfo = frequencies().ball_pass_outer_race_hz;
  const double fn = 3000.0, zeta = 0.05, wn = 2.0 * kPi * fn;
  std::vector<double> x(40000, 0.0);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> n(0.0, 0.2);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / fs;
    const double since = std::fmod(t, 1.0 / bpfo);  // time since the last impact
    x[i] = std::exp(-zeta * wn * since) * std::sin(wn * since) + n(rng);
  }
  AnalysisOptions o;
  o.resonance_hz = 3000.0;  // band 2-4 kHz around the resonance
  const ConditionIndicators c = analyze_vibration(x, fs, frequencies(), o);
  EXPECT_DOUBLE_EQ(c.envelope_low_hz, 2000.0);
  EXPECT_DOUBLE_EQ(c.envelope_high_hz, 4000.0);
  const FaultIndicator& f = c.faults[0];
  ASSERT_EQ(f.kind, FaultKind::OuterRace);
  EXPECT_NEAR(f.envelope_peak.frequency_hz, bpfo, 0.01 * bpfo);
  EXPECT_GE(f.envelope_peak.snr_db, 10.0);
  EXPECT_TRUE(f.suspected);
  for (std::size_t k = 1; k < 3; ++k) EXPECT_FALSE(c.faults[k].suspected) << fault_frequency_label(c.faults[k].kind);
  // Kurtosis by hand: a burst e^(-a s) sin(wn s), a = zeta wn = 942 /s, per period T = 1/87 s
  // has m2 = 1/(4 a T) = 0.0231 and m4 = (3/8)/(4 a T) = 1.5 a T m2^2 = 8.66e-3 (aT = 10.8);
  // with noise s^2 = 0.04: K = (m4 + 6 m2 s^2 + 3 s^4) / (m2 + s^2)^2 = 4.77 (noise alone: 3).
  // 0.3: the sample kurtosis of 40000 samples of this mix scatters by about 0.05.
  EXPECT_NEAR(c.acceleration.kurtosis, 4.77, 0.3);
  EXPECT_EQ(c.diagnosis.level, HealthLevel::Warn);
  EXPECT_EQ(c.diagnosis.reason.rfind("outer race defect suspected: envelope peak at 87.", 0), 0u) << c.diagnosis.reason;
}

// A 3 kHz carrier amplitude-modulated by 1 + e(t), in Gaussian noise (0.5 m/s^2 RMS, 20 kHz):
// the band envelope is 1 + e(t) (e > -1), so its spectrum holds exactly the lines of e and
// no harmonics that e does not have. 2 s: 0.5 Hz bins.
std::vector<double> modulated_carrier(const std::function<double(double)>& e, unsigned seed) {
  const double fs = 20000.0;
  std::vector<double> x(40000);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 0.5);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / fs;
    x[i] = (1.0 + e(t)) * std::sin(2.0 * kPi * 3000.0 * t) + n(rng);
  }
  return x;
}

// These tests are about the lines of a series; the band of a smooth modulation is not
// impulsive, which the rule asks of a series without sidebands (tested in test_fault_evidence),
// so that requirement is off here; and they are about one spectrum of the window as recorded
// (rules 10-13: test_real_signal_evidence).
ConditionIndicators analyze_carrier(const std::vector<double>& x, const BearingFrequencies& f) {
  AnalysisOptions o;
  o.resonance_hz = 3000.0;
  o.segment_s = 1e9;
  o.prewhiten = false;
  o.thresholds.impulsive_band_kurtosis = 0.0;
  return analyze_vibration(x, 20000.0, f, o);
}

// Envelope noise per 0.5 Hz bin: the band noise (0.5^2 x 2/10 = 0.05 (m/s^2)^2 over 1 kHz
// of envelope bandwidth) gives about 2 sqrt(5e-5 x 0.5 x 1.5) = 0.012 m/s^2 with Hann, so a
// 0.3 line is ~28 dB over it, a 0.2 line ~24 dB, a 0.09 sideband ~17 dB: all far over the
// 12 / 10 dB thresholds; an absent line is noise (a Rayleigh bin over 10 dB: ~0.1%).
TEST(ConditionIndicators, FundamentalWithoutHarmonicsIsNotAFault) {
  const double bpfo = frequencies().ball_pass_outer_race_hz;
  const ConditionIndicators c = analyze_carrier(
      modulated_carrier([&](double t) { return 0.3 * std::cos(2.0 * kPi * bpfo * t); }, 21), frequencies());
  const FaultIndicator& f = c.faults[0];
  ASSERT_EQ(f.kind, FaultKind::OuterRace);
  ASSERT_EQ(f.harmonics.size(), 4u);  // orders 1-4
  EXPECT_TRUE(f.harmonics[0].found);
  EXPECT_GE(f.harmonics[0].peak.snr_db, 20.0);
  EXPECT_FALSE(f.harmonics[1].found) << f.harmonics[1].peak.snr_db;
  EXPECT_EQ(f.harmonics_found, 1);
  EXPECT_FALSE(f.sidebands_required);  // frequencies() has both rings at 0 in the load frame
  EXPECT_FALSE(f.suspected);
  for (const FaultIndicator& g : c.faults) EXPECT_FALSE(g.suspected) << fault_frequency_label(g.kind);
  EXPECT_EQ(c.diagnosis.reason.find("suspected"), std::string::npos) << c.diagnosis.reason;
}

TEST(ConditionIndicators, FundamentalWithHarmonicsIsAFault) {
  const double bpfo = frequencies().ball_pass_outer_race_hz;
  const ConditionIndicators c = analyze_carrier(
      modulated_carrier(
          [&](double t) { return 0.3 * std::cos(2.0 * kPi * bpfo * t) + 0.2 * std::cos(4.0 * kPi * bpfo * t); }, 21),
      frequencies());
  const FaultIndicator& f = c.faults[0];
  EXPECT_EQ(f.harmonics_found, 2);  // no 3rd harmonic in e
  EXPECT_NEAR(f.harmonics[1].peak.frequency_hz, 2.0 * bpfo, 0.01 * 2.0 * bpfo);
  EXPECT_GE(f.harmonics[1].peak.snr_db, 15.0);
  EXPECT_TRUE(f.suspected);
  for (std::size_t k = 1; k < 4; ++k) EXPECT_FALSE(c.faults[k].suspected) << fault_frequency_label(c.faults[k].kind);
  EXPECT_EQ(c.diagnosis.reason.rfind("outer race defect suspected: envelope peak at 87.", 0), 0u) << c.diagnosis.reason;
  EXPECT_NE(c.diagnosis.reason.find("2 harmonics"), std::string::npos) << c.diagnosis.reason;
}

TEST(ConditionIndicators, InnerRaceNeedsItsShaftSpeedSidebands) {
  // The inner ring turns at 29 Hz in the load frame: an inner-race spall passes the load
  // zone once per turn, so its lines carry sidebands at -+29 Hz.
  BearingFrequencies fr = frequencies();
  fr.inner_ring_hz = 29.0;
  fr.relative_ring_hz = 29.0;
  const double bpfi = fr.ball_pass_inner_race_hz;
  auto series = [&](double t) { return 0.3 * std::cos(2.0 * kPi * bpfi * t) + 0.2 * std::cos(4.0 * kPi * bpfi * t); };
  // Harmonics but no sidebands: not an inner race defect.
  const ConditionIndicators bare = analyze_carrier(modulated_carrier(series, 22), fr);
  const FaultIndicator& b = bare.faults[1];
  ASSERT_EQ(b.kind, FaultKind::InnerRace);
  EXPECT_EQ(b.harmonics_found, 2);
  EXPECT_TRUE(b.sidebands_required);
  EXPECT_DOUBLE_EQ(b.modulation_hz, 29.0);
  ASSERT_EQ(b.sidebands.size(), 2u);
  EXPECT_EQ(b.sidebands_found, 0);
  EXPECT_FALSE(b.suspected);
  // The same series modulated by 1 + 0.6 cos(2 pi 29 t): sidebands of 0.09 at 133 -+ 29 Hz.
  const ConditionIndicators mod = analyze_carrier(
      modulated_carrier([&](double t) { return series(t) * (1.0 + 0.6 * std::cos(2.0 * kPi * 29.0 * t)); }, 22), fr);
  const FaultIndicator& m = mod.faults[1];
  EXPECT_EQ(m.harmonics_found, 2);
  EXPECT_EQ(m.sidebands_found, 2);
  EXPECT_NEAR(m.sidebands[0].peak.frequency_hz, bpfi - 29.0, 0.01 * (bpfi - 29.0));
  EXPECT_NEAR(m.sidebands[1].peak.frequency_hz, bpfi + 29.0, 0.01 * (bpfi + 29.0));
  EXPECT_TRUE(m.suspected);
  EXPECT_NE(mod.diagnosis.reason.find("inner race defect suspected"), std::string::npos) << mod.diagnosis.reason;
  EXPECT_NE(mod.diagnosis.reason.find("2/2 sidebands at -+29.0 Hz"), std::string::npos) << mod.diagnosis.reason;
}

TEST(ConditionIndicators, WindowAndErrors) {
  std::vector<double> x(30000, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.3 * i);
  AnalysisOptions o;
  o.window_s = 0.5;  // 10000 samples at 20 kHz (an FFT-friendly length: 2^4 5^4)
  const ConditionIndicators c = analyze_vibration(x, 20000.0, frequencies(), o);
  EXPECT_EQ(c.samples, 10000u);
  EXPECT_DOUBLE_EQ(c.window_s, 0.5);
  EXPECT_THROW(analyze_vibration(std::vector<double>(10, 1.0), 20000.0, frequencies()), InvalidInputError);
  EXPECT_THROW(analyze_vibration(x, 0.0, frequencies()), InvalidInputError);
  o.resonance_hz = 9500.0;  // band up to 10.5 kHz: beyond Nyquist at 20 kHz
  EXPECT_THROW(analyze_vibration(x, 20000.0, frequencies(), o), InvalidInputError);
}

}  // namespace
}  // namespace bearing_sim

namespace bearing_sim {
namespace {

// Fault lines faster than the envelope band is wide cannot be in its envelope: a shaft
// speed 30 times too high puts BPFO at 2610 Hz, beyond the 2 kHz resonance band. The series
// say so, and a window that shows no race or ball series is not called healthy.
TEST(ConditionIndicators, FaultLinesAboveTheBandCannotBeSeen) {
  const BearingFrequencies f = scaled_frequencies(frequencies(), 30.0);
  std::vector<double> x(20000);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> n(0.0, 1.0);
  for (double& v : x) v = n(rng);
  AnalysisOptions o;
  o.resonance_hz = 3000.0;  // band 2-4 kHz: envelope lines up to 2 kHz
  const ConditionIndicators c = analyze_vibration(x, 20000.0, f, o);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_FALSE(c.faults[k].resolvable) << fault_frequency_label(c.faults[k].kind);
    EXPECT_NE(c.faults[k].note.find("cannot see"), std::string::npos) << c.faults[k].note;
  }
  EXPECT_TRUE(c.faults[3].resolvable);  // the cage line, 291 Hz, is within the band's reach
  EXPECT_EQ(c.diagnosis.level, HealthLevel::Warn) << c.diagnosis.reason;
  EXPECT_NE(c.diagnosis.reason.find("cannot assess"), std::string::npos) << c.diagnosis.reason;
}

}  // namespace
}  // namespace bearing_sim
