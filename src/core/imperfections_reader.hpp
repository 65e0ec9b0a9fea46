#pragma once
// The reader of a bearing file's `imperfections:` and `defects:` sections (docs/bearing_file.md),
// apart from their physics (imperfections.hpp). Internal to the core library.
#include <string>

#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim {

// Parses the `imperfections:` and `defects:` sections of a bearing file (either may be
// a null node) for a bearing of `rows` rows (the `row:` keys must name one of them).
// Throws ConfigError naming the source and key.
ImperfectionSpec parse_imperfections(const YAML::Node& imperfections, const YAML::Node& defects,
                                     const std::string& source, int rows = 2);

}  // namespace bearing_sim
