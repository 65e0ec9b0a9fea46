#pragma once
// The bearing file (docs/bearing_file.md), in SI units once loaded.
#include <array>
#include <string>

#include "bearing_sim/core/flexible_ring_spec.hpp"
#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim {

// The largest pitch circle a bearing file may give: twice the largest slewing bearings
// (about 10 m); beyond it a size is a typing error, and the speed limit on the pitch line
// (frequencies.hpp) would leave the ring no speed at all.
inline constexpr double kMaxPitchDiameterM = 20.0;

enum class Arrangement { BackToBack, FaceToFace };
enum class RotatingRing { Outer, Inner };

struct Material {
  double youngs_modulus_Pa = 208e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;
};

// A rigid body that moves with the rotating ring (the CT gantry's rotor: tube, detector,
// slip ring), symmetric about the bearing axis: its centre of gravity on the axis at
// centre_of_gravity_axial_m from the bearing centre. A radial offset of the centre of gravity
// is an unbalance, given as a rotating load (scenarios), not here.
struct CarriedBody {
  double mass_kg = 0.0;                    // 0: none
  double centre_of_gravity_axial_m = 0.0;  // z of the centre of gravity, bearing frame
  double transverse_inertia_kg_m2 = 0.0;   // about an axis through the centre of gravity, normal to the bearing axis
  double polar_inertia_kg_m2 = 0.0;        // about the bearing axis (reported; the model has no spin DOF)
  bool present() const { return mass_kg > 0.0; }
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
  // g0 per ball along the contact line at equal ring temperatures (the file's clearance_um);
  // < 0 is preload. The model uses operating_clearance_m (thermal_clearance.hpp).
  double clearance_m = 0.0;
  // Inner minus outer ring temperature, K: an operating input, not a key of the bearing file.
  double ring_temperature_difference_K = 0.0;
  // Envelope; when absent, derived from the ball and pitch diameters (see defaults in the .cpp).
  double outer_diameter_m = 0.0;
  double inner_diameter_m = 0.0;
  double width_m = 0.0;
  RotatingRing rotating_ring = RotatingRing::Outer;
  Material material;
  double rotating_mass_kg = 0.0;    // 0: not given (static analysis only)
  CarriedBody carried_body;         // moves with the rotating ring; adds to its mass matrix
  double tilt_inertia_kg_m2 = 0.0;  // after loading: given or derived from the envelope
  bool tilt_inertia_given = false;
  // c_n per loaded contact: given, or solved from modal_damping_ratio at the reference load.
  double contact_damping_Ns_per_m = 0.0;
  // > 0 when the file gave the damping as the ratio of the radial mode (docs/model.md 7.3).
  double modal_damping_ratio = 0.0;
  std::array<double, 5> damping_reference_load{};  // Fx, Fy, Fz (N), Mx, My (N*m)
  // Extension of the bearing file: `imperfections:` and `defects:` (docs/bearing_file.md).
  ImperfectionSpec imperfections;
  // Extension: `flexible_ring:`, the rotating ring's bending modes (absent: a rigid ring).
  FlexibleRingSpec flexible_ring;

  bool has_dynamics() const { return rotating_mass_kg > 0.0; }
};

// Reads and validates a bearing file (src/core/bearing_config_reader.cpp); throws ConfigError
// naming `source` (a file name) and the key.
BearingConfig load_bearing_config(const std::string& path);
BearingConfig bearing_config_from_string(const std::string& yaml_text, const std::string& source = "<string>");

}  // namespace bearing_sim
