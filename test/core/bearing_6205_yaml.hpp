#pragma once
// The 6205-like deep groove bearing of the health tests as bearing-file text (Z = 9,
// d = 7.94 mm, dm = 39.04 mm, inner ring rotating), for the core tests and the
// bearing_tool tests that write it to a file. Append imperfections/defects as needed.
#include <string>

namespace bearing_sim::test {

inline const std::string kBearing6205Yaml =
    "name: 6205-like\n"
    "balls_per_row: 9\n"
    "ball_diameter_mm: 7.94\n"
    "pitch_diameter_mm: 39.04\n"
    "inner_groove_curvature: 0.52\n"
    "outer_groove_curvature: 0.52\n"
    "rotating_ring: inner\n"
    "rotating_mass_kg: 0.5\n"
    "damping: {contact_damping_Ns_per_m: 100}\n";

}  // namespace bearing_sim::test
