// The evidence rule's decisions beyond the lines of one series (docs/health.md, "Evidence"):
// impulsiveness of a series without sidebands, resolvability of a fault frequency, one
// series standing for another, the cage line beside a race series. Synthetic signals with
// closed-form envelopes, 20 kHz.
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/condition_indicators.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;
constexpr double kFs = 20000.0;

// Both rings at 0 in the load frame (no sidebands predicted), lines far apart.
BearingFrequencies stationary_frequencies() {
  BearingFrequencies f;
  f.ball_pass_outer_race_hz = 87.0;
  f.ball_pass_inner_race_hz = 133.0;
  f.ball_spin_hz = 55.5;
  f.cage_hz = 9.7;
  f.relative_ring_hz = 23.0;
  f.varying_compliance_hz = 87.0;  // Z |f_c| = BPFO: the outer race stands, Z ~ 9
  return f;
}

// Bursts e^(-a s) sin(2 pi 3 kHz s) at the times of impact (a = zeta wn, 5 % damping: the
// ringing of a 3 kHz resonance), impact k of amplitude gain(k, t), plus white noise.
std::vector<double> impact_train(double rate_hz, const std::function<double(int, double)>& gain, double noise_rms,
                                 double seconds, unsigned seed) {
  const double wn = 2.0 * kPi * 3000.0, a = 0.05 * wn;
  std::vector<double> x(static_cast<std::size_t>(seconds * kFs));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, noise_rms);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / kFs;
    const int k = static_cast<int>(std::floor(t * rate_hz));
    const double since = t - k / rate_hz;
    x[i] = gain(k, t) * std::exp(-a * since) * std::sin(wn * since) + n(rng);
  }
  return x;
}

// Rules 1-9 of a single spectrum of the window as recorded (the averaged segments and the
// whitened path of rules 10-13 are tested in test_real_signal_evidence).
AnalysisOptions resonance_band() {
  AnalysisOptions o;
  o.resonance_hz = 3000.0;  // band 2-4 kHz
  o.segment_s = 1e9;        // one segment: the whole window
  o.prewhiten = false;
  return o;
}

// A healthy bearing's ball-pass excitation seen through the 3 kHz path resonance: a smooth
// periodic modulation at BPFO with its 2nd harmonic, 1 + 0.5 cos + 0.3 cos 2, under a quiet
// sensor (0.05 m/s^2). Its lines pass the old rule (fundamental, 2nd harmonic, no sideband
// predicted for the stationary outer race), but it is no impact train: the band envelope
// e = 1 + 0.5 cos + 0.3 cos 2 gives SK = <e^4> / <e^2>^2 - 2 = -0.32 (by quadrature; the noise
// brings it towards 0), far below the impulsive threshold of 2.
TEST(FaultEvidence, SmoothBallPassSeriesUnderAQuietSensorIsHealthy) {
  const double bpfo = stationary_frequencies().ball_pass_outer_race_hz;
  std::vector<double> x(40000);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 0.05);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / kFs, p = 2.0 * kPi * bpfo * t;
    x[i] = (1.0 + 0.5 * std::cos(p) + 0.3 * std::cos(2.0 * p)) * std::sin(2.0 * kPi * 3000.0 * t) + n(rng);
  }
  const ConditionIndicators c = analyze_vibration(x, kFs, stationary_frequencies(), resonance_band());
  const FaultIndicator& f = c.faults[0];
  ASSERT_EQ(f.kind, FaultKind::OuterRace);
  EXPECT_GE(f.harmonics_found, 2);  // the lines are there ...
  EXPECT_FALSE(f.sidebands_required);
  EXPECT_TRUE(f.impulsiveness_required);
  EXPECT_NEAR(c.envelope_band_kurtosis, -0.32, 0.1);
  EXPECT_FALSE(f.impulsive);  // ... but not an impact train
  EXPECT_FALSE(f.suspected);
  EXPECT_NE(f.note.find("not impulsive"), std::string::npos) << f.note;
  EXPECT_EQ(c.diagnosis.level, HealthLevel::Ok) << c.diagnosis.reason;
}

