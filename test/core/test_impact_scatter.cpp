// Impacts that scatter about their periodic grid as real ones do (docs/model.md, section 9):
// the balls' place wander in their cage pockets moves the instants at which they meet a race
// spall, a ball spall's wandering spin axis carries it in and out of the rolling track, and
// a ball's spin slips on each passage through the unloaded arc.
// Checked on the deflection offsets themselves (Imperfections::add_offsets) against the
// process's closed forms.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim {
namespace {

// A 6205-like row: 9 balls of 7.94 mm on a 39.04 mm pitch circle, evenly spaced.
Imperfections::Geometry row_of_nine() {
  Imperfections::Geometry g;
  g.balls_per_row = 9;
  g.rows = 1;
  g.ball_diameter_m = 7.94e-3;
  g.outer_race_radius_m = 0.5 * (39.04e-3 + 7.94e-3);
  g.inner_race_radius_m = 0.5 * (39.04e-3 - 7.94e-3);
  for (int b = 0; b < 9; ++b) g.base_azimuth.push_back(b * kTwoPi / 9.0);
  return g;
}

// The instants at which a ball is centred on an outer-race spall (its dip deepest), with the
// cage turning at a constant rate: every pass of every ball over 20 s of cage turning.
std::vector<double> pass_instants(const ImperfectionSpec& spec, double cage_rad_s, double duration_s, double dt) {
  const Imperfections imp(spec, row_of_nine());
  std::vector<double> out(9), instants;
  double previous_depth = 0.0, previous_previous = 0.0;
  for (double t = 0.0; t < duration_s; t += dt) {
    RollingPhase p;
    p.cage = std::remainder(cage_rad_s * t, kTwoPi);
    p.time_s = t;
    std::fill(out.begin(), out.end(), 0.0);
    imp.add_offsets(p, out.data());
    const double depth = -*std::min_element(out.begin(), out.end());
    // A local maximum of the deepest dip: a ball at the spall's centre (one step early).
    if (previous_depth > depth && previous_depth >= previous_previous && previous_depth > 0.0)
      instants.push_back(t - dt);
    previous_previous = previous_depth;
    previous_depth = depth;
  }
  return instants;
}

Spall outer_spall() {
  Spall s;
  s.surface = Surface::OuterRace;
  s.width_m = 1.0e-3;
  s.depth_m = 20e-6;
  return s;
}

// Ball-pass period T = pitch / cage rate. With a place wander of standard deviation sigma along
// the pitch circle (radius r), each pass is moved by (sigma / r) / cage rate, independently
// from pass to pass once passes are a correlation time apart: residuals about the grid have
// standard deviation (sigma / r) / omega_c, and they do not grow (the grid keeps the mean
// period). 0.25 mm on the 6205 is 1.8 % of the 13.6 mm ball pitch.
TEST(ImpactScatter, PlaceWanderScattersPassesAboutTheirGridWithoutAccumulating) {
  ImperfectionSpec spec;
  spec.seed = 7;
  spec.spalls.push_back(outer_spall());
  spec.ball_place_wander_m = 0.25e-3;
  spec.ball_place_wander_correlation_s = 0.005;  // shorter than a cage turn: passes independent
  const double omega_c = 2.0 * kPi * 12.0, period = kTwoPi / 9.0 / omega_c, duration = 20.0;
  const std::vector<double> t = pass_instants(spec, omega_c, duration, 5e-6);
  ASSERT_GT(t.size(), 2000u);
  // Residuals about the nominal grid k T (a ball at the spall's centre when cage = k pitch).
  std::vector<double> r;
  for (double ti : t) r.push_back(ti - period * std::round(ti / period));
  const auto rms = [](const std::vector<double>& v, std::size_t from, std::size_t to) {
    double s = 0.0;
    for (std::size_t i = from; i < to; ++i) s += v[i] * v[i];
    return std::sqrt(s / static_cast<double>(to - from));
  };
  const double pitch_radius = 0.5 * 39.04e-3;
  const double expected = spec.ball_place_wander_m / pitch_radius / omega_c;
  const std::size_t n = r.size();
  // ~2160 passes: the sample RMS of n normal values has a relative standard error 1/sqrt(2n),
  // 1.5 %; the bound (0.45 pitch less half the spall's width, 23 sigma) cuts nothing; the
  // 5 us step reads the instants to 2.5e-6 s (0.7 % of the 0.36 ms scatter).
  EXPECT_NEAR(rms(r, 0, n), expected, 0.06 * expected);
  EXPECT_GT(expected / period, 0.015);  // the scatter asked for: 1.8 % of the period
  // Not accumulating: the last quarter's scatter is the first quarter's (a random walk's
  // would be sqrt(7) times larger at the end than over the first quarter).
  EXPECT_NEAR(rms(r, 3 * n / 4, n) / rms(r, 0, n / 4), 1.0, 0.15);
  // Without wander every pass is on the grid (to the 5 us step).
  spec.ball_place_wander_m = 0.0;
  const std::vector<double> exact = pass_instants(spec, omega_c, 1.0, 5e-6);
  ASSERT_GT(exact.size(), 100u);
  for (double ti : exact) EXPECT_NEAR(ti, period * std::round(ti / period), 6e-6);
}

// Ball 0's spall of half width `half_width` (angle on the ball) is struck at time t: it dips
// the ball somewhere in a spin turn (the spin angle swept in steps of a tenth of its width,
// time held: the latitude at t).
bool ball_spall_struck_at(const Imperfections& imp, double half_width, double t) {
  std::vector<double> out(9);
  for (double spin = 0.0; spin < kTwoPi; spin += 0.1 * 2.0 * half_width) {
    RollingPhase p;
    p.time_s = t;
    p.ball_spin = spin;
    std::fill(out.begin(), out.end(), 0.0);
    imp.add_offsets(p, out.data());
    if (out[0] < 0.0) return true;
  }
  return false;
}

// Ball 0 of a row of nine with a spall 0.5 mm wide and 20 um deep; its half width as an
// angle on the ball (7.94 mm).
constexpr double kBallSpallWidthM = 0.5e-3;
constexpr double kBallSpallHalfWidth = 0.5 * kBallSpallWidthM / (0.5 * 7.94e-3);
ImperfectionSpec one_ball_spall(std::uint64_t seed) {
  ImperfectionSpec spec;
  spec.seed = seed;
  Spall s;
  s.surface = Surface::Ball;
  s.ball = 0;
  s.width_m = kBallSpallWidthM;
  s.depth_m = 20e-6;
  spec.spalls.push_back(s);
  return spec;
}

// The share of `draws` instants a correlation time (0.1 s) apart, independent, at which the
// spall is struck.
double struck_share(const Imperfections& imp, int draws) {
  int struck = 0;
  for (int k = 0; k < draws; ++k) struck += ball_spall_struck_at(imp, kBallSpallHalfWidth, 0.1 * k + 0.05) ? 1 : 0;
  return static_cast<double>(struck) / draws;
}

// A ball spall of half width h (angle on the ball) whose latitude wanders as a stationary
// Gaussian of standard deviation s is struck while |latitude| < h: a share erf(h / (s sqrt 2))
// of the time. Sampled at 4000 instants a correlation time apart (independent): binomial
// standard error sqrt(p (1 - p) / 4000) = 0.8 %; 3 % is about four of them.
TEST(ImpactScatter, WanderingSpinAxisStrikesTheShareOfTimeTheLatitudeIsOnTheSpall) {
  ImperfectionSpec spec = one_ball_spall(3);
  spec.ball_spin_axis_wander_rad = 1.5 * kBallSpallHalfWidth;
  spec.ball_spin_axis_wander_correlation_s = 0.1;
  const double expected = std::erf(1.0 / (1.5 * std::sqrt(2.0)));
  EXPECT_NEAR(struck_share(Imperfections(spec, row_of_nine()), 4000), expected, 0.03);
  // Without wander: always struck.
  spec.ball_spin_axis_wander_rad = 0.0;
  EXPECT_EQ(struck_share(Imperfections(spec, row_of_nine()), 20), 1.0);
}

// The same spall left by the assembly at a mean latitude L off the track, wandering about it:
// struck while |L + s Z| < h, a share Phi((h - L) / s) - Phi((-h - L) / s) of the time
// (Z standard normal). Sampled as above (binomial standard error <= 0.8 %; 3 %). Without
// wander, a spall off the track (L > h, no rim) is never struck, one on it always.
TEST(ImpactScatter, ASpallLeftOffTheTrackIsStruckOnlyWhileTheWanderBringsItBack) {
  ImperfectionSpec spec = one_ball_spall(5);
  const auto phi = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  spec.ball_spall_latitude_rad = 1.5 * kBallSpallHalfWidth;
  spec.ball_spin_axis_wander_rad = 1.0 * kBallSpallHalfWidth;
  spec.ball_spin_axis_wander_correlation_s = 0.1;
  const double expected = phi((1.0 - 1.5) / 1.0) - phi((-1.0 - 1.5) / 1.0);  // 0.302
  EXPECT_NEAR(struck_share(Imperfections(spec, row_of_nine()), 4000), expected, 0.03);
  spec.ball_spin_axis_wander_rad = 0.0;
  EXPECT_EQ(struck_share(Imperfections(spec, row_of_nine()), 20), 0.0);  // off the track
  spec.ball_spall_latitude_rad = 0.5 * kBallSpallHalfWidth;
  EXPECT_EQ(struck_share(Imperfections(spec, row_of_nine()), 20), 1.0);  // on it
}

// The spin angle at which ball 0's spall is deepest at `phase` (the spin swept over the half
// turn in which the spall meets a race, time and cage held), from the dip's centroid on the
// circle of doubled angles (the dip repeats every half turn), in [-pi/2, pi/2).
double ball_spall_centre(const Imperfections& imp, RollingPhase phase) {
  constexpr int kSteps = 4000;
  std::vector<double> out(9);
  double c = 0.0, s = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    phase.ball_spin = kPi * i / kSteps;
    std::fill(out.begin(), out.end(), 0.0);
    imp.add_offsets(phase, out.data());
    c += -out[0] * std::cos(2.0 * phase.ball_spin);
    s += -out[0] * std::sin(2.0 * phase.ball_spin);
  }
  return 0.5 * std::atan2(s, c);
}

