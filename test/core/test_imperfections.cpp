// Distributed imperfections and spalls (docs/model.md section 9) against the classic waviness
// rules, closed-form deflection changes and the determinism the datasets rely on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

// 6205-size deep groove bearing, inner ring rotating, 0.5 kg on it.
constexpr int kBalls = 9;
const std::string kDynamics =
    "rotating_ring: inner\n"
    "rotating_mass_kg: 0.5\n"
    "tilt_inertia_kg_m2: 1.0e-4\n"
    "damping: {contact_damping_Ns_per_m: 150.0}\n";
constexpr double kInnerRpm = 1800.0;
constexpr double kSampleRateHz = 20000.0;

BearingConfig deep_groove(const std::string& extra, double clearance_um = 0.0) {
  return test::single_row(kBalls, 7.94, 39.04, 0.0, 0.52, 0.52, clearance_um, kDynamics + extra);
}

// Radial (x) acceleration over the second half of a run under a radial load along x.
std::vector<double> radial_acceleration(const BearingConfig& config, double duration_s, double radial_load_N = 1000.0) {
  const BearingModel model(config);
  BearingDynamics dynamics(model, test::load5(radial_load_N, 0, 0, 0, 0), kInnerRpm * 2.0 * kPi / 60.0,
                           DynamicsOptions{kSampleRateHz, 0});
  const int n = static_cast<int>(duration_s * kSampleRateHz);
  std::vector<double> ax;
  for (int i = 0; i < n; ++i) {
    const DynamicSample s = dynamics.step();
    if (i >= n / 2) ax.push_back(s.acceleration[0]);
  }
  return ax;
}

std::string inner_waviness(int order, double amplitude_um) {
  return "imperfections:\n  waviness:\n    - {surface: inner_race, order: " + std::to_string(order) +
         ", amplitude_um: " + std::to_string(amplitude_um) + "}\n";
}

// The waviness response alone: the run with waviness minus the smooth run (both are
// deterministic, so the varying-compliance lines cancel).
std::vector<double> waviness_response(int order, double clearance_um = 0.0, double radial_load_N = 1000.0) {
  const std::vector<double> smooth = radial_acceleration(deep_groove("", clearance_um), 0.5, radial_load_N);
  std::vector<double> wavy =
      radial_acceleration(deep_groove(inner_waviness(order, 0.5), clearance_um), 0.5, radial_load_N);
  for (std::size_t i = 0; i < wavy.size(); ++i) wavy[i] -= smooth[i];
  return wavy;
}

TEST(Waviness, InnerRaceOrdersZPlusMinusOneExciteThePredictedRadialFrequencies) {
  const BearingModel model(deep_groove(""));
  const double fi = kInnerRpm / 60.0;
  const double fc = bearing_frequencies(model, fi * 2.0 * kPi, 0.0).cage_hz;
  // docs/model.md section 8.2: q = kZ - 1 at |kZ (f_c - f_r) + f_r|, q = kZ + 1 at |kZ (f_c - f_r) - f_r|.
  const double expected_minus = std::abs(kBalls * (fc - fi) + fi);  // q = Z - 1: 132.4 Hz
  const double expected_plus = std::abs(kBalls * (fc - fi) - fi);   // q = Z + 1: 192.4 Hz
  // The 0.25 s window resolves 4 Hz; the peak search grid is 1 Hz, so 4 Hz is one bin.
  const double peak_minus = test::spectral_peak_hz(waviness_response(kBalls - 1), kSampleRateHz, 20.0, 1000.0, 1.0);
  const double peak_plus = test::spectral_peak_hz(waviness_response(kBalls + 1), kSampleRateHz, 20.0, 1000.0, 1.0);
  EXPECT_NEAR(peak_minus, expected_minus, 4.0);
  EXPECT_NEAR(peak_plus, expected_plus, 4.0);
}

