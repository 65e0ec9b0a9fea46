#pragma once
// Cage, ball-pass and ball-spin frequencies (docs/model.md section 8).
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

struct BearingFrequencies {
  double cage_hz = 0.0;                    // f_c, in the bearing frame
  double ball_pass_outer_race_hz = 0.0;    // Z |f_o - f_c|
  double ball_pass_inner_race_hz = 0.0;    // Z |f_i - f_c|
  double ball_spin_hz = 0.0;               // dm/(2d) (1 - gamma^2) f_r
  double relative_ring_hz = 0.0;           // |f_i - f_o|
  double varying_compliance_hz = 0.0;      // Z |f_c|: balls passing the stationary load zone
  // Ring speeds in the bearing frame (where the load is fixed): a spall on a ring turns
  // through the load zone at this rate (0 for a stationary ring).
  double inner_ring_hz = 0.0;              // |f_i|
  double outer_ring_hz = 0.0;              // |f_o|
};

BearingFrequencies bearing_frequencies(const BearingModel& model, double inner_rad_s, double outer_rad_s);
// For a speed of the configured rotating ring.
BearingFrequencies bearing_frequencies(const BearingModel& model, double rotating_ring_rad_s);

}  // namespace bearing_sim
