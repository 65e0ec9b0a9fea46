// Conservation law of the dynamic model: without damping and with the cage at rest, the
// energy 1/2 v'Mv + sum (2/5) Kn delta^2.5 - F.q is constant; with damping it decays.
// The convergence checks are classical RK4's (selected explicitly); the default exponential
// integrator has its own check at its automatic step.
#include <gtest/gtest.h>

#include <cmath>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
// Contact potential from the per-ball deflections: integral of Kn delta^1.5 is (2/5) Kn delta^2.5.
double energy(const BearingModel& model, const DynamicSample& s, const Vector5& load) {
  double v = 0.0;
  for (const BallState& b : model.ball_states(s.displacement, s.cage_angle_rad))
    if (b.deflection_m > 0) v += 0.4 * model.contact_stiffness() * std::pow(b.deflection_m, 2.5);
  return 0.5 * s.velocity.dot(model.mass_matrix() * s.velocity) + v - load.dot(s.displacement);
}

struct ReleaseRun {
  double e0, max_drift, swing, e_end;
};

ReleaseRun release(BearingConfig c, const Vector5& from, const Vector5& to, int samples, int substeps = 0,
                   IntegrationMethod method = IntegrationMethod::Rk4) {
  const BearingModel model(c);
  BearingDynamics dyn(model, from, 0.0,
                      DynamicsOptions{10000.0, substeps, true, method});  // cage at rest: time-invariant potential
  dyn.set_load(to);  // released from the old equilibrium: free vibration
  ReleaseRun r{energy(model, dyn.current(), to), 0.0, 0.0, 0.0};
  double kinetic_max = 0.0;
  for (int i = 0; i < samples; ++i) {
    const DynamicSample& s = dyn.step();
    const double e = energy(model, s, to);
    r.max_drift = std::max(r.max_drift, std::abs(e - r.e0));
    kinetic_max = std::max(kinetic_max, 0.5 * s.velocity.dot(model.mass_matrix() * s.velocity));
    r.e_end = e;
  }
  r.swing = kinetic_max;
  return r;
}
}  // namespace

TEST(Energy, ConservedWithoutDamping) {
  BearingConfig c = ct_bearing();
  c.contact_damping_Ns_per_m = 0.0;
  // Released from the 6800 N / 2100 N*m equilibrium to 8000 N / 2500 N*m: free vibration of
  // the ~1 kHz ring modes for 50 ms. RK4 is slightly dissipative: per step the energy of a mode
  // changes by ~(omega h)^6 / 72 (dissipation) plus 4th-order phase terms, so halving h must cut
  // the drift by at least 2^4 = 16 (RK4's order; ~30 is typical) and it must be < 1e-3 of the vibration energy at 8
  // steps per sample (omega h ~ 0.12).
  const Vector5 to = load5(8000, 0, 500, 0, 2500);
  const ReleaseRun r8 = release(c, ct_load(), to, 500, 8);
  const ReleaseRun r16 = release(c, ct_load(), to, 500, 16);
  ASSERT_GT(r8.swing, 0.0);
  EXPECT_LT(r8.max_drift, 1e-3 * r8.swing) << "drift " << r8.max_drift << " J, swing " << r8.swing << " J";
  EXPECT_LT(r16.max_drift, r8.max_drift / 16.0) << r16.max_drift << " vs " << r8.max_drift;
  // At the automatic step (omega_max h <= 0.5) the loss is visible but bounded: < 10% in 50 ms.
  const ReleaseRun ra = release(c, ct_load(), to, 500);
  EXPECT_LT(ra.max_drift, 0.1 * ra.swing);
}

TEST(Energy, ConservedWithoutDampingByTheExponentialIntegrator) {
  // The default integrator at its automatic step (one step per sample here, omega_max h
  // ~ 0.8): the linear part of the motion is exact, only the remainder's error drifts.
  BearingConfig c = ct_bearing();
  c.contact_damping_Ns_per_m = 0.0;
  const Vector5 to = load5(8000, 0, 500, 0, 2500);
  const ReleaseRun r = release(c, ct_load(), to, 500, 0, IntegrationMethod::ExponentialRk4);
  const ReleaseRun rk4 = release(c, ct_load(), to, 500, 0, IntegrationMethod::Rk4);
  ASSERT_GT(r.swing, 0.0);
  EXPECT_LT(r.max_drift, 1e-3 * r.swing) << "drift " << r.max_drift << " J, swing " << r.swing << " J";
  EXPECT_LT(r.max_drift, rk4.max_drift) << r.max_drift << " vs RK4 " << rk4.max_drift;
}

// The CT ring carrying a 690 kg rotor whose centre of gravity is 0.31 m off the bearing
// centre along the axis: the mass matrix couples x with theta_y and y with theta_x, and the
// energy 1/2 v^T M v + contact potential - load . q is conserved only if the dynamics use that
// same matrix (a diagonal or wrongly signed coupling drifts by the work of the missing terms).
TEST(Energy, ConservedWithACarriedBodyOffTheBearingCentre) {
  BearingConfig c = ct_bearing();
  c.contact_damping_Ns_per_m = 0.0;
  c.carried_body.mass_kg = 690.0;
  c.carried_body.centre_of_gravity_axial_m = 0.3088;
  c.carried_body.transverse_inertia_kg_m2 = 76.0;
  const BearingModel model(c);
  const Matrix5 m = model.mass_matrix();
  EXPECT_NEAR(m(0, 4), 690.0 * 0.3088, 1e-9);
  EXPECT_NEAR(m(1, 3), -690.0 * 0.3088, 1e-9);
  EXPECT_TRUE(m.isApprox(m.transpose()));
  const Vector5 to = load5(8000, 0, 500, 0, 2500);
  // The heavy ring's modes are ~4 times slower, so at 8 RK4 steps per sample (omega h ~ 0.03)
  // the truncation drift is at the rounding of the energy: only the bound is checked.
  const ReleaseRun r8 = release(c, ct_load(), to, 500, 8);
  ASSERT_GT(r8.swing, 0.0);
  EXPECT_LT(r8.max_drift, 1e-3 * r8.swing) << "drift " << r8.max_drift << " J, swing " << r8.swing << " J";
  const ReleaseRun adams = release(c, ct_load(), to, 500, 0, IntegrationMethod::ExponentialAdamsPec);
  EXPECT_LT(adams.max_drift, 1e-3 * adams.swing) << "drift " << adams.max_drift << " J, swing " << adams.swing << " J";
}

TEST(Energy, DecaysWithDamping) {
  const ReleaseRun r =
      release(ct_bearing(), ct_load(), load5(8000, 0, 500, 0, 2500), 500, 0, IntegrationMethod::ExponentialRk4);
  // 100 N s/m per contact damps the ~1 kHz modes by a few percent per cycle: over 50 ms most of
  // the vibration energy is gone.
  EXPECT_LT(r.e_end - (r.e0 - r.swing), 0.5 * r.swing);
  EXPECT_LT(r.e_end, r.e0);
}