RollingPhase at_cage(double cage, std::int64_t turns) {
  RollingPhase p;
  p.cage = cage;
  p.cage_turns = turns;
  return p;
}

// A ball's spin slips by an independent angle of standard deviation sigma on each passage
// through the middle of the unloaded arc (azimuth pi here; ball 0 sits at azimuth 0 at cage
// angle 0), and nothing pulls it back: the spall's phase after k passages has moved by a
// random walk's k sigma^2 of variance, and not at all within a passage. Over 1500 seeds the
// sample variance has a relative standard error sqrt(2 / 1500) = 3.7 %; 12 % is three of them
// and more. A walk's 9 passages hold 9 times the variance of one (a phase drawn anew on each
// passage, not accumulating, would give the same variance after 1 and 9).
TEST(ImpactScatter, SpinSlipIsARandomWalkOverThePassagesThroughTheUnloadedArc) {
  const double sigma = 4.0 * kPi / 180.0;
  Spall s;
  s.surface = Surface::Ball;
  s.ball = 0;
  s.width_m = 0.5e-3;
  s.depth_m = 20e-6;
  const int seeds = 1500;
  double sum1 = 0.0, sum_sq1 = 0.0, sum9 = 0.0, sum_sq9 = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    ImperfectionSpec spec;
    spec.seed = static_cast<std::uint64_t>(seed);
    spec.spalls.push_back(s);
    spec.ball_spin_slip_rad = sigma;
    const Imperfections imp(spec, row_of_nine());
    // Passage -1 (ball 0 before the first middle of the unloaded arc), 0 and 8.
    const double before = ball_spall_centre(imp, at_cage(0.0, 0));
    const double after_one = ball_spall_centre(imp, at_cage(0.0, 1));
    const double after_nine = ball_spall_centre(imp, at_cage(0.0, 9));
    if (seed <= 20) {
      // Within a passage (the ball from azimuth 0 to just short of pi) nothing moves; just past
      // pi it is the next passage's; a wrapped turn is a counted turn.
      EXPECT_EQ(ball_spall_centre(imp, at_cage(3.1, 0)), before);
      EXPECT_EQ(ball_spall_centre(imp, at_cage(3.2, 0)), after_one);
      EXPECT_NEAR(ball_spall_centre(imp, at_cage(0.5 + kTwoPi, 8)), ball_spall_centre(imp, at_cage(0.5, 9)), 1e-12);
    }
    const double d1 = std::remainder(after_one - before, kPi), d9 = std::remainder(after_nine - before, kPi);
    sum1 += d1;
    sum_sq1 += d1 * d1;
    sum9 += d9;
    sum_sq9 += d9 * d9;
  }
  const double var1 = sum_sq1 / seeds, var9 = sum_sq9 / seeds;
  EXPECT_NEAR(var1, sigma * sigma, 0.12 * sigma * sigma);
  EXPECT_NEAR(var9, 9.0 * sigma * sigma, 0.12 * 9.0 * sigma * sigma);
  // No drift: the means within four standard errors of 0.
  EXPECT_NEAR(sum1 / seeds, 0.0, 4.0 * sigma / std::sqrt(seeds));
  EXPECT_NEAR(sum9 / seeds, 0.0, 4.0 * 3.0 * sigma / std::sqrt(seeds));
  // Without slip the spall keeps its phase over any number of passages, and the offsets are
  // those of a spec without the keys, bit for bit.
  ImperfectionSpec spec;
  spec.seed = 5;
  spec.spalls.push_back(s);
  const Imperfections plain(spec, row_of_nine());
  spec.ball_spin_slip_azimuth_rad = 1.0;
  const Imperfections zero_slip(spec, row_of_nine());
  EXPECT_EQ(ball_spall_centre(zero_slip, at_cage(0.0, 9)), ball_spall_centre(plain, at_cage(0.0, 0)));
  for (int k = 0; k < 50; ++k) {
    RollingPhase p = at_cage(0.1 * k, k);
    p.ball_spin = 0.37 * k;
    std::vector<double> a(9, 0.0), b(9, 0.0);
    plain.add_offsets(p, a.data());
    zero_slip.add_offsets(p, b.data());
    EXPECT_EQ(a, b);
  }
}

}  // namespace
}  // namespace bearing_sim
