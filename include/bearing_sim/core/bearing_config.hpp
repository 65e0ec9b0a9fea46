#pragma once
// The bearing file (docs/bearing_file.md), in SI units once loaded.
#include <string>

#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim {

enum class Arrangement { BackToBack, FaceToFace };
enum class RotatingRing { Outer, Inner };

struct Material {
  double youngs_modulus_Pa = 208e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;
};

struct BearingConfig {
  std::string name;
  int rows = 1;
  Arrangement arrangement = Arrangement::BackToBack;
  int balls_per_row = 0;
  double ball_diameter_m = 0.0;
  double pitch_diameter_m = 0.0;
  double row_spacing_m = 0.0;
  double row_phase_rad = 0.0;
  double contact_angle_rad = 0.0;
  double inner_groove_curvature = 0.0;
  double outer_groove_curvature = 0.0;
  double clearance_m = 0.0;  // g0 per ball along the contact line; < 0 is preload
  // Envelope; when absent, derived from the ball and pitch diameters (see defaults in the .cpp).
  double outer_diameter_m = 0.0;
  double inner_diameter_m = 0.0;
  double width_m = 0.0;
  RotatingRing rotating_ring = RotatingRing::Outer;
  Material material;
  double rotating_mass_kg = 0.0;     // 0: not given (static analysis only)
  double tilt_inertia_kg_m2 = 0.0;   // after loading: given or derived from the envelope
  bool tilt_inertia_given = false;
  double contact_damping_Ns_per_m = 0.0;
  // Extension of the bearing file: `imperfections:` and `defects:` (docs/bearing_file.md).
  ImperfectionSpec imperfections;

  bool has_dynamics() const { return rotating_mass_kg > 0.0; }
};

// Parses and validates; throws ConfigError naming `source` (a file name) and the key.
BearingConfig parse_bearing_config(const YAML::Node& root, const std::string& source);
BearingConfig load_bearing_config(const std::string& path);
BearingConfig bearing_config_from_string(const std::string& yaml_text,
                                         const std::string& source = "<string>");

}  // namespace bearing_sim
