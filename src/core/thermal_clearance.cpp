// Thermal change of the clearance (docs/model.md section 3.7).
#include "bearing_sim/core/thermal_clearance.hpp"

#include <cmath>
#include <sstream>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

double thermal_clearance_change_m(const BearingConfig& c, double dT) {
  if (!std::isfinite(dT) || std::abs(dT) > kMaxRingTemperatureDifferenceK) {
    std::ostringstream why;
    why << "ring temperature difference " << dT << " K refused: must be finite and within +-"
        << kMaxRingTemperatureDifferenceK << " K";
    throw InvalidInputError(why.str());
  }
  // The diametral clearance closes by alpha dT dm (balls at the mean ring temperature); one
  // ball's share along its contact line is half of it, projected by cos a0.
  return -kBearingSteelExpansionPerK * dT * 0.5 * c.pitch_diameter_m * std::cos(c.contact_angle_rad);
}

double operating_clearance_m(const BearingConfig& c) {
  const double dT = c.ring_temperature_difference_K;
  if (dT == 0.0) return c.clearance_m;  // bit-identical to a model without the input
  const double g0 = c.clearance_m + thermal_clearance_change_m(c, dT);
  const double limit = 0.05 * c.ball_diameter_m;
  if (!(std::abs(g0) < limit)) {
    std::ostringstream why;
    why << "ring temperature difference " << dT << " K turns the clearance of " << c.clearance_m * 1e6 << " um into "
        << g0 * 1e6 << " um" << (g0 < 0.0 ? " (interference)" : "") << ": beyond the model's +-" << limit * 1e6
        << " um (5 % of the ball diameter)";
    throw InvalidInputError(why.str());
  }
  return g0;
}

BearingModel with_ring_temperature_difference(const BearingModel& model, double dT) {
  BearingConfig config = model.config();
  config.ring_temperature_difference_K = dT;
  BearingModel changed(config);
  changed.set_deflection_offsets(model.deflection_offsets());
  changed.clear_spalls();
  for (const Spall& s : model.imperfections().spalls()) changed.add_spall(s);
  return changed;
}

}  // namespace bearing_sim
