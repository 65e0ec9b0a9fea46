#pragma once
// Mathematical constants of the whole package, defined once.
namespace bearing_sim {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;  // exact: doubling a double does not round

}  // namespace bearing_sim
