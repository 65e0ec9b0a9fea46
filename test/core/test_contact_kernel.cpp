// The fast contact-force loop (AVX-512 where the CPU has it) must give the portable
// loop's forces: same formulas and correctly rounded square roots, only the order of the
// operations and of the sums differs.
#include <gtest/gtest.h>

#include <random>

#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

void expect_kernels_agree(const BearingModel& model, const Vector5& load) {
  const Vector5 q0 = solve_static(model, load).displacement;
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  const double scale = load.head<3>().norm() + load.tail<2>().norm() / model.pitch_radius_m();
  for (int trial = 0; trial < 200; ++trial) {
    Vector5 q = q0, v;
    for (int i = 0; i < 5; ++i) {
      q[i] += 0.2 * std::abs(q0[i]) * n(rng);  // around the load zone, balls entering and leaving
      v[i] = 1e-3 * n(rng) * (i < 3 ? 1.0 : 1.0 / model.pitch_radius_m());
    }
    const RollingPhase phase{0.1 * trial};
    const Vector5 fast = model.contact_force(q, v, phase, model.balls(), BearingModel::ContactKernel::Fastest);
    const Vector5 portable = model.contact_force(q, v, phase, model.balls(), BearingModel::ContactKernel::Portable);
    Vector5 scaled = fast - portable;
    scaled.tail<2>() /= model.pitch_radius_m();
    // Rounding of a few hundred ball forces summed in a different order: 1e-12 of the load.
    EXPECT_LT(scaled.norm(), 1e-12 * scale) << "trial " << trial;
  }
}

TEST(ContactKernel, FastAndPortableLoopsAgreeForTheCtBearing) {
  expect_kernels_agree(BearingModel(test::ct_bearing()), test::ct_load());
}

TEST(ContactKernel, FastAndPortableLoopsAgreeForAPreloadedInnerRingBearing) {
  BearingConfig c = test::single_row(13, 9.0, 46.0, 25.0, 0.52, 0.53, -3.0,
                                     "rotating_ring: inner\nrotating_mass_kg: 1\ndamping: {contact_damping_Ns_per_m: 300}\n");
  expect_kernels_agree(BearingModel(c), test::load5(800.0, -300.0, 1500.0, 5.0, -3.0));
}

}  // namespace
}  // namespace bearing_sim