TEST(Waviness, WithEveryBallLoadedOrdersOtherThanZPlusMinusOneGiveNoRadialForce) {
  // The rule assumes every ball is loaded alike: 5 um preload and a light 100 N radial
  // load. (In a half-loaded bearing the load zone's own harmonics let other orders through.)
  // q = Z + 3 is not kZ +- 1, so the ball forces cancel around the row; its would-be line,
  // carried by the 2nd harmonic of the load distribution, is |Z (f_c - f_r) - 3 f_r|.
  const double fi = kInnerRpm / 60.0;
  const BearingModel model(deep_groove(""));
  const double fc = bearing_frequencies(model, fi * 2.0 * kPi, 0.0).cage_hz;
  const std::vector<double> plus_one = waviness_response(kBalls + 1, -5.0, 100.0);
  const std::vector<double> plus_three = waviness_response(kBalls + 3, -5.0, 100.0);
  const double line_plus_one = test::dft_amplitude(plus_one, kSampleRateHz, std::abs(kBalls * (fc - fi) - fi));
  const double line_plus_three = test::dft_amplitude(plus_three, kSampleRateHz, std::abs(kBalls * (fc - fi) - 3 * fi));
  // Same amplitude on the race; only the small unevenness of the preloaded ball loads
  // leaks a radial force for q = Z + 3: require it 10x weaker.
  EXPECT_LT(line_plus_three, 0.1 * line_plus_one);
}

TEST(Spall, ABallOverARaceSpallLosesTheEffectiveDepth) {
  // Outer race spall 2 mm wide, 5 um deep, centred under ball 0 (azimuth 0, load side).
  BearingConfig healthy = deep_groove("");
  BearingConfig spalled =
      deep_groove("defects:\n  - {surface: outer_race, position_deg: 0, width_mm: 2.0, depth_um: 5}\n");
  const BearingModel a(healthy), b(spalled);
  const Vector5 q = solve_static(a, test::load5(1000.0, 0, 0, 0, 0)).displacement;
  const std::vector<BallState> before = a.ball_states(q, 0.0), after = b.ball_states(q, 0.0);
  // At the same ring position only the ball over the spall changes, by the full depth:
  // the half-sine dip is at its maximum at the centre, and 5 um < w^2/(4d) = 126 um.
  EXPECT_NEAR(before[0].deflection_m - after[0].deflection_m, 5e-6, 1e-12);
  for (int j = 1; j < kBalls; ++j) EXPECT_DOUBLE_EQ(before[j].deflection_m, after[j].deflection_m);
}

TEST(Spall, AShallowWideSpallIsLimitedByHowFarTheBallCanDrop) {
  // A 0.5 mm wide, 50 um deep spall: the ball rests on both edges, where the gap between the
  // ball (radius r) and the race (radius R at the contact) across w is w^2 / 8 (1 / r - 1 / R)
  // on the outer race, which curves towards the ball (6.54 um), w^2 / 8 (1 / r + 1 / R) on the
  // inner race (9.88 um); w^2 / (4 d) = 7.87 um on a flat one.
  const double w = 0.5e-3, r = 0.5 * 7.94e-3, dm = 39.04e-3;
  const BearingModel a(deep_groove(""));
  const Vector5 q = solve_static(a, test::load5(1000.0, 0, 0, 0, 0)).displacement;
  for (const char* race : {"outer_race", "inner_race"}) {
    const BearingModel b(deep_groove(std::string("defects:\n  - {surface: ") + race +
                                     ", position_deg: 0, width_mm: 0.5, depth_um: 50}\n"));
    const double drop = a.ball_states(q, 0.0)[0].deflection_m - b.ball_states(q, 0.0)[0].deflection_m;
    const bool outer = race[0] == 'o';
    const double race_radius = outer ? 0.5 * dm + r : 0.5 * dm - r;  // contact angle 0
    EXPECT_NEAR(drop, w * w / 8.0 * (1.0 / r + (outer ? -1.0 : 1.0) / race_radius), 1e-12) << race;
  }
}

