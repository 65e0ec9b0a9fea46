// Rule 14 of the diagnosis (docs/health.md): a spalled ball struck intermittently, found in
// the times between consecutive impacts where the envelope spectrum finds nothing. Checked
// against closed forms: the Poisson tail, the count of a constructed impact train, the share
// of exponential intervals that falls in the window.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../../src/core/impact_intervals.hpp"
#include "bearing_sim/core/condition_indicators.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

TEST(ImpactIntervals, PoissonUpperTailMatchesTheClosedForms) {
  for (double mean : {0.05, 0.5, 3.0, 17.0}) {
    const double e = std::exp(-mean);
    EXPECT_DOUBLE_EQ(poisson_upper_tail(0, mean), 1.0);
    EXPECT_NEAR(poisson_upper_tail(1, mean), 1.0 - e, 1e-12);
    EXPECT_NEAR(poisson_upper_tail(2, mean), 1.0 - e * (1.0 + mean), 1e-12);
    EXPECT_NEAR(poisson_upper_tail(3, mean), 1.0 - e * (1.0 + mean + 0.5 * mean * mean), 1e-12);
  }
  // Far in the tail the first term dominates: P(N >= k) -> p(k) / (1 - mean / (k + 1)).
  const double mean = 2.0, k = 40.0;
  const double first = std::exp(-mean + k * std::log(mean) - std::lgamma(k + 1.0));
  EXPECT_NEAR(poisson_upper_tail(40, mean) / (first / (1.0 - mean / (k + 1.0))), 1.0, 2e-3);
}

// An envelope of floor 1 +- 10 % with spikes of 10 at given samples.
std::vector<double> spiky_envelope(std::size_t n, const std::vector<std::size_t>& at, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> floor(0.9, 1.1);
  std::vector<double> e(n);
  for (double& v : e) v = floor(*rng);
  for (std::size_t i : at) {  // a burst: up in one sample, down over five
    for (std::size_t j = 0; j < 6 && i + j < n; ++j) e[i + j] = 10.0 * std::exp(-0.5 * j);
  }
  return e;
}

// Runs of strikes exactly one period apart, the runs separated by 3-8 periods: every interval
// within a run is in the window, none between runs is in the neighbourhood (+-28 %).
TEST(ImpactIntervals, CountsTheIntervalsWithinRunsOfStrikes) {
  const double fs = 12000.0, period_s = 0.00708;
  const double period = period_s * fs;
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> run_length(2, 6);
  std::uniform_real_distribution<double> gap(3.0, 8.0);
  std::vector<std::size_t> at;
  std::size_t expected_in_window = 0;
  double t = 10.0;
  while (t < 10.0 * fs - 7.0 * period) {
    const int len = run_length(rng);
    for (int k = 0; k < len; ++k) at.push_back(static_cast<std::size_t>(std::llround(t + k * period)));
    expected_in_window += static_cast<std::size_t>(len - 1);
    t += (len - 1) * period + gap(rng) * period;
  }
  const ImpactIntervals r = impact_intervals(spiky_envelope(static_cast<std::size_t>(10.0 * fs), at, &rng), fs,
                                             period_s, DiagnosisThresholds{});
  EXPECT_EQ(r.impacts, at.size());
  EXPECT_EQ(r.in_window, expected_in_window);
  EXPECT_EQ(r.around, 0u);
  EXPECT_NEAR(r.expected, 0.5 / 3.0, 1e-12);
  EXPECT_NEAR(r.chance, poisson_upper_tail(expected_in_window, 0.5 / 3.0), 1e-15);
  EXPECT_NEAR(r.median_ratio, 1.0, 1.0 / period);  // the strikes rounded to samples
  EXPECT_TRUE(r.found);
}

// A strictly periodic impulsive source near the ball's period (a shaft order 5 x f_r lies 6 %
// from the 6205's 2 x BSF): every interval lies in the +-7 % window, but off its centre by
// more than half the tolerance, so it is not the ball; 2 % off (a ball's slip), it is.
TEST(ImpactIntervals, PeriodicSourceOffTheBallsPeriodIsNotTheBall) {
  const double fs = 12000.0, period_s = 0.00708;
  const double period = period_s * fs;
  for (double ratio : {1.055, 0.945, 1.02}) {
    std::mt19937_64 rng(7);
    std::vector<std::size_t> at;
    for (double t = 10.0; t < 10.0 * fs - 10.0; t += ratio * period) at.push_back(static_cast<std::size_t>(t));
    const ImpactIntervals r = impact_intervals(spiky_envelope(static_cast<std::size_t>(10.0 * fs), at, &rng), fs,
                                               period_s, DiagnosisThresholds{});
    EXPECT_EQ(r.in_window, at.size() - 1) << ratio;
    EXPECT_LT(r.chance, 1e-100) << ratio;
    EXPECT_NEAR(r.median_ratio, ratio, 1.0 / period) << ratio;
    EXPECT_EQ(r.found, std::abs(ratio - 1.0) <= 0.035) << ratio;
  }
}

