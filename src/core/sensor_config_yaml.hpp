#pragma once
// The readers of a sensor file's YAML (docs/sensor.md): virtual_accelerometer_reader.cpp and
// machine_background_reader.cpp, apart from the sensor's physics (virtual_accelerometer.hpp,
// machine_background.hpp). Internal to the core library.
#include <string>

#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/machine_background.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"

namespace bearing_sim {

// Reads the `sensor:` mapping (the node given is the mapping itself), with its `path_modes`
// and `installation:`. Keys carry their units (docs/sensor.md); an unknown key, a wrong type
// or a value out of range is a ConfigError naming `source` and the key.
AccelerometerConfig parse_accelerometer_config(const YAML::Node& sensor, const std::string& source);

// Reads the `installation:` mapping (the node given is the mapping itself); `prefix` is the
// path of its keys in messages ("sensor.installation."). Unknown key, wrong type, non-finite
// or out-of-range value: ConfigError naming `source` and the key.
InstallationConfig parse_installation_config(const YAML::Node& node, const std::string& source,
                                             const std::string& prefix);

}  // namespace bearing_sim