// The textbook outer-race spall: impacts at BPFO ringing the 3 kHz resonance. Closed form of
// the band's SK for ideal bursts: |c|^2 = e^(-2 a s) per period T = 1/BPFO, so
// <|c|^4> / <|c|^2>^2 = a T and SK = a T - 2 = 8.8 (a T = 0.05 x 2 pi 3000 / 87 = 10.8); white
// noise of 0.2 m/s^2 puts 0.008 (m/s^2)^2 into the 2 kHz band beside the bursts'
// 1/(4 a T) = 0.0231, which scales SK by (0.0231 / 0.0311)^2: 4.9. That is an upper bound:
// the band smooths each burst's onset over ~1/B = 0.5 ms against a 1.06 ms decay, which
// lowers the peaks (measured 3.6). The lower bound is the rule's threshold, 2.
TEST(FaultEvidence, ImpactTrainAtBpfoIsImpulsiveAndAnOuterRaceDefect) {
  const double bpfo = stationary_frequencies().ball_pass_outer_race_hz;
  const auto x = impact_train(
      bpfo, [](int, double) { return 1.0; }, 0.2, 2.0, 4);
  const ConditionIndicators c = analyze_vibration(x, kFs, stationary_frequencies(), resonance_band());
  EXPECT_GT(c.envelope_band_kurtosis, 2.0);
  EXPECT_LT(c.envelope_band_kurtosis, 4.9);
  const FaultIndicator& f = c.faults[0];
  EXPECT_TRUE(f.impulsiveness_required);
  EXPECT_TRUE(f.impulsive);
  EXPECT_TRUE(f.suspected) << c.diagnosis.reason;
  for (std::size_t k = 1; k < 4; ++k) EXPECT_FALSE(c.faults[k].suspected) << fault_frequency_label(c.faults[k].kind);
  EXPECT_EQ(c.diagnosis.reason.rfind("outer race defect suspected", 0), 0u) << c.diagnosis.reason;
}

// A slow cage (0.5 Hz, the CT gantry at 60 rpm) in a 1 s window (1 Hz bins): the line lies
// inside the main lobe of the envelope's mean, so nothing of it can be "found", however
// strong the signal near 0 Hz; the note asks for a longer window ((3 + 2) bins / 0.5 Hz = 10 s).
TEST(FaultEvidence, HalfHertzCageLineInOneSecondIsUnresolvable) {
  BearingFrequencies f = stationary_frequencies();
  f.cage_hz = 0.5;
  // Impacts at 87 Hz whose strength follows the cage (1 + 0.8 cos 2 pi 0.5 t): an envelope
  // full of energy in the lowest bins.
  const auto x = impact_train(
      87.0, [](int, double t) { return 1.0 + 0.8 * std::cos(2.0 * kPi * 0.5 * t); }, 0.05, 1.0, 6);
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& cage = c.faults[3];
  ASSERT_EQ(cage.kind, FaultKind::Cage);
  EXPECT_FALSE(cage.resolvable);
  EXPECT_FALSE(cage.harmonics[0].found);
  EXPECT_EQ(cage.harmonics_found, 0);
  EXPECT_FALSE(cage.suspected);
  EXPECT_NE(cage.note.find("not resolvable"), std::string::npos) << cage.note;
  EXPECT_NE(cage.note.find("10.0 s"), std::string::npos) << cage.note;
  EXPECT_EQ(c.diagnosis.reason.find("cage"), std::string::npos) << c.diagnosis.reason;
  // The 2 s window resolves 0.5 Hz only from 2.5 Hz on: still not; 10 s would.
  EXPECT_TRUE(c.faults[0].resolvable);
}

