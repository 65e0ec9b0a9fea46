#pragma once
// Cage, ball-pass and ball-spin frequencies (docs/model.md section 8).
#include <string>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

// The fastest either ring may turn, as the speed of its pitch circle (diameter dm): every
// front refuses a faster one (bearing_tool, Python, sweeps, scenarios, the node). The fastest
// real ball bearings (aero-engine main shafts, spindles with ceramic balls) reach dm n ~3.5e6
// mm*rpm, a pitch-line speed of ~180 m/s; 500 m/s (dm n ~9.5e6 mm*rpm) is well above any
// bearing's limiting speed, so a faster run describes no bearing (the 6205: 25,600 rad/s,
// 245,000 rpm; the CT bearing: 900 rad/s, 8,600 rpm).
constexpr double kMaxPitchLineSpeedMPerS = 500.0;
// kMaxPitchLineSpeedMPerS / (dm / 2), rad/s.
double max_ring_speed_rad_s(double pitch_diameter_m);
// Why a ring speed is refused ("" when it is not): not finite, or beyond max_ring_speed_rad_s;
// names the speed and the limit in rad/s and rpm.
std::string ring_speed_refusal(double speed_rad_s, double pitch_diameter_m);
// Throws InvalidInputError "<what>: <ring_speed_refusal>" for a refused speed.
void check_ring_speed(double speed_rad_s, double pitch_diameter_m, const std::string& what);

struct BearingFrequencies {
  double cage_hz = 0.0;                  // f_c, in the bearing frame
  double ball_pass_outer_race_hz = 0.0;  // Z |f_o - f_c|
  double ball_pass_inner_race_hz = 0.0;  // Z |f_i - f_c|
  double ball_spin_hz = 0.0;             // dm/(2d) (1 - gamma^2) f_r
  double relative_ring_hz = 0.0;         // |f_i - f_o|
  double varying_compliance_hz = 0.0;    // Z |f_c|: balls passing the stationary load zone
  // Ring speeds in the bearing frame (where the load is fixed): a spall on a ring turns
  // through the load zone at this rate (0 for a stationary ring).
  double inner_ring_hz = 0.0;  // |f_i|
  double outer_ring_hz = 0.0;  // |f_o|
};

BearingFrequencies bearing_frequencies(const BearingModel& model, double inner_rad_s, double outer_rad_s);
// For a speed of the configured rotating ring.
BearingFrequencies bearing_frequencies(const BearingModel& model, double rotating_ring_rad_s);

}  // namespace bearing_sim
