#pragma once
// The reader of a bearing file's YAML (docs/bearing_file.md), for the core's other readers
// (a sweep varies the keys of a bearing file). Internal to the core library.
#include <string>

#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/bearing_config.hpp"

namespace bearing_sim {

// Parses and validates; throws ConfigError naming `source` (a file name) and the key.
BearingConfig parse_bearing_config(const YAML::Node& root, const std::string& source);

}  // namespace bearing_sim