// Outer ring turning at f_r = 25 Hz, inner ring standing: an outer-race spall is struck only
// while it crosses the load zone, so the impacts at BPFO = 130 Hz come in bursts once per
// turn (gain max(0, cos 2 pi f_r t)^2: sidebands at k BPFO -+ m f_r of every order). Its
// +f_r sideband, 155 Hz, lies within 1 % of BPFI = 156 Hz (the stationary inner race needs
// no sideband), and 2 (BPFO + f_r) = 310 Hz is a line too: the BPFI series alone passes. It
// is a line of the stronger BPFO series, so only the outer race is reported.
TEST(FaultEvidence, SidebandOfTheTurningOuterRaceIsNoInnerRaceDefect) {
  BearingFrequencies f;
  f.ball_pass_outer_race_hz = 130.0;
  f.ball_pass_inner_race_hz = 156.0;
  f.ball_spin_hz = 47.3;  // 2 x = 94.6 Hz, away from every line of the train
  f.cage_hz = 10.83;
  f.outer_ring_hz = 25.0;
  f.inner_ring_hz = 0.0;
  f.relative_ring_hz = 25.0;
  f.varying_compliance_hz = 156.0;  // the inner race stands; Z = 14.4 (156 / 10.83)
  const auto x = impact_train(
      130.0, [](int, double t) { return std::pow(std::max(0.0, std::cos(2.0 * kPi * 25.0 * t)), 2); }, 0.05, 2.0, 7);
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& outer = c.faults[0];
  const FaultIndicator& inner = c.faults[1];
  EXPECT_TRUE(outer.sidebands_required);
  EXPECT_GE(outer.sidebands_found, 1);
  EXPECT_TRUE(outer.suspected) << c.diagnosis.reason;
  // The BPFI series has its lines (at the sideband) ...
  EXPECT_TRUE(inner.harmonics[0].found);
  EXPECT_NEAR(inner.envelope_peak.frequency_hz, 155.0, 0.5);
  EXPECT_GE(inner.harmonics_found, 2);
  // ... and is withdrawn as the outer race series' sideband.
  EXPECT_FALSE(inner.suspected);
  EXPECT_NE(inner.note.find("BPFO"), std::string::npos) << inner.note;
  EXPECT_EQ(c.diagnosis.reason.find("inner race"), std::string::npos) << c.diagnosis.reason;
}

// Balls of unequal size strike a stationary outer-race spall unequally; the pattern of
// strengths repeats once per cage turn (Z = 9 impacts), so the envelope carries
// FTF = BPFO / 9 and its harmonics. That line is the outer race series' cage-rate
// modulation, not a second defect.
TEST(FaultEvidence, CageLineBesideAStationaryRaceSeriesIsItsModulation) {
  const double bpfo = 87.3;  // 9 x 9.7 Hz
  BearingFrequencies f = stationary_frequencies();
  f.ball_pass_outer_race_hz = bpfo;
  f.varying_compliance_hz = bpfo;
  const double size_gain[9] = {1.0, 0.6, 0.9, 0.4, 1.0, 0.7, 0.5, 0.8, 0.6};  // per ball
  const auto x = impact_train(
      bpfo, [&](int k, double) { return size_gain[k % 9]; }, 0.05, 2.0, 8);
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& outer = c.faults[0];
  const FaultIndicator& cage = c.faults[3];
  EXPECT_TRUE(outer.suspected) << c.diagnosis.reason;
  // The cage series' own lines are there (fundamental and 2nd harmonic over 12 / 10 dB) ...
  EXPECT_TRUE(cage.harmonics[0].found);
  EXPECT_GE(cage.harmonics_found, 2);
  // ... and read as the outer race series' modulation.
  EXPECT_FALSE(cage.suspected);
  EXPECT_NE(cage.note.find("cage-rate modulation of the BPFO series"), std::string::npos) << cage.note;
  EXPECT_EQ(c.diagnosis.reason.find("cage"), std::string::npos) << c.diagnosis.reason;
}

