#include "test_support.hpp"

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

}  // namespace bearing_sim::test
