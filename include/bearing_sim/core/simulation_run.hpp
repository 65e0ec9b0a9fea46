#pragma once
// A fixed-input run of the dynamic model from the static equilibrium, with the summary
// that bearing_tool simulate, the tests and the benchmark report.
#include <functional>

#include "bearing_sim/core/bearing_dynamics.hpp"

namespace bearing_sim {

struct SimulationRequest {
  Vector5 load = Vector5::Zero();  // Fx, Fy, Fz (N), Mx, My (N*m) on the moving ring
  double ring_speed_rad_s = 0.0;   // of the configured rotating ring
  double duration_s = 1.0;
  double sample_rate_hz = 10000.0;
  int substeps = 0;  // 0: automatic
  IntegrationMethod method = kDefaultIntegrationMethod;
};

struct SimulationSummary {
  std::size_t samples = 0;
  double substeps = 0.0;  // internal steps per sample (e.g. 1.25: five per four samples)
  double internal_step_s = 0.0;
  // Over the second half of the run (the start-up transient excluded), mean removed.
  double a_rms_x = 0.0;  // m/s^2
  double a_rms_y = 0.0;
  double a_rms_z = 0.0;
  double level_db = 0.0;  // L of a_rms_x
  Vector5 mean_displacement = Vector5::Zero();
  double realtime_factor = 0.0;  // simulated seconds per wall second of the integration
};

// Calls on_sample (if given) for every sample in order. A bearing file with a flexible_ring
// block runs FlexibleDynamics (make_ring_dynamics; integrator adams_pec or rk4), the samples
// its rigid-body coordinates. Throws like BearingDynamics / FlexibleDynamics.
SimulationSummary run_simulation(const BearingModel& model, const SimulationRequest& request,
                                 const std::function<void(const DynamicSample&)>& on_sample = {});

}  // namespace bearing_sim
