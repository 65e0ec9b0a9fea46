#pragma once
// Clearance at a temperature difference between the rings (docs/model.md section 3.7): the
// warmer ring expands more, which closes the clearance (inner ring warmer) or opens it.
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

// Linear thermal expansion coefficient of bearing steel (100Cr6 / AISI 52100), 1/K.
constexpr double kBearingSteelExpansionPerK = 11.5e-6;
// Largest |T_inner - T_outer| accepted, K: beyond it the rings' temperatures leave the range
// in which standard heat-stabilised bearing steel keeps its dimensions (up to 150 degC).
constexpr double kMaxRingTemperatureDifferenceK = 150.0;

// Change of g0 (per ball, along the contact line) for T_inner - T_outer = dT (K):
// -alpha dT (dm / 2) cos a0. Throws InvalidInputError for a non-finite or too large dT.
double thermal_clearance_change_m(const BearingConfig& config, double ring_temperature_difference_K);

// g0 the model uses: clearance_m plus the change at config.ring_temperature_difference_K.
// Throws InvalidInputError, naming the temperature difference and the clearance, when the
// result leaves the model's range |g0| < 5 % of the ball diameter (the bearing file's rule).
double operating_clearance_m(const BearingConfig& config);

// The running bearing at another ring temperature difference: its config, ball offsets and
// spalls (with their creation times) kept, for BearingDynamics::set_model. Throws as above.
BearingModel with_ring_temperature_difference(const BearingModel& model, double ring_temperature_difference_K);

}  // namespace bearing_sim
