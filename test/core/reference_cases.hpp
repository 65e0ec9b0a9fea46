#pragma once
// Reference cases shared by the core tests, the benchmark and the integrator study, so that
// their figures are of the same bearing. Paths are relative to the package's source folder.
#include <string>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim::test {

// The CT gantry bearing (config/bearings/ct_gantry_lyc.yaml) with the waviness and the
// inner-race spall of config/imperfections/ct_gantry_waviness_and_spall.yaml.
inline BearingConfig ct_gantry_with_defects(const std::string& source_dir) {
  BearingConfig config = load_bearing_config(source_dir + "/config/bearings/ct_gantry_lyc.yaml");
  const std::string file = source_dir + "/config/imperfections/ct_gantry_waviness_and_spall.yaml";
  config.imperfections = load_imperfections(file, config.rows);
  return config;
}

}  // namespace bearing_sim::test