// A sharp-edged pit (an EDM fault: 0.021 in wide, 0.011 in deep) in the outer race under ball
// 0: the ball pivots on the nearer edge, so its centre drops as the exact geometry of the ball
// (radius r) touching the edge of the race (radius R) has it: at an angle D = u / R from the
// edge (u = w/2 - |s| its distance along the race from that edge, s from the centre) its centre
// lies R cos D - sqrt(r^2 - R^2 sin^2 D) from the race's centre, against R - r on the intact
// race; deepest, w^2 / 8 (1 / r - 1 / R), at the centre where it rests on both. The model's
// parabola u^2 / 2 (1 / r - 1 / R) is that to 0.13 % here (u <= w / 2 = 0.27 mm, r = 3.97 mm,
// R = 23.5 mm): tolerance 0.2 % of the drop. Past the edge nothing changes.
TEST(Spall, ABallOverASharpEdgedSpallDropsAsItPivotsOnTheNearerEdge) {
  const double w = 0.5334e-3, r = 0.5 * 7.94e-3;
  const double outer_race_radius = 0.5 * (39.04e-3 + 7.94e-3);  // dm / 2 + d / 2 (contact angle 0)
  const BearingModel a(deep_groove(""));
  const BearingModel b(
      deep_groove("imperfections: {spall_edges: sharp}\n"
                  "defects:\n  - {surface: outer_race, position_deg: 0, width_mm: 0.5334, depth_um: 279.4}\n"));
  const Vector5 q = solve_static(a, test::load5(1000.0, 0, 0, 0, 0)).displacement;
  for (const double f : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, -0.6}) {
    const double s = f * 0.5 * w;  // along the race from the pit's centre
    const double cage = s / outer_race_radius;
    const double drop = a.ball_states(q, cage)[0].deflection_m - b.ball_states(q, cage)[0].deflection_m;
    const double angle = (0.5 * w - std::abs(s)) / outer_race_radius, R = outer_race_radius;
    const double exact = R * std::cos(angle) - std::sqrt(r * r - R * R * std::sin(angle) * std::sin(angle)) - (R - r);
    EXPECT_NEAR(drop, exact, 2e-3 * exact) << "at " << f << " of the half width";
  }
  EXPECT_NEAR(a.ball_states(q, 0.0)[0].deflection_m - b.ball_states(q, 0.0)[0].deflection_m,
              w * w / 8.0 * (1.0 / r - 1.0 / outer_race_radius), 1e-12);
  const double past = 0.51 * w / outer_race_radius;
  EXPECT_DOUBLE_EQ(a.ball_states(q, past)[0].deflection_m, b.ball_states(q, past)[0].deflection_m);
}

TEST(Spall, ASharpEdgedSpallShallowerThanTheBallCanDropHasAFlatFloor) {
  // 2 mm wide, 5 um deep: resting on both edges the ball would drop
  // D = w^2 / 8 (1 / r - 1 / R) = 105 um; it reaches the floor, 5 um, wherever the pivoting
  // drop (1 - 2|x|/w)^2 D exceeds it, and drops less only within 0.22 (= sqrt(5 / 105)) of the
  // half width from the edges.
  const BearingModel a(deep_groove(""));
  const BearingModel b(
      deep_groove("imperfections: {spall_edges: sharp}\n"
                  "defects:\n  - {surface: outer_race, position_deg: 0, width_mm: 2.0, depth_um: 5}\n"));
  const Vector5 q = solve_static(a, test::load5(1000.0, 0, 0, 0, 0)).displacement;
  const double outer_race_radius = 0.5 * (39.04e-3 + 7.94e-3), d = 7.94e-3, w = 2e-3;
  for (const double f : {0.0, 0.5, 0.79, 0.9}) {
    const double cage = f * 0.5 * w / outer_race_radius;
    const double drop = a.ball_states(q, cage)[0].deflection_m - b.ball_states(q, cage)[0].deflection_m;
    const double u = 1.0 - f, full_drop = w * w / 8.0 * (2.0 / d - 1.0 / outer_race_radius);
    EXPECT_NEAR(drop, std::min(5e-6, full_drop * u * u), 1e-12) << "at " << f << " of the half width";
  }
}

