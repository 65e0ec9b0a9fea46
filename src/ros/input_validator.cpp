#include "bearing_sim/ros/input_validator.hpp"

#include <cmath>
#include <sstream>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"

namespace bearing_sim {
namespace ros_node {

InputCheck check_load(const Vector5& load, const InputLimits& limits, const BearingModel* model) {
  InputCheck c;
  std::ostringstream why;
  const double force = load.head<3>().norm(), moment = load.tail<2>().norm();
  if (!load.allFinite()) {
    why << "load is not finite";
  } else if (force > limits.max_force_N) {
    why << "force " << force << " N exceeds max_force_N = " << limits.max_force_N;
  } else if (moment > limits.max_moment_Nm) {
    why << "moment " << moment << " N*m exceeds max_moment_Nm = " << limits.max_moment_Nm;
  } else if (model) {
    // A load with no static equilibrium would only drive the dynamics to divergence.
    try {
      c.max_contact_pressure_Pa = solve_static(*model, load).max_contact_pressure_Pa;
    } catch (const LoadNotCarriedError& e) {
      why << "load not carried: " << e.what();
    } catch (const InvalidInputError& e) {
      why << "invalid load: " << e.what();
    }
  }
  c.reason = why.str();
  c.accepted = c.reason.empty();
  return c;
}

InputCheck check_speed(double ring_speed_rad_s, const InputLimits& limits) {
  InputCheck c;
  std::ostringstream why;
  if (!std::isfinite(ring_speed_rad_s))
    why << "speed is not finite";
  else if (std::abs(ring_speed_rad_s) > limits.max_speed_rad_s)
    why << "speed " << ring_speed_rad_s << " rad/s exceeds max_speed_rad_s = " << limits.max_speed_rad_s;
  c.reason = why.str();
  c.accepted = c.reason.empty();
  return c;
}

InputCheck check_setting(double value, const SettingRange& range) {
  InputCheck c;
  if (!std::isfinite(value) || value < range.min || value > range.max) {
    std::ostringstream why;
    why << range.name << " = " << value << " refused: must be finite and in [" << range.min << ", " << range.max
        << "]";
    c.reason = why.str();
  }
  c.accepted = c.reason.empty();
  return c;
}

}  // namespace ros_node
}  // namespace bearing_sim
