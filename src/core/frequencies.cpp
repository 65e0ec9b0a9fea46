#include "bearing_sim/core/frequencies.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

double max_ring_speed_rad_s(double pitch_diameter_m) { return kMaxPitchLineSpeedMPerS / (0.5 * pitch_diameter_m); }

std::string ring_speed_refusal(double speed_rad_s, double pitch_diameter_m) {
  const double limit = max_ring_speed_rad_s(pitch_diameter_m);
  if (std::abs(speed_rad_s) <= limit) return "";  // NaN fails too
  constexpr double kRadSToRpm = 60.0 / kTwoPi;
  std::ostringstream why;
  why.precision(4);
  why << speed_rad_s << " rad/s (" << speed_rad_s * kRadSToRpm << " rpm) is beyond +-" << limit << " rad/s ("
      << limit * kRadSToRpm << " rpm), a pitch-line speed of " << kMaxPitchLineSpeedMPerS << " m/s on this bearing's "
      << pitch_diameter_m * 1e3 << " mm pitch circle, above any bearing's limiting speed";
  return why.str();
}

void check_ring_speed(double speed_rad_s, double pitch_diameter_m, const std::string& what) {
  const std::string why = ring_speed_refusal(speed_rad_s, pitch_diameter_m);
  if (!why.empty()) throw InvalidInputError(what + ": " + why);
}

BearingFrequencies bearing_frequencies(const BearingModel& model, double inner_rad_s, double outer_rad_s) {
  if (!std::isfinite(inner_rad_s) || !std::isfinite(outer_rad_s))
    throw InvalidInputError("bearing frequencies: the ring speeds must be finite numbers (inner " +
                            std::to_string(inner_rad_s) + " rad/s, outer " + std::to_string(outer_rad_s) + " rad/s)");
  const auto& c = model.config();
  check_ring_speed(inner_rad_s, c.pitch_diameter_m, "inner ring speed");
  check_ring_speed(outer_rad_s, c.pitch_diameter_m, "outer ring speed");
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