// A round pit (an EDM hole, 0.5334 mm across, 279.4 um deep) under ball 0 of a bearing whose
// grooves' radii are 0.52 d: across the track the groove nearly conforms to the ball, the gap
// between them y^2 / 2 (2 / d - 1 / (0.52 d)) at a distance y from the contact's centre line, so
// the ball rests on the pit's sides after w^2 / 8 (2 / d - 1 / (0.52 d)) = 0.34 um, long before
// it would rest on its edges along the track (7.4 um in the outer race, 11.2 um in the inner).
// Near an edge, where the pivoting drop along the track is the smaller, that one holds.
TEST(Spall, ABallOverARoundPitRestsOnItsSidesAcrossTheTrack) {
  const double w = 0.5334e-3, d = 7.94e-3, dm = 39.04e-3;
  const double across = w * w / 8.0 * (2.0 / d - 1.0 / (0.52 * d));
  const BearingModel a(deep_groove(""));
  const Vector5 q = solve_static(a, test::load5(1000.0, 0, 0, 0, 0)).displacement;
  for (const char* race : {"outer_race", "inner_race"}) {
    const BearingModel b(deep_groove(std::string("imperfections: {spall_edges: sharp, spall_pits: round}\n"
                                                 "defects:\n  - {surface: ") +
                                     race + ", position_deg: 0, width_mm: 0.5334, depth_um: 279.4}\n"));
    EXPECT_NEAR(a.ball_states(q, 0.0)[0].deflection_m - b.ball_states(q, 0.0)[0].deflection_m, across, 1e-12) << race;
  }
  // Along the outer race (radius R at the contact): the smaller of the two drops.
  const double R = 0.5 * (dm + d), along = w * w / 8.0 * (2.0 / d - 1.0 / R);
  const BearingModel b(
      deep_groove("imperfections: {spall_edges: sharp, spall_pits: round}\n"
                  "defects:\n  - {surface: outer_race, position_deg: 0, width_mm: 0.5334, depth_um: 279.4}\n"));
  for (const double f : {0.5, 0.9, 0.97}) {
    const double cage = f * 0.5 * w / R, u = 1.0 - f;
    EXPECT_NEAR(a.ball_states(q, cage)[0].deflection_m - b.ball_states(q, cage)[0].deflection_m,
                std::min(across, along * u * u), 1e-12)
        << "at " << f << " of the half width";
  }
}

// Its recast rim, 1 um high and 100 um wide, a ring round the pit whose crest circles it at
// c = (w + b) / 2: the ball gains the rim's height on the crest, c from the centre along the
// track. Nearer the centre it rides the crest where the ring passes beside it, y = sqrt(c^2 - x^2)
// across, and keeps h - y^2 / 2 (2 / d - 1 / (0.52 d)) of the lift: 0.51 um over the centre,
// nearly all of it over the ring's inner flank. Past the rim nothing changes. A trench-shaped
// pit with the same rim drops the ball along the track as without one, and its rim is a bump
// beside each edge: halfway down the inner flank it keeps half the height (sin^2).
TEST(Spall, ARoundPitsRecastRimLiftsTheBallOnItsCrestAndOverThePit) {
  const double w = 0.5334e-3, b = 100e-6, h = 1e-6, d = 7.94e-3, R = 0.5 * (39.04e-3 + 7.94e-3);
  const double c = 0.5 * (w + b), across_curvature = 2.0 / d - 1.0 / (0.52 * d);
  const std::string pit = "defects:\n  - {surface: outer_race, position_deg: 0, width_mm: 0.5334, depth_um: 279.4}\n";
  const BearingModel a(deep_groove(""));
  const BearingModel round(deep_groove(
      "imperfections: {spall_edges: sharp, spall_pits: round, spall_rim_height_um: 1, spall_rim_width_um: 100}\n" +
      pit));
  const BearingModel trench(
      deep_groove("imperfections: {spall_edges: sharp, spall_rim_height_um: 1, spall_rim_width_um: 100}\n" + pit));
  const Vector5 q = solve_static(a, test::load5(1000.0, 0, 0, 0, 0)).displacement;
  const auto drop = [&](const BearingModel& m, double along_m) {
    return a.ball_states(q, along_m / R)[0].deflection_m - m.ball_states(q, along_m / R)[0].deflection_m;
  };
  for (const double x : {0.0, 0.3 * w, 0.5 * w, 0.5 * w + 0.25 * b})
    EXPECT_NEAR(drop(round, -x), 0.5 * (c * c - x * x) * across_curvature - h, 1e-12) << "at " << x * 1e6 << " um";
  EXPECT_NEAR(drop(trench, 0.0), w * w / 8.0 * (2.0 / d - 1.0 / R), 1e-12);
  EXPECT_NEAR(drop(trench, -0.5 * w - 0.25 * b), -0.5 * h, 1e-12);  // halfway down the rim's inner flank
  for (const BearingModel* m : {&round, &trench}) {
    EXPECT_NEAR(drop(*m, 0.5 * w + 0.5 * b), -h, 1e-12);          // the crest
    EXPECT_NEAR(drop(*m, -0.5 * w - 0.75 * b), -0.5 * h, 1e-12);  // halfway down its outer flank, sin^2
    EXPECT_DOUBLE_EQ(drop(*m, 0.5 * w + 1.01 * b), 0.0);          // past it
  }
}