// The cage-rate comb of a stationary-race spall (rule 8). Balls of unequal size strike a
// stationary outer-race spall in a pattern of 9 strengths g_j that repeats once per cage turn,
// so the envelope is a train of period 1 / f_c: lines at every m f_c (f_c = 9.7 Hz), of
// strength |G_(m mod 9)| / G_0 against the BPFO line (G the DFT of g, G_0 = 0.622): -18.1 dB
// at m = 12 and 24 (k = 3, 6), -16.7 dB at 11, -11.8 dB at 13 (k = 2, 4). 2 x the ball spin
// is 116.6 Hz, 0.2 % from 12 f_c = 116.4 Hz: the ball series finds its fundamental there, its
// 2nd harmonic at 24 f_c and its sidebands at -+f_c on 11 and 13 f_c, and passes alone; every
// one of those lines is the outer race's. (12 is more than 2 lines from 9 and 18 f_c: the ball
// series' -+2 f_c sidebands do not reach BPFO, which rule 6 would withdraw.) The BPFO line
// (0 dB) is the stronger: the ball series is withdrawn.
TEST(FaultEvidence, BallSeriesOnTheCageRateCombOfAStationaryRaceSpallIsNoBallDefect) {
  const double fc = 9.7, bpfo = 9.0 * fc;
  BearingFrequencies f = stationary_frequencies();
  f.ball_pass_outer_race_hz = bpfo;
  f.varying_compliance_hz = bpfo;
  f.ball_spin_hz = 58.3;  // 2 x = 116.6 Hz
  f.cage_hz = fc;
  const double size_gain[9] = {1.0, 0.4, 0.7, 0.3, 0.9, 0.5, 1.0, 0.2, 0.6};  // per ball
  const auto x = impact_train(
      bpfo, [&](int k, double) { return size_gain[k % 9]; }, 0.05, 2.0, 9);
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& outer = c.faults[0];
  const FaultIndicator& ball = c.faults[2];
  ASSERT_EQ(ball.kind, FaultKind::Ball);
  EXPECT_TRUE(outer.suspected) << c.diagnosis.reason;
  // The ball series' own evidence is there, on the comb ...
  EXPECT_NEAR(ball.envelope_peak.frequency_hz, 12.0 * fc, 0.2);
  EXPECT_GE(ball.harmonics_found, 2);
  EXPECT_FALSE(ball.sidebands_required);  // a ball's sidebands support, not required (rule 13)
  EXPECT_GE(ball.sidebands_found, 1);
  EXPECT_LT(ball.envelope_peak.snr_db, outer.envelope_peak.snr_db);
  // ... and withdrawn as the stronger outer race series' cage-rate comb.
  EXPECT_FALSE(ball.suspected);
  EXPECT_NE(ball.note.find("line 12 of the cage-rate comb"), std::string::npos) << ball.note;
  EXPECT_NE(ball.note.find("BPFO"), std::string::npos) << ball.note;
  EXPECT_EQ(c.diagnosis.reason.find("ball"), std::string::npos) << c.diagnosis.reason;
}

