#pragma once
// Shared fixtures of the core tests.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim::test {

using bearing_sim::kPi;  // one value of pi: the core's

// Path of a shipped bearing file, e.g. bearing_file("ct_gantry_lyc.yaml").
std::string bearing_file(const std::string& name);
// Path of a shipped config file, e.g. config_path("sensors/ct_gantry_housing_accelerometer.yaml").
std::string config_path(const std::string& relative);
// The whole text of a file ("" when it cannot be read).
std::string read_text(const std::string& path);

// The ISO/TS 16281 reference bearing of docs/model.md section 6.4 (6 balls, 11.1 mm, a0 = 0).
BearingConfig iso_reference_bearing(double clearance_m = 0.0);

// The CT gantry bearing of config/bearings/ct_gantry_lyc.yaml.
BearingConfig ct_bearing();
// Its operating case: 6800 N along x, 2100 N*m about y, outer ring at 180 rpm.
Vector5 ct_load();
constexpr double kCtSpeedRadS = 180.0 * 2.0 * kPi / 60.0;

// A single-row bearing built from the given numbers (sizes in mm, angle in deg).
BearingConfig single_row(int balls, double d_mm, double dm_mm, double contact_angle_deg, double fi, double fo,
                         double clearance_um = 0.0, const std::string& extra_yaml = "");

// Amplitude spectrum |X(f)| of x (mean removed) at frequency f, by a direct DFT sum.
double dft_amplitude(const std::vector<double>& x, double sample_rate_hz, double f_hz);

// One-sided Welch PSD (Hann, 50 % overlap, segments of n samples); bin k at k fs / n.
std::vector<double> welch_psd(const std::vector<double>& x, double sample_rate_hz, int n);

// Frequency of the largest |X(f)| on a grid from f_min to f_max (DC excluded by f_min > 0).
double spectral_peak_hz(const std::vector<double>& x, double sample_rate_hz, double f_min_hz, double f_max_hz,
                        double step_hz);

// The 6205-like deep groove bearing of the health tests (Z = 9, d = 7.94 mm, dm = 39.04 mm,
// fi = fo = 0.52), inner ring rotating with 0.5 kg, 100 N*s/m per contact, plus extra keys.
BearingModel bearing_6205(const std::string& extra_yaml = "");

// The indicator of one fault kind in an analysis.
const FaultIndicator& fault(const ConditionIndicators& c, FaultKind kind);

// Generalized load vector (Fx, Fy, Fz, Mx, My).
Vector5 load5(double fx, double fy, double fz, double mx, double my);

// Expects parse() to throw a ConfigError whose message holds every one of `words` (the
// file's name, the key, the reason); `input` names what was parsed in a failure's message.
template <typename Parse>
void expect_config_error(const Parse& parse, const std::vector<std::string>& words, const std::string& input) {
  try {
    parse();
    ADD_FAILURE() << "no ConfigError for " << input;
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    for (const std::string& w : words) EXPECT_NE(what.find(w), std::string::npos) << "'" << w << "' not in: " << what;
  }
}

}  // namespace bearing_sim::test
