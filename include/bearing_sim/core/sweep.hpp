#pragma once
// Parameter studies ("sweeps") over a base bearing file: the CT paper's figures 3-4
// (L against groove curvature, balls per row, clearance, axial load ratio) and the INS
// paper's stiffness-against-load curves. A definition (YAML, docs/bearing_tool.md
// "sweep") names the base bearing file, the operating point, optional sets of
// imperfections (waviness, roughness) and one or more studies (a parameter and its
// values). Each case is an independent quasi-static solution and, for dynamic sweeps,
// a run_simulation; cases run in parallel, each with its own BearingModel.
#include <functional>
#include <string>
#include <vector>

#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/simulation_run.hpp"

namespace bearing_sim {

struct SweepOperatingPoint {
  Vector5 load = Vector5::Zero();  // Fx, Fy, Fz (N), Mx, My (N*m) on the moving ring
  double speed_rpm = 0.0;          // of the bearing file's rotating ring
  double duration_s = 0.5;
  double sample_rate_hz = 10000.0;
};

struct SweepImperfectionSet {
  std::string name;
  // The `imperfections:` mapping as YAML text, as in a bearing file but `order` may be "Z",
  // "Z-1", "2Z+1", ... (resolved for each case); empty or null: none.
  std::string imperfections_yaml;
  bool from_bearing_file = false;
};

struct SweepStudy {
  std::string parameter;
  std::vector<double> values;
};

struct SweepDefinition {
  std::string name;
  std::string source;        // the definition file, for messages
  std::string bearing_path;  // resolved
  std::string bearing_yaml;  // the base bearing file's text (each case varies its keys)
  SweepOperatingPoint operating_point;
  bool dynamic = true;  // false: quasi-static only (stiffness against load)
  std::vector<SweepImperfectionSet> imperfection_sets;
  std::vector<SweepStudy> studies;
};

struct SweepCase {
  int study = 0;
  std::string parameter;
  double value = 0.0;
  int imperfection_set = 0;
  std::string imperfection_set_name;
  BearingConfig config;  // the varied bearing (validated)
  SweepOperatingPoint operating_point;
};

struct SweepResult {
  SweepCase c;
  bool ok = false;
  std::string error;  // when !ok: why (load not carried, divergence)
  StaticSolution statics;
  // Undamped natural frequencies of the moving ring on its contacts at the static
  // equilibrium (K phi = w^2 diag(m, m, m, J, J) phi), ascending, Hz; zeros without a mass.
  Vector5 ring_modes_hz = Vector5::Zero();
  bool dynamic = false;
  SimulationSummary dynamics;
  double wall_s = 0.0;
};

// The parameters a study may vary, with what they change (one table in sweep.cpp).
struct SweepParameterInfo {
  std::string name;
  std::string description;
};
const std::vector<SweepParameterInfo>& sweep_parameters();

// Reads and checks a definition; the bearing path is relative to the definition file
// (from_string: to base_dir). Throws InvalidInputError naming the file (source) and key
// (also for a value of a study that makes the bearing file invalid, e.g. a groove
// curvature <= 0.5).
SweepDefinition load_sweep_definition(const std::string& path);
SweepDefinition sweep_definition_from_string(const std::string& yaml_text, const std::string& source,
                                             const std::string& base_dir);

// All cases, study by study, imperfection set by set, value by value (validated).
std::vector<SweepCase> sweep_cases(const SweepDefinition& definition);

// One case (throws nothing for a load not carried or a divergence: the result says so).
SweepResult run_sweep_case(const SweepCase& c, bool dynamic);

// Runs every case on `threads` threads (0: hardware_concurrency); results in case order,
// identical for any thread count. on_done (optional) is called after each case under a lock.
std::vector<SweepResult> run_sweep(
    const SweepDefinition& definition, int threads = 0,
    const std::function<void(const SweepResult&, std::size_t done, std::size_t total)>& on_done = {});

// CSV with a header row (columns in docs/bearing_tool.md).
std::string sweep_csv_header();
std::string sweep_csv_row(const SweepResult& r);

}  // namespace bearing_sim
