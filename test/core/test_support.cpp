#include "test_support.hpp"

#include <stdexcept>

#include <cmath>
#include <complex>
#include <fstream>
#include <sstream>

#include <unsupported/Eigen/FFT>

#include "bearing_6205_yaml.hpp"

namespace bearing_sim::test {

std::string bearing_file(const std::string& name) {
  return std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/" + name;
}

std::string config_path(const std::string& relative) {
  return std::string(BEARING_SIM_SOURCE_DIR) + "/config/" + relative;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

BearingConfig iso_reference_bearing(double clearance_m) {
  BearingConfig c = bearing_config_from_string(
      "name: ISO/TS 16281 reference\n"
      "balls_per_row: 6\n"
      "ball_diameter_mm: 11.1\n"
      "pitch_diameter_mm: 43.5\n"
      "inner_groove_curvature: 0.52\n"
      "outer_groove_curvature: 0.53\n"
      "contact_angle_deg: 0\n"
      "material: {youngs_modulus_GPa: 210.0, poisson_ratio: 0.3}\n",
      "iso_reference");
  c.clearance_m = clearance_m;
  return c;
}

BearingConfig ct_bearing() { return load_bearing_config(bearing_file("ct_gantry_lyc.yaml")); }

Vector5 ct_load() { return load5(6800.0, 0.0, 0.0, 0.0, 2100.0); }

BearingConfig single_row(int balls, double d_mm, double dm_mm, double contact_angle_deg, double fi, double fo,
                         double clearance_um, const std::string& extra_yaml) {
  std::ostringstream y;
  y.precision(17);
  y << "name: test single row\n"
    << "balls_per_row: " << balls << "\n"
    << "ball_diameter_mm: " << d_mm << "\n"
    << "pitch_diameter_mm: " << dm_mm << "\n"
    << "contact_angle_deg: " << contact_angle_deg << "\n"
    << "inner_groove_curvature: " << fi << "\n"
    << "outer_groove_curvature: " << fo << "\n"
    << "clearance_um: " << clearance_um << "\n"
    << extra_yaml;
  return bearing_config_from_string(y.str(), "single_row");
}

double dft_amplitude(const std::vector<double>& x, double sample_rate_hz, double f_hz) {
  // Goertzel recurrence: one DFT term at an arbitrary frequency, mean removed.
  double m = 0.0;
  for (double v : x) m += v;
  m /= static_cast<double>(x.size());
  const double w = 2.0 * kPi * f_hz / sample_rate_hz, coeff = 2.0 * std::cos(w);
  double s1 = 0.0, s2 = 0.0;
  for (double v : x) {
    const double s0 = (v - m) + coeff * s1 - s2;
    s2 = s1;
    s1 = s0;
  }
  const double re = s1 - s2 * std::cos(w), im = s2 * std::sin(w);
  return 2.0 * std::hypot(re, im) / static_cast<double>(x.size());
}

std::vector<double> welch_psd(const std::vector<double>& x, double fs, int n) {
  std::vector<double> window(n), psd(n / 2 + 1, 0.0);
  double window_power = 0.0;
  for (int i = 0; i < n; ++i) {
    window[i] = 0.5 - 0.5 * std::cos(2.0 * kPi * i / n);
    window_power += window[i] * window[i];
  }
  Eigen::FFT<double> fft;
  std::vector<double> segment(n);
  std::vector<std::complex<double>> spectrum;
  int segments = 0;
  for (std::size_t start = 0; start + n <= x.size(); start += n / 2, ++segments) {
    for (int i = 0; i < n; ++i) segment[i] = x[start + i] * window[i];
    fft.fwd(spectrum, segment);
    for (int k = 0; k <= n / 2; ++k) psd[k] += std::norm(spectrum[k]);
  }
  for (int k = 0; k <= n / 2; ++k) psd[k] *= (k == 0 || k == n / 2 ? 1.0 : 2.0) / (fs * window_power * segments);
  return psd;
}

double spectral_peak_hz(const std::vector<double>& x, double sample_rate_hz, double f_min_hz, double f_max_hz,
                        double step_hz) {
  double best = -1.0, best_f = 0.0;
  for (double f = f_min_hz; f <= f_max_hz; f += step_hz) {
    const double a = dft_amplitude(x, sample_rate_hz, f);
    if (a > best) {
      best = a;
      best_f = f;
    }
  }
  return best_f;
}

Vector5 load5(double fx, double fy, double fz, double mx, double my) {
  Vector5 l;
  l << fx, fy, fz, mx, my;
  return l;
}

BearingModel bearing_6205(const std::string& extra_yaml) {
  return BearingModel(bearing_config_from_string(kBearing6205Yaml + extra_yaml, "6205-like"));
}

const FaultIndicator& fault(const ConditionIndicators& c, FaultKind kind) {
  for (const FaultIndicator& f : c.faults)
    if (f.kind == kind) return f;
  throw std::runtime_error(std::string("no indicator for ") + fault_kind_name(kind));
}

}  // namespace bearing_sim::test
