#pragma once
// bearing_tool's reports of a flexible ring (docs/model.md section 18, docs/bearing_tool.md):
// the static shape and modes beside the rigid ring's load distribution, and the offline
// simulation with the ring's modal coordinates.
#include <string>

#include <nlohmann/json.hpp>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/flexible_bearing.hpp"

namespace bearing_sim::tool {

// The ring's modes (free, on the seat), its static modal amplitudes, the linearized system's
// natural frequencies (with rotating_mass_kg) and the peak ball load beside the rigid ring's.
nlohmann::json flexible_ring_static_json(const FlexibleBearing& bearing, const FlexibleStaticSolution& solution,
                                         const StaticSolution& rigid);
void print_flexible_ring_static(const nlohmann::json& ring);

struct FlexibleSimulationRequest {
  std::string bearing_path;
  Vector5 load = Vector5::Zero();
  double ring_speed_rad_s = 0.0;
  double ring_speed_rpm = 0.0;
  double duration_s = 1.0;
  double rate_hz = 10000.0;
  int substeps = 0;  // 0: automatic (FlexibleDynamics)
  IntegrationMethod method = IntegrationMethod::ExponentialAdamsPec;
  std::string csv;  // empty: none
  bool json = false;
  bool allow_long_run = false;  // start a run estimated over an hour (--allow-long-run)
};

// Runs FlexibleDynamics and prints its summary (tables or JSON); writes the CSV if asked.
void run_flexible_simulation(const BearingModel& model, const FlexibleSimulationRequest& request);

}  // namespace bearing_sim::tool