// The same pit and ring on ball 0, its spin axis still: every spin turn the pit meets the outer
// race and then the inner, each time along its centre line. Each meeting is one lift with no
// break in it: up the ring's outer flank to h on the crest, and between the two crests never
// below h - (w + b)^2 / 8 (2 / d - 1 / (0.52 d)) (both grooves 0.52 d here), its value over the
// pit's centre. Spin sampled every 2 pi / 400000 rad (0.31 um on the ball's surface): the crest
// is missed by at most 3.5e-12 m (h sin^2 near its top), the centre by less.
TEST(Spall, ABallPitsRingHoldsTheBallUpOverThePitOnEitherRace) {
  const double w = 0.5334e-3, b = 100e-6, h = 1e-6, d = 7.94e-3;
  const double centre_lift = h - (w + b) * (w + b) / 8.0 * (2.0 / d - 1.0 / (0.52 * d));
  const BearingModel m(
      deep_groove("imperfections: {spall_edges: sharp, spall_pits: round, spall_rim_height_um: 1, "
                  "spall_rim_width_um: 100}\n"
                  "defects:\n  - {surface: ball, ball: 0, position_deg: 0, width_mm: 0.5334, depth_um: 279.4}\n"));
  constexpr int kSteps = 400000;
  std::vector<double> lift(kSteps);
  std::vector<double> out(m.ball_count());
  for (int i = 0; i < kSteps; ++i) {
    RollingPhase phase;
    phase.ball_spin = 2.0 * kPi * i / kSteps;
    std::fill(out.begin(), out.end(), 0.0);
    m.imperfections().add_offsets(phase, out.data());
    lift[i] = out[0];
  }
  // The meetings: runs of positive lift, the turn's start joined to its end.
  int start = 0;
  while (lift[start] > 0.0) ++start;
  std::vector<std::vector<double>> meetings;
  for (int k = 0; k < kSteps; ++k) {
    const double v = lift[(start + k) % kSteps];
    if (v > 0.0 && (k == 0 || !(lift[(start + k - 1) % kSteps] > 0.0))) meetings.emplace_back();
    if (v > 0.0) meetings.back().push_back(v);
  }
  ASSERT_EQ(meetings.size(), 2u);
  for (const std::vector<double>& v : meetings) {
    EXPECT_NEAR(*std::max_element(v.begin(), v.end()), h, 1e-11);
    std::size_t first = 0, last = v.size() - 1;
    while (v[first] < h - 1e-11) ++first;
    while (v[last] < h - 1e-11) --last;
    EXPECT_NEAR(*std::min_element(v.begin() + first, v.begin() + last + 1), centre_lift, 1e-11);
  }
}

TEST(Spall, UnknownPitShapesAndRimsWithoutSharpEdgesAreRefusedNamingTheKey) {
  test::expect_config_error([] { BearingModel m(deep_groove("imperfections: {spall_pits: square}\n")); },
                            {"imperfections.spall_pits", "'trench' or 'round'"}, "spall_pits: square");
  test::expect_config_error(
      [] { BearingModel m(deep_groove("imperfections: {spall_rim_height_um: 1, spall_rim_width_um: 100}\n")); },
      {"imperfections.spall_rim_height_um", "spall_edges: sharp"}, "a rim on a rounded edge");
  test::expect_config_error(
      [] {
        BearingModel m(
            deep_groove("imperfections: {spall_edges: sharp, spall_rim_height_um: 30, "
                        "spall_rim_width_um: 100}\n"));
      },
      {"imperfections.spall_rim_height_um", "[0, 20] um"}, "a 30 um rim");
}

TEST(Spall, AnUnknownSpallEdgeIsRefusedNamingTheKey) {
  test::expect_config_error([] { BearingModel m(deep_groove("imperfections: {spall_edges: jagged}\n")); },
                            {"imperfections.spall_edges", "'rounded' or 'sharp'"}, "spall_edges: jagged");
}

