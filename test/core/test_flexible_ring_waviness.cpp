// Waviness of order k Z +- n on a race drives the flexible ring's n-th bending mode
// (docs/model.md 18.4): with Z evenly spaced balls, the load change cos(q phi_j) of ball j
// projects onto a ring mode of order m as sum_j cos(q phi_j) cos(m theta_j), which is zero
// unless q +- m is a multiple of Z. The response of the other modes comes only from the
// contacts' nonlinearity.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "bearing_sim/core/flexible_dynamics.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

constexpr int kBalls = 16;
constexpr double kOuterRpm = 600.0;

// A preloaded single-row bearing (every ball loaded alike, 5 um) whose rotating outer ring is
// a 15 x 10 mm steel ring with its in-plane modes n = 2..5, and waviness of `order` on the
// fixed inner race, 1 % of the preload deflection.
FlexibleBearing wavy_bearing(int order) {
  const std::string extra =
      "rotating_mass_kg: 2.0\n"
      "damping: {contact_damping_Ns_per_m: 50}\n"
      "flexible_ring: {section_width_mm: 15, section_height_mm: 10, in_plane_max_order: 5, "
      "modal_damping_ratio: 0.02}\n"
      "imperfections:\n  waviness:\n    - {surface: inner_race, order: " +
      std::to_string(order) + ", amplitude_um: 0.05}\n";
  return FlexibleBearing(BearingModel(test::single_row(kBalls, 10.0, 200.0, 0.0, 0.52, 0.52, -5.0, extra)));
}

struct ModeResponse {
  std::vector<double> rms_m;       // per mode order 2..5: RMS amplitude of (cos, sin)
  std::vector<double> driven_cos;  // the driven mode's cos coordinate over time
};

ModeResponse simulate(int order, int driven_mode, double rate_hz, double duration_s, double settle_s) {
  FlexibleDynamics dyn(wavy_bearing(order), Vector5::Zero(), kOuterRpm * 2 * kPi / 60.0, rate_hz);
  const int modes = static_cast<int>(dyn.bearing().modes().size());
  std::vector<std::vector<double>> coordinate(2 * modes);
  const int samples = static_cast<int>(duration_s * rate_hz), settle = static_cast<int>(settle_s * rate_hz);
  for (int i = 0; i < samples; ++i) {
    const FlexibleSample& s = dyn.step();
    if (i < settle) continue;
    for (int c = 0; c < 2 * modes; ++c) coordinate[c].push_back(s.coordinates[5 + c]);
  }
  const auto rms = [](const std::vector<double>& v) {
    double mean = 0.0, sq = 0.0;
    for (double x : v) mean += x;
    mean /= v.size();
    for (double x : v) sq += (x - mean) * (x - mean);
    return std::sqrt(sq / v.size());
  };
  ModeResponse r;
  for (int m = 0; m < modes; ++m) r.rms_m.push_back(std::hypot(rms(coordinate[2 * m]), rms(coordinate[2 * m + 1])));
  r.driven_cos = coordinate[2 * (driven_mode - 2)];
  std::cout << "waviness order " << order << ", substeps " << dyn.substeps() << ": modal RMS (m) n=2..5:";
  for (double a : r.rms_m) std::cout << " " << a;
  std::cout << "\n";
  return r;
}

void expect_mode_driven(int order, int n, double expected_hz) {
  constexpr double kRate = 2000.0, kDuration = 1.0, kSettle = 0.2;
  const ModeResponse r = simulate(order, n, kRate, kDuration, kSettle);
  for (int m = 2; m <= 5; ++m) {
    if (m == n) continue;
    // Other modes: second order in the waviness (1 % of the deflection), times the few load
    // harmonics the preload's Hertz curvature adds: below 5 % of the driven mode.
    EXPECT_LT(r.rms_m[m - 2], 0.05 * r.rms_m[n - 2]) << "order " << order << ", mode " << m;
  }
  // Mode n in the ring's own frame, driven at Z f_c +- n f_o (the ball set's Z-fold pattern
  // moving at the cage speed, seen from the turning ring); 0.8 s of record: 1.25 Hz bins.
  const double peak = test::spectral_peak_hz(r.driven_cos, kRate, 5.0, 500.0, 0.25);
  EXPECT_NEAR(peak, expected_hz, 1.25) << "order " << order;
  std::cout << "mode " << n << " peak at " << peak << " Hz, expected " << expected_hz << " Hz\n";
}

// Cage speed of a fixed inner ring: f_o (1 + gamma) / 2, gamma = d cos a0 / dm = 10 / 200.
double cage_hz() { return kOuterRpm / 60.0 * (1.0 + 10.0 / 200.0) / 2.0; }

TEST(FlexibleRingWaviness, OrderZPlusTwoDrivesTheOvalMode) {
  expect_mode_driven(kBalls + 2, 2, kBalls * cage_hz() + 2 * kOuterRpm / 60.0);
}

TEST(FlexibleRingWaviness, OrderZMinusThreeDrivesTheTriangularMode) {
  expect_mode_driven(kBalls - 3, 3, kBalls * cage_hz() - 3 * kOuterRpm / 60.0);
}

}  // namespace
}  // namespace bearing_sim
