// A diverging RK4 step on the running node: reported as ERROR, model reset to the static
// equilibrium, never NaN, and recovery. The node runs test/ros/ct_light_ring.yaml (the CT
// bearing with a 1 kg ring) with ~integrator: rk4 and a fixed ~substeps: 3, so that the cfg's maximum contact
// damping (2000 N*s/m, a physical value) is beyond the step's stability limit: the core
// picks a stable step by itself only in automatic mode (~substeps: 0).
#include <dynamic_reconfigure/Reconfigure.h>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "node_test_support.hpp"
#include "service_calls.hpp"

using namespace node_test;

namespace {
constexpr double kRate = 10000.0;

bool reconfigure(const std::string& name, double value) {
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::DoubleParameter p;
  p.name = name;
  p.value = value;
  srv.request.config.doubles.push_back(p);
  return bearing_sim::test::call_until_answered("bearing_sim_node/set_parameters", srv);
}

void settle(std::uint64_t from, double seconds) {
  ASSERT_TRUE(recorder().wait_for_sample(from + static_cast<std::uint64_t>(seconds * kRate), 10.0 + 2 * seconds));
}

void expect_mean_at_static(std::uint64_t from, std::uint64_t to, const bearing_sim::BearingModel& model) {
  const bearing_sim::StaticSolution s = bearing_sim::solve_static(model, ct_load());
  const double scale = s.displacement.head<3>().norm();
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(recorder().mean_displacement(c, from, to), s.displacement[c], 0.005 * scale) << "axis " << c;
}
}  // namespace

TEST(NodeInputs, DivergenceIsReportedAsErrorAndResetNeverNaN) {
  ASSERT_TRUE(recorder().wait_for_sample(0, 60.0)) << "no vibration samples";
  // Independent check of the premise, from the core's linearization: |lambda| h of the
  // fastest mode is below the RK4 limit (~2.8) at 100 N*s/m and far above it at 2000.
  bearing_sim::BearingModel model = ct_model();
  auto damped = model.config();
  damped.contact_damping_Ns_per_m = 2000.0;
  const double h = 1.0 / (3.0 * kRate);
  EXPECT_LT(bearing_sim::BearingDynamics::fastest_rate_rad_s(model, ct_load()) * h, 2.5);
  EXPECT_GT(bearing_sim::BearingDynamics::fastest_rate_rad_s(bearing_sim::BearingModel(damped), ct_load()) * h, 6.0);

  // Healthy first: no divergence at the file's damping.
  settle(recorder().next_index(), 0.5);
  ASSERT_TRUE(recorder().wait_for_new_diagnostics(1, 15.0));
  diagnostic_msgs::DiagnosticStatus model_status;
  ASSERT_TRUE(recorder().diagnostic("Model", &model_status));
  EXPECT_EQ(Recorder::value(model_status, "divergences"), "0");

  ASSERT_TRUE(reconfigure("contact_damping_Ns_per_m", 2000.0));
  settle(recorder().next_index(), 0.5);
  ASSERT_TRUE(recorder().wait_for_new_diagnostics(2, 15.0));
  ASSERT_TRUE(recorder().diagnostic("Model", &model_status));
  EXPECT_EQ(model_status.level, diagnostic_msgs::DiagnosticStatus::ERROR);
  EXPECT_GT(std::stoi(Recorder::value(model_status, "divergences")), 0);
  EXPECT_EQ(recorder().non_finite(), 0u);  // reset to the equilibrium, never NaN

  // Back to the file's damping: the model recovers to the static equilibrium and stops diverging.
  ASSERT_TRUE(reconfigure("contact_damping_Ns_per_m", 100.0));
  const std::uint64_t sent = recorder().next_index();
  settle(sent, 1.0);
  expect_mean_at_static(sent + 5000, sent + 10000, model);
  ASSERT_TRUE(recorder().wait_for_new_diagnostics(1, 15.0));
  ASSERT_TRUE(recorder().diagnostic("Model", &model_status));
  const int count = std::stoi(Recorder::value(model_status, "divergences"));
  ASSERT_TRUE(recorder().wait_for_new_diagnostics(1, 15.0));
  ASSERT_TRUE(recorder().diagnostic("Model", &model_status));
  EXPECT_EQ(std::stoi(Recorder::value(model_status, "divergences")), count);
  EXPECT_EQ(recorder().gaps(), 0u);
  EXPECT_EQ(recorder().repeats(), 0u);
  EXPECT_EQ(recorder().non_finite(), 0u);
}

NODE_TEST_MAIN("test_node_divergence")
