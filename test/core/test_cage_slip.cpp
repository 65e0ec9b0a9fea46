// Cage slip and ball-spacing scatter (imperfections): slip lowers the cage speed and so
// moves the ball-pass lines, as in real bearings; scatter moves the balls off even spacing.
// Also a known limit of the roughness model, kept visible: a frozen 1-D race profile with
// evenly spaced balls repeats at the ball-pass frequency.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/simulation_run.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::bearing_6205;
using test::fault;

constexpr double kRateHz = 40000.0;
constexpr double kSpeedRadS = 1800.0 * 2.0 * test::kPi / 60.0;

ConditionIndicators analyze(const BearingModel& model) {
  SimulationRequest r;
  r.load = test::load5(1000.0, 0.0, 200.0, 0.0, 0.0);
  r.ring_speed_rad_s = kSpeedRadS;
  r.duration_s = 1.0;
  r.sample_rate_hz = kRateHz;
  std::vector<double> ax;
  run_simulation(model, r, [&ax](const DynamicSample& s) { ax.push_back(s.acceleration[0]); });
  AnalysisOptions o;
  o.window_s = 0.8;                    // start-up transient excluded
  o.peak_search.tolerance_rel = 0.05;  // let the search see a slipped line
  return analyze_vibration(ax, kRateHz, bearing_frequencies(model, kSpeedRadS), o);
}

TEST(CageSlip, SlipLowersTheOuterRaceBallPassLineByTheSlip) {
  const std::string spall = "defects: [{surface: outer_race, position_deg: 0, width_mm: 1.0, depth_um: 30}]\n";
  const BearingModel model = bearing_6205(spall + "imperfections: {cage_slip_percent: 3.0}\n");
  const double bpfo = bearing_frequencies(model, kSpeedRadS).ball_pass_outer_race_hz;
  const SpectralPeak peak =
      fault(analyze(model), FaultKind::OuterRace).envelope_peak;  // a copy: the analysis is a temporary
  // Outer race fixed: BPFO = Z f_c, and the cage turns 3% slower. One bin is 1.25 Hz
  // (0.8 s); the interpolated peak is good to a fraction of it.
  EXPECT_NEAR(peak.frequency_hz, 0.97 * bpfo, 0.6);
  EXPECT_GT(peak.snr_db, 10.0);
}

// The dynamics wraps the cage angle every sample and counts the turns it takes off: angle
// plus 2 pi turns is the slipping cage's rate times the time (the balls' passages through the
// unloaded arc are counted on it, docs/model.md 9.5). 1 s at 1800 rpm: ~11.6 turns.
TEST(CageSlip, TheDynamicsCountsTheCageTurnsItWraps) {
  const BearingModel model = bearing_6205("imperfections: {cage_slip_percent: 3.0}\n");
  BearingDynamics dynamics(model, test::load5(1000.0, 0.0, 200.0, 0.0, 0.0), kSpeedRadS, DynamicsOptions{20000.0, 0});
  for (int i = 0; i < 20000; ++i) dynamics.step();
  const RollingPhase& p = dynamics.phase();
  const double unwrapped = p.cage + 2.0 * test::kPi * static_cast<double>(p.cage_turns);
  const double expected = 0.97 * dynamics.cage_speed_rad_s() * p.time_s;
  EXPECT_NEAR(p.time_s, 1.0, 1e-12);
  EXPECT_GE(p.cage_turns, 11);
  EXPECT_LE(std::abs(p.cage), test::kPi);
  // 20000 sums of an advance and a wrap, each rounded to ~1e-15 rad.
  EXPECT_NEAR(unwrapped, expected, 1e-9);
}

TEST(CageSlip, BallSpacingScatterHasTheConfiguredSpread) {
  const BearingModel even = bearing_6205("");
  const BearingModel scattered = bearing_6205("imperfections: {seed: 4, ball_spacing_jitter_mm: 0.2}\n");
  double sum_sq = 0.0;
  for (int b = 0; b < even.ball_count(); ++b) {
    const double arc = std::remainder(scattered.base_azimuth_rad(b) - even.base_azimuth_rad(b), 2.0 * test::kPi) *
                       even.pitch_radius_m();
    sum_sq += arc * arc;
  }
  const double rms_mm = std::sqrt(sum_sq / even.ball_count()) * 1e3;
  // 9 draws: the sample RMS of a normal variable lies within [0.35, 1.65] sigma with
  // probability > 99.9% (chi-square, 9 degrees of freedom); the seed is fixed anyway.
  EXPECT_GT(rms_mm, 0.35 * 0.2);
  EXPECT_LT(rms_mm, 1.65 * 0.2);
  EXPECT_GT(rms_mm, 0.0);
}

TEST(RoughnessModelLimit, FrozenProfileWithEvenSpacingRingsAtTheBallPass) {
  // Documented in docs/health.md: do not use roughness alone as a "healthy" reference for
  // envelope analysis. If this stops holding, the roughness model has changed: update the docs.
  const ConditionIndicators c = analyze(bearing_6205("imperfections: {seed: 3, roughness_rms_um: 0.1}\n"));
  const double worst = std::max(fault(c, FaultKind::OuterRace).envelope_peak.snr_db,
                                fault(c, FaultKind::InnerRace).envelope_peak.snr_db);
  EXPECT_GE(worst, 10.0);
}

}  // namespace
}  // namespace bearing_sim
