// Loads the bearing cannot carry and non-finite loads (docs/model.md section 6.2): a clear error,
// promptly, not a hang or a NaN.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
template <class F>
double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
// Generous: a Newton solve takes well under a millisecond; 2 s only catches a hang.
constexpr double kPromptS = 2.0;
}  // namespace

TEST(LoadErrors, AxialForceAgainstSingleRowAngularContact) {
  const BearingModel model(single_row(12, 12.7, 65.0, 25.0, 0.52, 0.53));
  // Carried one way (outer ring pushed towards -z onto its contacts)...
  EXPECT_NO_THROW(solve_static(model, load5(0, 0, -1000, 0, 0)));
  // ...not the other: the balls lift off.
  const double t = seconds([&] { EXPECT_THROW(solve_static(model, load5(0, 0, 1000, 0, 0)), LoadNotCarriedError); });
  EXPECT_LT(t, kPromptS);
  // Same with a radial component that the bearing alone could carry.
  EXPECT_THROW(solve_static(model, load5(500, 0, 2000, 0, 0)), LoadNotCarriedError);
}

TEST(LoadErrors, HugeRadialLoad) {
  const BearingModel model(iso_reference_bearing());
  const double t = seconds([&] { EXPECT_THROW(solve_static(model, load5(1e9, 0, 0, 0, 0)), LoadNotCarriedError); });
  EXPECT_LT(t, kPromptS);
  // The message says which bearing and which load.
  try {
    solve_static(model, load5(1e9, 0, 0, 0, 0));
  } catch (const LoadNotCarriedError& e) {
    EXPECT_NE(std::string(e.what()).find("ISO/TS 16281 reference"), std::string::npos) << e.what();
  }
}

TEST(LoadErrors, MomentOnADeepGrooveSingleRow) {
  // A single row at a0 = 0 has (almost) no tilt stiffness: a large moment is not carried.
  const BearingModel model(iso_reference_bearing());
  const double t = seconds([&] { EXPECT_THROW(solve_static(model, load5(0, 0, 0, 0, 1e5)), LoadNotCarriedError); });
  EXPECT_LT(t, kPromptS);
}

TEST(LoadErrors, NonFiniteLoad) {
  const BearingModel model(ct_bearing());
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(solve_static(model, load5(nan, 0, 0, 0, 0)), InvalidInputError);
  EXPECT_THROW(solve_static(model, load5(0, 0, 0, 0, inf)), InvalidInputError);
  EXPECT_THROW(solve_static(model, ct_load(), nan), InvalidInputError);
  EXPECT_THROW(BearingDynamics(model, load5(6800, nan, 0, 0, 2100), kCtSpeedRadS), InvalidInputError);
}

TEST(LoadErrors, ZeroLoadIsTheOrigin) {
  // No load, no clearance: the unloaded position, at once.
  const StaticSolution s = solve_static(BearingModel(ct_bearing()), Vector5::Zero());
  EXPECT_EQ(s.displacement.norm(), 0.0);
  EXPECT_EQ(s.max_ball_load_N, 0.0);
}