// The cage-rate comb of a ball spall (rule 8). The spalled ball is carried through a load zone
// of a quarter of the cage turn (impact strength 1 for |cage angle| < 45 deg, 0.1 outside), so
// its impacts at 2 x the ball spin = 111 Hz are amplitude-modulated by a rectangular wave at
// f_c = 9.7 Hz, whose m-th harmonic is 0.9 sin(m pi / 4) / (m pi): the envelope carries the
// modulation itself, lines at m f_c of 0.025 (m = 9) and 0.018 (m = 18) against the mean 0.325
// (-22, -25 dB). 9 f_c = Z f_c = 87.3 Hz is the stationary outer race's ball pass, whose series
// needs no sideband and sees an impulsive band (the ball's bursts): it passes alone. Every one
// of its lines is the ball series': the BPFO series is withdrawn.
TEST(FaultEvidence, StationaryRaceSeriesOnTheCageRateCombOfABallSpallIsNoRaceDefect) {
  const double fc = 9.7, bsf2 = 111.0;
  BearingFrequencies f = stationary_frequencies();
  f.ball_pass_outer_race_hz = 9.0 * fc;
  f.varying_compliance_hz = 9.0 * fc;
  f.ball_spin_hz = bsf2 / 2.0;
  f.cage_hz = fc;
  const auto x = impact_train(
      bsf2, [&](int, double t) { return std::cos(2.0 * kPi * fc * t) > std::cos(kPi / 4.0) ? 1.0 : 0.1; }, 0.01, 2.0,
      10);
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& outer = c.faults[0];
  const FaultIndicator& ball = c.faults[2];
  EXPECT_TRUE(ball.suspected) << c.diagnosis.reason;
  // The BPFO series' own evidence is there, on the ball's comb (9 and 18 f_c) ...
  EXPECT_NEAR(outer.envelope_peak.frequency_hz, 9.0 * fc, 0.2);
  EXPECT_GE(outer.harmonics_found, 2);
  EXPECT_TRUE(outer.impulsiveness_required);
  EXPECT_TRUE(outer.impulsive);
  EXPECT_LT(outer.envelope_peak.snr_db, ball.envelope_peak.snr_db);
  // ... and withdrawn as the stronger ball series' cage-rate comb.
  EXPECT_FALSE(outer.suspected);
  EXPECT_NE(outer.note.find("line 9 of the cage-rate comb"), std::string::npos) << outer.note;
  EXPECT_NE(outer.note.find("2xBSF"), std::string::npos) << outer.note;
  EXPECT_EQ(c.diagnosis.reason.rfind("ball defect suspected", 0), 0u) << c.diagnosis.reason;
  EXPECT_EQ(c.diagnosis.reason.find("outer race"), std::string::npos) << c.diagnosis.reason;
}

// The healthy compliance's cage-rate comb read as a ball series (rule 5, lines on the comb).
// Balls of unequal size make the ball-pass excitation repeat once per cage turn, so a
// smooth envelope e = 1 + 0.25 (cos 11 p + cos 12 p + cos 13 p + cos 24 p), p = 2 pi f_c t,
// f_c = 9.7 Hz, modulates the 3 kHz resonance under a quiet sensor. 2 x the ball spin is
// 116.6 Hz, 0.2 % from 12 f_c: the ball series finds its fundamental (12 f_c), 2nd harmonic
// (24 f_c) and both sidebands (11, 13 f_c), all on the comb, and passed the old rule (its
// sidebands are required, so impulsiveness was not). The band is not impulsive:
// <e^2> = 1 + 4 x 0.25^2 / 2 = 9/8 and <e^4> = 31/16 (the products 11 + 13 = 12 + 12 = 24 add
// to it), SK = (31/16) / (81/64) - 2 = -0.469 (-38/81), far below 2: not a ball defect.
TEST(FaultEvidence, SmoothCageRateCombAtTwiceTheBallSpinIsHealthy) {
  const double fc = 9.7;
  BearingFrequencies f = stationary_frequencies();
  f.ball_pass_outer_race_hz = 9.0 * fc;
  f.varying_compliance_hz = 9.0 * fc;
  f.ball_spin_hz = 58.3;  // 2 x = 116.6 Hz
  f.cage_hz = fc;
  std::vector<double> x(40000);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 0.02);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / kFs, p = 2.0 * kPi * fc * t;
    const double e = 1.0 + 0.25 * (std::cos(11.0 * p) + std::cos(12.0 * p) + std::cos(13.0 * p) + std::cos(24.0 * p));
    x[i] = e * std::sin(2.0 * kPi * 3000.0 * t) + n(rng);
  }
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& ball = c.faults[2];
  ASSERT_EQ(ball.kind, FaultKind::Ball);
  // The lines are there, on the comb ...
  EXPECT_NEAR(ball.envelope_peak.frequency_hz, 12.0 * fc, 0.2);
  EXPECT_GE(ball.harmonics_found, 2);
  EXPECT_FALSE(ball.sidebands_required);  // a ball's sidebands support, not required (rule 13)
  EXPECT_EQ(ball.sidebands_found, 2);
  EXPECT_NEAR(c.envelope_band_kurtosis, -38.0 / 81.0, 0.1);
  // ... but in a band that is no impact train.
  EXPECT_TRUE(ball.impulsiveness_required);
  EXPECT_FALSE(ball.impulsive);
  EXPECT_FALSE(ball.suspected);
  EXPECT_NE(ball.note.find("cage-rate comb"), std::string::npos) << ball.note;
  EXPECT_EQ(c.diagnosis.level, HealthLevel::Ok) << c.diagnosis.reason;
}

