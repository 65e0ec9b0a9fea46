#include "test_support.hpp"

#include <cmath>
#include <sstream>

namespace bearing_sim::test {

std::string bearing_file(const std::string& name) {
  return std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/" + name;
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
  double m = 0.0;
  for (double v : x) m += v;
  m /= static_cast<double>(x.size());
  double re = 0.0, im = 0.0;
  const double w = 2.0 * kPi * f_hz / sample_rate_hz;
  for (std::size_t i = 0; i < x.size(); ++i) {
    re += (x[i] - m) * std::cos(w * static_cast<double>(i));
    im -= (x[i] - m) * std::sin(w * static_cast<double>(i));
  }
  return 2.0 * std::hypot(re, im) / static_cast<double>(x.size());
}

Vector5 load5(double fx, double fy, double fz, double mx, double my) {
  Vector5 l;
  l << fx, fy, fz, mx, my;
  return l;
}

}  // namespace bearing_sim::test
