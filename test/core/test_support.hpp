#pragma once
// Shared fixtures of the core tests.
#include <string>

#include "bearing_sim/core/bearing_config.hpp"

namespace bearing_sim::test {

// Path of a shipped bearing file, e.g. bearing_file("ct_gantry_lyc.yaml").
std::string bearing_file(const std::string& name);

// The ISO/TS 16281 reference bearing of MODEL.md section 4 (6 balls, 11.1 mm, a0 = 0).
BearingConfig iso_reference_bearing(double clearance_m = 0.0);

}  // namespace bearing_sim::test
