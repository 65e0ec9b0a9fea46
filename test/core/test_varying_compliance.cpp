// Varying compliance (docs/model.md section 8.1): balls passing the load zone at Z f_c give the
// dominant line of the acceleration spectrum of a smooth bearing.
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/simulation_run.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
std::vector<double> second_half_ax(const BearingModel& model, const SimulationRequest& req) {
  std::vector<double> ax;
  run_simulation(model, req, [&](const DynamicSample& s) { ax.push_back(s.acceleration[0]); });
  return std::vector<double>(ax.begin() + static_cast<long>(ax.size() / 2), ax.end());
}
}  // namespace

TEST(VaryingCompliance, DeepGrooveFundamentalDominates) {
  // 6205-size deep groove bearing, 9 balls, inner ring (0.5 kg with its shaft) at 1797 rpm,
  // 500 N radial: the ring mode (~2 kHz) is far above Z f_c (~107 Hz), and its harmonics are weak.
  const BearingModel model(single_row(9, 7.94, 39.04, 0.0, 0.52, 0.52, 0.0,
                                      "rotating_ring: inner\nrotating_mass_kg: 0.5\n"
                                      "damping: {contact_damping_Ns_per_m: 200}\n"));
  SimulationRequest req;
  req.load = load5(500, 0, 0, 0, 0);
  req.ring_speed_rad_s = 1797.0 * 2.0 * kPi / 60.0;
  req.duration_s = 1.0;
  const std::vector<double> x = second_half_ax(model, req);
  const double bin = req.sample_rate_hz / static_cast<double>(x.size());  // 2 Hz
  const double vc = bearing_frequencies(model, req.ring_speed_rad_s).varying_compliance_hz;
  // Independent: outer ring fixed, f_c = f_i (1 - gamma)/2, gamma = 7.94/39.04; Z f_c = 107.36 Hz.
  EXPECT_NEAR(vc, 9.0 * 29.95 * (1.0 - 7.94 / 39.04) / 2.0, 1e-9);
  const double peak = spectral_peak_hz(x, req.sample_rate_hz, 0.5 * bin, 4900.0, 0.25);
  EXPECT_NEAR(peak, vc, std::max(bin, 0.01 * vc)) << "bin " << bin << " Hz";
}

TEST(VaryingCompliance, CtBearingPeakIsAHarmonicOfZfc) {
  // In the CT case (207 balls per row) the fundamental at 313 Hz is weak and the ring mode
  // near 1.2 kHz amplifies a harmonic: the largest line must still be n Z f_c.
  const BearingModel model(ct_bearing());
  SimulationRequest req;
  req.load = ct_load();
  req.ring_speed_rad_s = kCtSpeedRadS;
  req.duration_s = 0.4;
  const std::vector<double> x = second_half_ax(model, req);
  const double bin = req.sample_rate_hz / static_cast<double>(x.size());  // 5 Hz
  const double vc = bearing_frequencies(model, req.ring_speed_rad_s).varying_compliance_hz;
  const double peak = spectral_peak_hz(x, req.sample_rate_hz, 0.5 * bin, 4900.0, 0.5);
  const double n = std::round(peak / vc);
  EXPECT_GE(n, 1.0);
  EXPECT_NEAR(peak, n * vc, bin) << "peak " << peak << " Hz, Z f_c " << vc << " Hz";
  // A line, not a broad resonance: 10x above the spectrum half-way to the next harmonic.
  EXPECT_GT(dft_amplitude(x, req.sample_rate_hz, peak), 10.0 * dft_amplitude(x, req.sample_rate_hz, peak + 0.5 * vc));
}
