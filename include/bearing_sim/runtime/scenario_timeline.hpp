#pragma once
// What the scenario player sends when (ROS-free; scenario_player_node is its ROS shell).
// The player calls advance() with the time since playback started, on the node's clock;
// it gets the commands due since the last call, in the order to execute them.
#include <cstdint>
#include <string>
#include <vector>

#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/input_validator.hpp"

namespace bearing_sim {
namespace runtime {

// The node applies its inputs once per chunk (10 ms at the launch's 100 samples at 10 kHz),
// so 100 Hz is the finest staircase it can follow.
struct TimelineSettings {
  double speed_rate_hz = 100.0;  // grid of speed updates (each sent only if the speed changed)
  double load_rate_hz = 100.0;   // grid of load updates (only if changed: each costs the node a static solution)
  double state_rate_hz = 10.0;   // ScenarioState labels (also right after every defect event)
  bool loop = false;             // at the end start again (defects cleared); else finish
};

struct TimelineCommand {
  enum class Kind {
    ClearDefects,  // a new pass of a looping scenario begins
    DefectEvent,   // `event` is due: a spall appears, or a clear
    Speed,         // `speed_rad_s` = the scenario's at `scenario_time_s`
    Load,          // `load` = the scenario's at `scenario_time_s` (unbalance included)
    // `ring_temperature_difference_K` changed (on the load grid; only for a scenario with the key)
    RingTemperature,
    State,  // publish the labels at `scenario_time_s`
    End     // the scenario is over (not looping): the node keeps the last inputs
  };
  Kind kind = Kind::State;
  double scenario_time_s = 0.0;  // within the current pass: evaluate the scenario here
  std::uint64_t pass = 0;        // 0 for the first pass
  ScenarioDefectEvent event;
  double speed_rad_s = 0.0;
  Vector5 load = Vector5::Zero();
  double ring_temperature_difference_K = 0.0;
};

class ScenarioTimeline {
 public:
  // Throws InvalidInputError for a rate that is not finite and > 0.
  ScenarioTimeline(const Scenario& scenario, TimelineSettings settings);

  // Commands due at `elapsed_s` since playback started (non-decreasing; the first call,
  // usually at 0, sends the speed, load, events at 0 and state). An event fires exactly
  // once per pass, at the first call at or after its time, in the scenario's order.
  std::vector<TimelineCommand> advance(double elapsed_s);

  bool finished() const { return finished_; }
  std::uint64_t pass() const { return pass_; }
  const TimelineSettings& settings() const { return settings_; }

 private:
  void emit_due(double t, bool end_of_pass, std::vector<TimelineCommand>* out);
  TimelineCommand command(TimelineCommand::Kind kind, double t) const;
  void start_pass();

  const Scenario& scenario_;
  TimelineSettings settings_;
  double pass_start_s_ = 0.0;
  std::uint64_t pass_ = 0;
  bool finished_ = false;
  std::size_t next_event_ = 0;
  // Next grid cell (index) on which each output may go out.
  std::int64_t next_speed_cell_ = 0, next_load_cell_ = 0, next_state_cell_ = 0;
  bool have_sent_inputs_ = false;
  double last_speed_rad_s_ = 0.0;
  Vector5 last_load_ = Vector5::Zero();
  double last_ring_temperature_K_ = 0.0;
};

// Why bearing_sim_node with these input limits (its max_force_N, max_moment_Nm and
// max_speed_rad_s) would refuse an input of the scenario, "" if it would refuse none. The
// node refuses such an input and runs on at the last good one, so the labels would say an
// input the data never had; the scenario player refuses the scenario before its first
// sample instead. Checks every extreme of the time line (Scenario::input_extremes: the
// unbalance at its worst angle) with the node's rule (a magnitude above its limit) and
// names the first in time: the key that sets it, the value, the time and the limit, e.g.
//   load.segments[0].force_N: |(Fx, Fy, Fz)| = 150000 N at t = 1 s exceeds the node's max_force_N = 100000 N
std::string scenario_limit_refusal(const Scenario& scenario, const InputLimits& limits);

// A parameter of bearing_sim_node for a run of this scenario, as text for roslaunch
// (`scenario_player --param NAME FILE`): bearing_file, sensor_file (resolved paths), and the
// inputs at t = 0: initial_force_{x,y,z}_N, initial_moment_{x,y}_Nm, initial_speed_rad_s.
// Throws InvalidInputError for another name.
std::string scenario_node_parameter(const Scenario& scenario, const std::string& name);

}  // namespace runtime
}  // namespace bearing_sim
