#include "bearing_sim/core/frequencies.hpp"

#include <cmath>
#include <string>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

BearingFrequencies bearing_frequencies(const BearingModel& model, double inner_rad_s, double outer_rad_s) {
  if (!std::isfinite(inner_rad_s) || !std::isfinite(outer_rad_s))
    throw InvalidInputError("bearing frequencies: the ring speeds must be finite numbers (inner " +
                            std::to_string(inner_rad_s) + " rad/s, outer " + std::to_string(outer_rad_s) + " rad/s)");
  const auto& c = model.config();
  const double z = c.balls_per_row;
  const double wc = model.cage_speed_rad_s(inner_rad_s, outer_rad_s);
  BearingFrequencies f;
  f.cage_hz = wc / kTwoPi;
  f.ball_pass_outer_race_hz = z * std::abs(outer_rad_s - wc) / kTwoPi;
  f.ball_pass_inner_race_hz = z * std::abs(inner_rad_s - wc) / kTwoPi;
  f.relative_ring_hz = std::abs(inner_rad_s - outer_rad_s) / kTwoPi;
  f.ball_spin_hz = model.ball_spin_speed_rad_s(inner_rad_s, outer_rad_s) / kTwoPi;
  f.varying_compliance_hz = z * std::abs(wc) / kTwoPi;
  f.inner_ring_hz = std::abs(inner_rad_s) / kTwoPi;
  f.outer_ring_hz = std::abs(outer_rad_s) / kTwoPi;
  return f;
}

BearingFrequencies bearing_frequencies(const BearingModel& model, double rotating_ring_rad_s) {
  double wi = 0.0, wo = 0.0;
  model.ring_speeds(rotating_ring_rad_s, &wi, &wo);
  return bearing_frequencies(model, wi, wo);
}

}  // namespace bearing_sim