// Impacts at random times (a Poisson process of the same mean rate): the share of intervals in
// the window is what the density around predicts, nothing is found.
TEST(ImpactIntervals, RandomImpactsAreNoPeriod) {
  const double fs = 12000.0, period_s = 0.00708;
  const double period = period_s * fs;
  std::mt19937_64 rng(5);
  std::exponential_distribution<double> interval(1.0 / period);
  std::vector<std::size_t> at;
  for (double t = 10.0; t < 60.0 * fs - 10.0;) {
    at.push_back(static_cast<std::size_t>(t));
    t += std::max(0.6 * period, interval(rng));  // half a period apart at least, as the picking keeps them
  }
  const ImpactIntervals r = impact_intervals(spiky_envelope(static_cast<std::size_t>(60.0 * fs), at, &rng), fs,
                                             period_s, DiagnosisThresholds{});
  ASSERT_EQ(r.impacts, at.size());
  // Exponential intervals of mean T (the 0.6 T floor is below the neighbourhood): a share
  // e^-0.93 - e^-1.07 in the window; Poisson count, 4 standard deviations.
  const double share = std::exp(-0.93) - std::exp(-1.07);
  const double mean = share * static_cast<double>(r.impacts - 1);
  EXPECT_NEAR(static_cast<double>(r.in_window), mean, 4.0 * std::sqrt(mean));
  EXPECT_NEAR(r.expected, mean, 4.0 * std::sqrt(mean));
  EXPECT_GT(r.chance, 1e-3);
  EXPECT_FALSE(r.found);
}

BearingFrequencies cwru_6205_at(double fr) {
  BearingFrequencies f;
  f.ball_pass_outer_race_hz = 3.5848 * fr;
  f.ball_pass_inner_race_hz = 5.4152 * fr;
  f.ball_spin_hz = 0.5 * 4.7135 * fr;
  f.cage_hz = 0.39828 * fr;
  f.inner_ring_hz = fr;
  f.relative_ring_hz = fr;
  f.varying_compliance_hz = f.ball_pass_outer_race_hz;
  return f;
}

// A spalled ball of the CWRU 6205 at 1772 rpm struck in runs of 2-4 strikes, each run's
// period off 1 / (2 x BSF) by up to +-7 % (the ball's slip), the runs 2-12 periods apart at
// random, each strike of a random strength (log-normal, sigma 0.7: where the pit meets the
// contact) ringing a 3.5 kHz resonance under noise. The 2 x BSF line smears over 14 % and
// the averaged envelope spectrum finds no series (its 2 x BSF line stays under the threshold
// of 19 averaged segments); the intervals name the ball. Without rule 14: nothing.
TEST(ImpactIntervals, IntermittentBallSpallIsNamedFromItsImpactIntervals) {
  const double fs = 12000.0, fr = 1772.0 / 60.0;
  const BearingFrequencies f = cwru_6205_at(fr);
  const double period_s = 1.0 / (2.0 * f.ball_spin_hz);
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> run_length(2, 4);
  std::uniform_real_distribution<double> slip(-0.07, 0.07), gap(2.0, 12.0);
  std::normal_distribution<double> log_strength(0.0, 0.7);
  std::vector<double> impacts, strengths;
  for (double t = 0.01; t < 10.0;) {
    const int len = run_length(rng);
    const double run_period = period_s * (1.0 + slip(rng));
    for (int k = 0; k < len; ++k) {
      impacts.push_back(t + k * run_period);
      strengths.push_back(std::exp(log_strength(rng)));
    }
    t += (len - 1) * run_period + gap(rng) * period_s;
  }
  const double wn = 2.0 * kPi * 3500.0, a = 0.03 * wn;
  std::normal_distribution<double> noise(0.0, 0.2);
  std::vector<double> x(static_cast<std::size_t>(10.0 * fs));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i / fs;
    const auto next = std::upper_bound(impacts.begin(), impacts.end(), t);
    const double ring =
        next == impacts.begin()
            ? 0.0
            : strengths[static_cast<std::size_t>(next - impacts.begin() - 1)] * std::exp(-a * (t - *(next - 1))) *
                  std::sin(wn * (t - *(next - 1)));
    x[i] = ring + noise(rng);
  }
  AnalysisOptions o;
  o.measure_speed = false;  // no shaft lines in this signal
  const ConditionIndicators c = analyze_vibration(x, fs, f, o);
  const FaultIndicator& ball = c.faults[2];
  ASSERT_EQ(ball.kind, FaultKind::Ball);
  EXPECT_TRUE(ball.intervals.tested);
  EXPECT_TRUE(ball.intervals.found) << ball.note;
  EXPECT_TRUE(ball.suspected);
  EXPECT_EQ(c.diagnosis.verdict.outcome, VerdictOutcome::Fault) << c.diagnosis.reason;
  ASSERT_EQ(c.diagnosis.verdict.kinds.size(), 1u);
  EXPECT_EQ(c.diagnosis.verdict.kinds[0], FaultKind::Ball);
  EXPECT_NE(c.diagnosis.reason.find("struck intermittently"), std::string::npos) << c.diagnosis.reason;

  o.thresholds.ball_impact_intervals = false;
  const ConditionIndicators without = analyze_vibration(x, fs, f, o);
  EXPECT_EQ(without.diagnosis.verdict.outcome, VerdictOutcome::None) << without.diagnosis.reason;
  EXPECT_LT(without.faults[2].envelope_peak.snr_db, without.fault_snr_db_used);
  EXPECT_FALSE(without.faults[2].intervals.tested);
}

}  // namespace
}  // namespace bearing_sim