// A series on the skirt of a stronger series' harmonic (rule 9). Outer ring turning at
// f_r = 25 Hz, an outer-race spall struck in the load zone (gain max(0, cos 2 pi f_r t)^2, as
// above) whose impact rate wanders as the cage slip fluctuates: phase 2 pi BPFO t +
// beta sin(2 pi r t), BPFO = 130 Hz, r = 3.5 Hz, beta = 0.25, so the n-th harmonic carries
// FM sidebands n BPFO -+ j r of relative strength J_j(n beta) / J_0(n beta): -11.8 dB at
// 2 BPFO + r = 263.5 Hz (J_1(0.5) / J_0(0.5)), -4.8 dB at 4 BPFO + r = 523.5 Hz. 2 x the ball
// spin is 264.4 Hz: the ball series finds its fundamental at 263.5 Hz (2nd harmonic 523.5
// Hz), and with f_c = 21.5 Hz its +f_c sideband at 285 Hz = 2 BPFO + f_r, a line of the
// outer race's load-zone modulation: it passes. In the 1 s window (1 Hz bins) 263.5 Hz is
// 3.5 bins from the BPFO series' 2nd harmonic, closer than the 5 bins at which two lines are
// resolvable: the ball series is withdrawn.
TEST(FaultEvidence, SeriesOnTheSkirtOfAStrongerHarmonicIsNotResolvable) {
  BearingFrequencies f;
  f.ball_pass_outer_race_hz = 130.0;
  f.ball_pass_inner_race_hz = 156.0;
  f.ball_spin_hz = 132.2;  // 2 x = 264.4 Hz
  f.cage_hz = 21.5;
  f.outer_ring_hz = 25.0;
  f.inner_ring_hz = 0.0;
  f.relative_ring_hz = 25.0;
  f.varying_compliance_hz = 156.0;
  const double wn = 2.0 * kPi * 3000.0, damping = 0.05 * wn, bpfo = 130.0, r = 3.5, beta = 0.25;
  std::vector<double> x(20000);  // 1 s
  std::mt19937_64 rng(12);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / kFs;
    const double cycles = bpfo * t + beta / (2.0 * kPi) * std::sin(2.0 * kPi * r * t);  // impacts so far
    const double since = (cycles - std::floor(cycles)) / bpfo;
    const double gain = std::pow(std::max(0.0, std::cos(2.0 * kPi * 25.0 * t)), 2);
    x[i] = gain * std::exp(-damping * since) * std::sin(wn * since) + noise(rng);
  }
  const ConditionIndicators c = analyze_vibration(x, kFs, f, resonance_band());
  const FaultIndicator& outer = c.faults[0];
  const FaultIndicator& ball = c.faults[2];
  EXPECT_TRUE(outer.suspected) << c.diagnosis.reason;
  ASSERT_GE(outer.harmonics_found, 2);
  EXPECT_NEAR(outer.harmonics[1].peak.frequency_hz, 2.0 * bpfo, 0.3);
  // The ball series' own evidence is there ...
  EXPECT_NEAR(ball.envelope_peak.frequency_hz, 2.0 * bpfo + r, 0.3);
  EXPECT_GE(ball.harmonics_found, 2);
  EXPECT_GE(ball.sidebands_found, 1);
  // ... but 3.5 bins from the stronger series' 2nd harmonic.
  EXPECT_FALSE(ball.suspected);
  EXPECT_NE(ball.note.find("harmonic 2"), std::string::npos) << ball.note;
  EXPECT_NE(ball.note.find("BPFO"), std::string::npos) << ball.note;
  EXPECT_EQ(c.diagnosis.reason.find("ball"), std::string::npos) << c.diagnosis.reason;
}

}  // namespace
}  // namespace bearing_sim