TEST(Spall, AGrowingSpallDeepensAtItsRateAndAFixedOneKeepsItsDepth) {
  // 2 mm wide outer-race spalls centred under ball 0 (at rest: every angle 0), 5 um deep,
  // one growing at 3600 um/h = 1 um/s: after 2 s the ball drops 7 um into it (still below
  // w^2/(4d) = 126 um), into the fixed one 5 um at any time. The neighbours, 40 deg away,
  // are not over either.
  const auto offsets_at = [](const std::string& growth, double t) {
    const BearingModel model(
        deep_groove("defects:\n  - {surface: outer_race, position_deg: 0, width_mm: 2.0, "
                    "depth_um: 5" +
                    growth + "}\n"));
    std::vector<double> out(kBalls, 0.0);
    model.imperfections().add_offsets(RollingPhase{0.0, 0.0, 0.0, 0.0, t}, out.data());
    return out;
  };
  const std::vector<double> growing = offsets_at(", depth_growth_um_per_hour: 3600", 2.0);
  const std::vector<double> fixed = offsets_at("", 2.0);
  EXPECT_NEAR(growing[0], -7e-6, 1e-15);
  EXPECT_NEAR(fixed[0], -5e-6, 1e-15);
  EXPECT_NEAR(offsets_at(", depth_growth_um_per_hour: 3600", 0.0)[0], -5e-6, 1e-15);
  for (int j = 1; j < kBalls; ++j) {
    EXPECT_EQ(growing[j], 0.0);
    EXPECT_EQ(fixed[j], 0.0);
  }
}

TEST(Spall, DefectsThatDoNotFitTheBearingAreRejected) {
  const BearingModel model(deep_groove(""));
  BearingDynamics dynamics(model, test::load5(1000.0, 0, 0, 0, 0), 0.0, DynamicsOptions{kSampleRateHz, 0});
  Spall too_deep{Surface::OuterRace, 0.0, 0, 1e-3, 3e-3};  // deeper than d/4 = 1.985 mm
  EXPECT_THROW(dynamics.add_spall(too_deep), InvalidInputError);
  Spall no_such_ball{Surface::Ball, 0.0, kBalls, 0.5e-3, 10e-6};
  EXPECT_THROW(dynamics.add_spall(no_such_ball), InvalidInputError);
  Spall too_wide{Surface::InnerRace, 0.0, 0, 0.05, 10e-6};  // 50 mm on a 31 mm race
  EXPECT_THROW(dynamics.add_spall(too_wide), InvalidInputError);
  // A bad defect in a bearing file is a ConfigError naming the key.
  try {
    deep_groove("defects:\n  - {surface: outer_race, width_mm: 1.0, depth_um: 10, size: 3}\n");
    FAIL() << "an unknown defect key must be rejected";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("defects[0].size"), std::string::npos) << e.what();
  }
  try {
    deep_groove("imperfections:\n  waviness:\n    - {surface: cage, order: 3, amplitude_um: 0.1}\n");
    FAIL() << "an unknown surface must be rejected";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("waviness[0].surface"), std::string::npos) << e.what();
  }
}

