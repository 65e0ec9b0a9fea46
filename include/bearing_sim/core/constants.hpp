#pragma once
// Mathematical constants of the whole package, defined once.
namespace bearing_sim {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;  // exact: doubling a double does not round

// The largest angle a user may give (a cage angle, a spall's position), rad: about 160,000
// turns. Doubles there are 1.2e-10 rad apart, so the angle is still known to far better than
// any ball's or spall's place; at 1e300 rad they are 1e284 rad apart and every ball added to
// it lands on the same double (all balls at one azimuth).
inline constexpr double kMaxAngleRad = 1e6;

}  // namespace bearing_sim
