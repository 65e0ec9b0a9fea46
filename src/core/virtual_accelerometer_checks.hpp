#pragma once
// The sensor configuration's checks, shared by its reader (virtual_accelerometer_reader.cpp)
// and the VirtualAccelerometer's constructor. Internal to the core library.
#include <string>

#include "bearing_sim/core/virtual_accelerometer.hpp"

namespace bearing_sim::detail {

struct AccelerometerProblem {
  std::string key, what;
  bool any() const { return !key.empty(); }
};

// The checks that do not depend on the input rate, the installation's included: the first
// key out of range (as in the sensor file) and what is wrong; an empty key when none is.
AccelerometerProblem accelerometer_config_problem(const AccelerometerConfig& c);

}  // namespace bearing_sim::detail