// The message of the InvalidInputError `f` throws ("" when none).
template <class F>
std::string refusal(F f) {
  try {
    f();
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(Spall, AbsurdPlacesAndSizesBelowASpallAreRefusedNamingTheLimit) {
  BearingModel model(deep_groove(""));
  // 1e300 rad was accepted (and echoed with 63 digits); the limit is kMaxAngleRad.
  std::string why = refusal([&] { model.add_spall(Spall{Surface::OuterRace, 1e300, 0, 1e-3, 10e-6}); });
  EXPECT_NE(why.find("position 1e+300 rad is beyond +-1e+06 rad"), std::string::npos) << why;
  why = refusal([&] { model.add_spall(Spall{Surface::InnerRace, -1.5e6, 0, 1e-3, 10e-6}); });
  EXPECT_NE(why.find("position -1.5e+06 rad"), std::string::npos) << why;
  // 1e-300 m wide (reported as "0.00 mm wide" and counted as present), or as shallow.
  why = refusal([&] { model.add_spall(Spall{Surface::OuterRace, 0.0, 0, 1e-300, 10e-6}); });
  EXPECT_NE(why.find("at least 1 um wide and deep"), std::string::npos) << why;
  why = refusal([&] { model.add_spall(Spall{Surface::Ball, 0.0, 2, 0.5e-3, 0.9e-6}); });
  EXPECT_NE(why.find("0.9 um deep"), std::string::npos) << why;
  EXPECT_TRUE(model.imperfections().spalls().empty());
  // The limits themselves are spalls.
  model.add_spall(Spall{Surface::OuterRace, kMaxAngleRad, 0, kMinSpallSizeM, kMinSpallSizeM});
  model.add_spall(Spall{Surface::Ball, -kMaxAngleRad, 2, kMinSpallSizeM, kMinSpallSizeM});
  EXPECT_EQ(model.imperfections().spalls().size(), 2u);
}

TEST(Spall, AtMostTheCapOfSpallsArePresentAtOnce) {
  BearingModel model(deep_groove(""));
  for (int i = 0; i < kMaxSpalls; ++i)
    model.add_spall(Spall{i % 2 ? Surface::InnerRace : Surface::OuterRace, 0.1 * i, 0, 0.5e-3, 10e-6});
  const std::string why = refusal([&] { model.add_spall(Spall{Surface::OuterRace, 0.0, 0, 0.5e-3, 10e-6}); });
  EXPECT_NE(why.find("64 spalls are present, at most 64 may be at once"), std::string::npos) << why;
  EXPECT_EQ(model.imperfections().spalls().size(), static_cast<std::size_t>(kMaxSpalls));
  // Cleared, there is room again.
  model.clear_spalls();
  model.add_spall(Spall{Surface::OuterRace, 0.0, 0, 0.5e-3, 10e-6});
  EXPECT_EQ(model.imperfections().spalls().size(), 1u);
  // A bearing file with one spall too many is refused naming the bearing.
  std::string defects = "defects:\n";
  for (int i = 0; i <= kMaxSpalls; ++i)
    defects += "  - {surface: outer_race, position_deg: " + std::to_string(i) + ", width_mm: 0.5, depth_um: 10}\n";
  try {
    BearingModel too_many(deep_groove(defects));
    FAIL() << "65 spalls in a bearing file must be refused";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 64"), std::string::npos) << e.what();
  }
}

TEST(Spall, AStaticCageAngleBeyondTheLimitIsRefusedAndOneWithinIsExact) {
  const BearingModel model(deep_groove(""));
  const Vector5 load = test::load5(1000.0, 0, 0, 0, 0);
  // 1e300 rad put all balls at one azimuth (a maximum ball load of 0).
  const std::string why = refusal([&] { solve_static(model, load, 1e300); });
  EXPECT_NE(why.find("cage angle 1e+300 rad is beyond +-1e+06 rad"), std::string::npos) << why;
  EXPECT_FALSE(refusal([&] { solve_static(model, load, -1e7); }).empty());
  // Within the limit the balls keep their places: 1000 cage turns on is the same solution
  // (the rounding of 2000 pi + 0.1 is ~1e-12 rad).
  const StaticSolution near = solve_static(model, load, 0.1), far = solve_static(model, load, 2000.0 * kPi + 0.1);
  EXPECT_GT(near.max_ball_load_N, 100.0);
  EXPECT_NEAR(far.max_ball_load_N, near.max_ball_load_N, 1e-6 * near.max_ball_load_N);
}

TEST(Spall, RuntimeGrowthStopsAtTheLargestSpallTheBearingHolds) {
  // Outer race spall under ball 0, 1 mm wide and 20 um deep, growing 1 mm/s and 10 um/s.
  const BearingModel model(deep_groove(""));
  Imperfections imperfections = model.imperfections();
  Spall spall{Surface::OuterRace, 0.0, 0, 1e-3, 20e-6};
  spall.width_growth_m_per_s = 1e-3;
  spall.depth_growth_m_per_s = 10e-6;
  imperfections.add_spall(spall);
  const auto drops_at = [&](double time_s) {
    RollingPhase phase;  // cage and rings at 0: ball j at azimuth 40 j deg
    phase.time_s = time_s;
    std::vector<double> offsets(kBalls, 0.0);
    imperfections.add_offsets(phase, offsets.data());
    return offsets;
  };
  // Growing at 2 s: 3 mm wide, 40 um deep (below w^2 / (4 d) = 283 um), all of it under ball 0.
  EXPECT_NEAR(drops_at(2.0)[0], -40e-6, 1e-12);
  // Unbounded, 1e4 s would make it 10 m wide and 0.1 m deep: every ball in it. It stops at a
  // quarter of the raceway (pi/2 of arc) and d/4 deep, so ball 0 drops d/4, balls 1 and 8
  // (40 deg from the centre, inside its 45 deg half width) d/4 cos(pi 40/90), the others not at all.
  const double d = 7.94e-3;
  const std::vector<double> late = drops_at(1e4), much_later = drops_at(1e9);
  EXPECT_NEAR(late[0], -d / 4.0, 1e-12);
  EXPECT_NEAR(late[1], -d / 4.0 * std::cos(4.0 * kPi / 9.0), 1e-12);
  EXPECT_NEAR(late[8], -d / 4.0 * std::cos(4.0 * kPi / 9.0), 1e-12);
  for (int j = 2; j <= 7; ++j) EXPECT_EQ(late[j], 0.0) << "ball " << j;
  // And it stays there.
  for (int j = 0; j < kBalls; ++j) EXPECT_EQ(much_later[j], late[j]) << "ball " << j;
}

TEST(Spall, InjectedAndClearedAtRuntime) {
  const BearingModel model(deep_groove(""));
  const Vector5 load = test::load5(1000.0, 0, 0, 0, 0);
  BearingDynamics healthy(model, load, kInnerRpm * 2.0 * kPi / 60.0, DynamicsOptions{kSampleRateHz, 0});
  BearingDynamics spalled(model, load, kInnerRpm * 2.0 * kPi / 60.0, DynamicsOptions{kSampleRateHz, 0});
  spalled.add_spall(Spall{Surface::InnerRace, 0.0, 0, 1e-3, 20e-6});
  double healthy_peak = 0.0, spalled_peak = 0.0;
  for (int i = 0; i < 2000; ++i) {
    healthy_peak = std::max(healthy_peak, std::abs(healthy.step().acceleration[0]));
    spalled_peak = std::max(spalled_peak, std::abs(spalled.step().acceleration[0]));
  }
  // Balls dropping 20 um into the spall under ~300 N give impacts far above the smooth
  // bearing's varying-compliance vibration.
  EXPECT_GT(spalled_peak, 10.0 * healthy_peak);
  spalled.clear_spalls();
  spalled.reset_to_equilibrium();
  healthy.reset_to_equilibrium();
  double difference = 0.0;
  for (int i = 0; i < 200; ++i)
    difference = std::max(difference, std::abs(spalled.step().acceleration[0] - healthy.step().acceleration[0]));
  // Cleared: both at rest at the same equilibrium; only the cage phase differs (same speed, same
  // number of samples), so the two runs coincide.
  EXPECT_LT(difference, 1e-9 * healthy_peak + 1e-12);
}

TEST(Imperfections, DeterministicPerSeedAndDifferentAcrossSeeds) {
  auto run = [](int seed) {
    return radial_acceleration(deep_groove("imperfections:\n  seed: " + std::to_string(seed) +
                                           "\n  roughness_rms_um: 0.05\n  ball_diameter_variation_um: 0.2\n"),
                               0.05);
  };
  const std::vector<double> a = run(7), b = run(7), c = run(8);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "sample " << i;
  double max_difference = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) max_difference = std::max(max_difference, std::abs(a[i] - c[i]));
  EXPECT_GT(max_difference, 0.0);
}

TEST(Imperfections, BallDiameterVariationHasTheConfiguredSpread) {
  const BearingModel model(bearing_config_from_string(
      "balls_per_row: 400\nball_diameter_mm: 5\npitch_diameter_mm: 1000\ninner_groove_curvature: 0.52\n"
      "outer_groove_curvature: 0.52\nimperfections: {seed: 3, ball_diameter_variation_um: 0.3}\n"));
  double sum = 0.0, sum_sq = 0.0;
  for (double d : model.deflection_offsets()) {
    sum += d;
    sum_sq += d * d;
  }
  const double n = model.ball_count();
  const double sd = std::sqrt(sum_sq / n - (sum / n) * (sum / n));
  // The sample standard deviation of 400 normal draws is within 4 standard errors
  // (sd / sqrt(2n) = 3.5%) of the true one with near certainty.
  EXPECT_NEAR(sd, 0.3e-6, 4.0 * 0.3e-6 / std::sqrt(2.0 * n));
}

}  // namespace
}  // namespace bearing_sim
