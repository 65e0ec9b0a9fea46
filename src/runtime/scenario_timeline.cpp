#include "bearing_sim/runtime/scenario_timeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <string>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace runtime {
namespace {

void check_rate(double rate_hz, const char* name) {
  if (!std::isfinite(rate_hz) || !(rate_hz > 0.0))
    throw InvalidInputError(std::string("scenario player: ") + name + " must be finite and > 0, got " +
                            std::to_string(rate_hz));
}

// Index of the grid cell [k / rate, (k + 1) / rate) holding t.
std::int64_t cell(double t, double rate_hz) { return static_cast<std::int64_t>(std::floor(t * rate_hz)); }

}  // namespace

ScenarioTimeline::ScenarioTimeline(const Scenario& scenario, TimelineSettings settings)
    : scenario_(scenario), settings_(settings) {
  check_rate(settings_.speed_rate_hz, "speed_rate_hz");
  check_rate(settings_.load_rate_hz, "load_rate_hz");
  check_rate(settings_.state_rate_hz, "state_rate_hz");
}

TimelineCommand ScenarioTimeline::command(TimelineCommand::Kind kind, double t) const {
  TimelineCommand c;
  c.kind = kind;
  c.scenario_time_s = t;
  c.pass = pass_;
  return c;
}

void ScenarioTimeline::start_pass() {
  next_event_ = 0;
  next_speed_cell_ = next_load_cell_ = next_state_cell_ = 0;
}

std::vector<TimelineCommand> ScenarioTimeline::advance(double elapsed_s) {
  std::vector<TimelineCommand> out;
  if (finished_) return out;
  const double duration = scenario_.duration_s();
  for (;;) {
    const double t = std::max(0.0, elapsed_s - pass_start_s_);
    if (!(t >= duration)) {  // also a NaN elapsed time: nothing beyond what is due at the last t
      if (std::isfinite(t)) emit_due(t, false, &out);
      return out;
    }
    // The rest of this pass, with the final values and labels exactly at its end.
    emit_due(duration, true, &out);
    if (!settings_.loop) {
      finished_ = true;
      out.push_back(command(TimelineCommand::Kind::End, duration));
      return out;
    }
    pass_start_s_ += duration;
    ++pass_;
    start_pass();
    out.push_back(command(TimelineCommand::Kind::ClearDefects, 0.0));
  }
}

void ScenarioTimeline::emit_due(double t, bool end_of_pass, std::vector<TimelineCommand>* out) {
  using Kind = TimelineCommand::Kind;
  bool event_fired = false;
  const std::vector<ScenarioDefectEvent>& events = scenario_.defect_events();
  while (next_event_ < events.size() && events[next_event_].time_s <= t) {
    TimelineCommand c = command(Kind::DefectEvent, t);
    c.event = events[next_event_++];
    out->push_back(std::move(c));
    event_fired = true;
  }

  const ScenarioInputs in = scenario_.inputs_at(t);
  if (end_of_pass || cell(t, settings_.speed_rate_hz) >= next_speed_cell_) {
    next_speed_cell_ = cell(t, settings_.speed_rate_hz) + 1;
    if (!have_sent_inputs_ || in.ring_speed_rad_s != last_speed_rad_s_) {
      TimelineCommand c = command(Kind::Speed, t);
      c.speed_rad_s = in.ring_speed_rad_s;
      out->push_back(std::move(c));
      last_speed_rad_s_ = in.ring_speed_rad_s;
    }
  }
  if (end_of_pass || cell(t, settings_.load_rate_hz) >= next_load_cell_) {
    next_load_cell_ = cell(t, settings_.load_rate_hz) + 1;
    if (!have_sent_inputs_ || in.load != last_load_) {
      TimelineCommand c = command(Kind::Load, t);
      c.load = in.load;
      out->push_back(std::move(c));
      last_load_ = in.load;
    }
    // Each change is a new model in the node (ramps come as 0.1 K steps): only on change.
    if (scenario_.has_ring_temperature_difference() &&
        (!have_sent_inputs_ || in.ring_temperature_difference_K != last_ring_temperature_K_)) {
      TimelineCommand c = command(Kind::RingTemperature, t);
      c.ring_temperature_difference_K = in.ring_temperature_difference_K;
      out->push_back(std::move(c));
      last_ring_temperature_K_ = in.ring_temperature_difference_K;
    }
  }
  have_sent_inputs_ = true;
  if (end_of_pass || event_fired || cell(t, settings_.state_rate_hz) >= next_state_cell_) {
    next_state_cell_ = cell(t, settings_.state_rate_hz) + 1;
    out->push_back(command(Kind::State, t));
  }
}

std::string scenario_limit_refusal(const Scenario& scenario, const InputLimits& limits) {
  constexpr double kRadSToRpm = 60.0 / (2.0 * 3.14159265358979323846);
  for (const Scenario::InputExtreme& e : scenario.input_extremes()) {
    std::ostringstream why;
    if (e.force_N > limits.max_force_N) {
      // The unbalance named when the load alone stays within the limit.
      if (e.unbalance_N > 0.0 && e.load_force_N <= limits.max_force_N)
        why << "load.unbalance: with the load of " << e.force_key << " |(Fx, Fy, Fz)| reaches " << e.force_N
            << " N at t = " << e.time_s << " s (the unbalance's " << e.unbalance_N << " N at " << e.speed_signed_rad_s
            << " rad/s, at its worst angle)";
      else
        why << e.force_key << ": |(Fx, Fy, Fz)| = " << e.force_N << " N at t = " << e.time_s << " s"
            << (e.unbalance_N > 0.0 ? " (the unbalance included)" : "");
      why << " exceeds the node's max_force_N = " << limits.max_force_N << " N";
    } else if (e.moment_Nm > limits.max_moment_Nm) {
      why << e.moment_key << ": |(Mx, My)| = " << e.moment_Nm << " N*m at t = " << e.time_s
          << " s exceeds the node's max_moment_Nm = " << limits.max_moment_Nm << " N*m";
    } else if (e.speed_rad_s > limits.max_speed_rad_s) {
      why << (e.speed_key.empty() ? "speed" : e.speed_key) << ": |speed| = " << e.speed_rad_s << " rad/s ("
          << e.speed_rad_s * kRadSToRpm << " rpm) at t = " << e.time_s
          << " s exceeds the node's max_speed_rad_s = " << limits.max_speed_rad_s << " rad/s";
    }
    if (!why.str().empty()) return why.str();
  }
  return "";
}

std::string scenario_node_parameter(const Scenario& scenario, const std::string& name) {
  if (name == "bearing_file") return scenario.bearing_file();
  if (name == "sensor_file") return scenario.sensor_file();
  const ScenarioInputs in = scenario.inputs_at(0.0);
  const char* const load_names[5] = {"initial_force_x_N", "initial_force_y_N", "initial_force_z_N",
                                     "initial_moment_x_Nm", "initial_moment_y_Nm"};
  double value = 0.0;
  if (name == "initial_speed_rad_s") {
    value = in.ring_speed_rad_s;
  } else {
    const auto* it = std::find(std::begin(load_names), std::end(load_names), name);
    if (it == std::end(load_names))
      throw InvalidInputError("unknown node parameter '" + name +
                              "' (bearing_file, sensor_file, initial_force_{x,y,z}_N, "
                              "initial_moment_{x,y}_Nm, initial_speed_rad_s)");
    value = in.load[it - std::begin(load_names)];
  }
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", value);  // round-trips the double
  return buf;
}

}  // namespace runtime
}  // namespace bearing_sim
