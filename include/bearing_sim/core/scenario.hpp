#pragma once
// A scenario: a time line of the rotating ring's speed, the load on it (with an optional
// rotating unbalance) and defect events, read from a YAML file (docs/scenarios.md).
// The live scenario player and the offline dataset generator both ask it for the inputs
// at a time, so that they agree to the last bit.
#include <cstdint>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim {

// The longest scenario run: a scenario file's duration_s and a duration given in its place
// (bearing_tool generate --duration-s, bearing_sim.generate duration_s).
constexpr double kMaxScenarioDurationS = 1e7;

class ScenarioReader;

// Inputs of the simulation at one scenario time.
struct ScenarioInputs {
  Vector5 load = Vector5::Zero();  // Fx, Fy, Fz (N), Mx, My (N*m) on the rotating ring, unbalance included
  double ring_speed_rad_s = 0.0;
  double ring_angle_rad = 0.0;                 // integral of the speed from t = 0 (not wrapped)
  std::string phase;                           // name of the phase the time lies in ("" if none)
  double ring_temperature_difference_K = 0.0;  // inner minus outer ring
};

struct ScenarioDefectEvent {
  enum class Kind { Spall, Clear };
  Kind kind = Kind::Spall;
  double time_s = 0.0;
  Spall spall;  // Kind::Spall: growth rates in m/s, created_at_s = time_s
};

struct ScenarioPhase {
  std::string name;
  double start_s = 0.0;  // the phase lasts until the next one starts (the last one until the end)
};

// Rotating unbalance: a mass at a radius on the rotating ring. Its reaction on the ring
// is m e (omega^2 along the mass and -alpha perpendicular to it), turning with the ring.
struct Unbalance {
  double mass_kg = 0.0;
  double radius_m = 0.0;
  double phase_rad = 0.0;  // angle of the mass at ring angle 0, from the x axis towards y
};

class Scenario {
 public:
  // Throw ConfigError naming the file and the key for anything malformed, unknown or
  // impossible (including a defect that does not fit the bearing).
  static Scenario load(const std::string& path);
  // `source` names the text in errors; relative bearing/sensor paths resolve against its
  // directory (the working directory if it has none).
  static Scenario from_string(const std::string& yaml, const std::string& source);

  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  const std::string& source() const { return source_; }
  double duration_s() const { return duration_s_; }
  std::uint64_t seed() const { return seed_; }
  double sample_rate_hz() const { return sample_rate_hz_; }          // for the offline generator
  const std::string& bearing_file() const { return bearing_file_; }  // resolved path
  const std::string& sensor_file() const { return sensor_file_; }    // resolved, may be empty
  const std::vector<ScenarioPhase>& phases() const { return phases_; }
  const Unbalance& unbalance() const { return unbalance_; }

  // Speed, angle, load and phase at a time >= 0 (after duration_s: the final values held,
  // the angle still advancing). Throws InvalidInputError for a negative or non-finite time.
  ScenarioInputs inputs_at(double time_s) const;
  double ring_speed_at(double time_s) const;
  double ring_angle_at(double time_s) const;
  // Load with the unbalance (inputs_at(t).load without the phase look-up).
  Vector5 load_at(double time_s) const;
  // Load without the unbalance.
  Vector5 base_load_at(double time_s) const;
  // Reaction of the unbalance on the ring at that speed, acceleration and ring angle.
  Vector5 unbalance_load(double speed_rad_s, double acceleration_rad_s2, double ring_angle_rad) const;
  std::string phase_at(double time_s) const;

  // Inner minus outer ring temperature (K) at a time: steps and ramps, a ramp applied as a
  // staircase of kTemperatureStepK (each step is a new model, docs/scenarios.md).
  double ring_temperature_difference_at(double time_s) const;
  bool has_ring_temperature_difference() const { return has_temperature_; }
  static constexpr double kTemperatureStepK = 0.1;

  // Defect events in time order.
  const std::vector<ScenarioDefectEvent>& defect_events() const { return defect_events_; }

  // The largest inputs the time line sends, for limits the reader does not know (the node's
  // max_force_N, max_moment_Nm and max_speed_rad_s, checked by the scenario player before the
  // first sample: docs/scenarios.md "Labels"). Between two consecutive times at which a load
  // or speed piece starts or ends, the load is constant or linear and the speed constant,
  // linear or decaying, so each magnitude below is convex there and largest at one of the two
  // ends: the list holds both ends of every such stretch (the pieces of the stretch evaluated
  // at each end), and the state at duration_s, in time order.
  struct InputExtreme {
    double time_s = 0.0;
    // |(Fx, Fy, Fz)| with the rotating unbalance at its worst angle (along the radial force):
    // sqrt((|(Fx, Fy)| + U)^2 + Fz^2), U = m e sqrt(omega^4 + alpha^2).
    double force_N = 0.0;
    double unbalance_N = 0.0;   // U, 0 without an unbalance
    double load_force_N = 0.0;  // |(Fx, Fy, Fz)| of the load alone
    double moment_Nm = 0.0;     // |(Mx, My)|
    double speed_rad_s = 0.0;   // |speed|
    double speed_signed_rad_s = 0.0;
    // The keys of the file that set the load and the speed there, e.g. "load.segments[1].force_N",
    // "load.initial.moment_Nm", "speed.segments[0].to_speed_rpm" ("" for a speed never set: 0).
    std::string force_key, moment_key, speed_key;
  };
  std::vector<InputExtreme> input_extremes() const;
  // The spalls present at a time (events at or before it), in the order they appeared.
  std::vector<Spall> spalls_at(double time_s) const;
  // Width and depth of a spall at a time (its growth law: linear from its creation).
  static double spall_width_at(const Spall& spall, double time_s);
  static double spall_depth_at(const Spall& spall, double time_s);

 private:
  friend class ScenarioReader;  // src/core/scenario_reader.cpp: fills the time lines from the file

  // Pieces of the piecewise time lines.
  struct SpeedPiece {
    enum class Kind { Hold, Ramp, Coast };
    Kind kind = Kind::Hold;
    double start_s = 0.0, end_s = 0.0;  // end_s = infinity for the last piece
    double start_speed = 0.0;           // rad/s
    double end_speed = 0.0;             // ramp target
    double time_constant_s = 0.0;       // coast
    double start_angle = 0.0;           // rad, integral of the pieces before
    // Keys that set the speed at the start and the target (input_extremes).
    std::string start_key, end_key;
  };
  struct LoadPiece {
    double start_s = 0.0, end_s = 0.0;  // a step has end_s == start_s
    Vector5 from = Vector5::Zero(), to = Vector5::Zero();
    // Keys that set the force and the moment of `from` and `to` (input_extremes).
    std::string from_force_key, from_moment_key, to_force_key, to_moment_key;
  };

  Scenario() = default;
  const SpeedPiece& speed_piece(double time_s) const;
  static double piece_speed(const SpeedPiece& p, double time_s);
  static double piece_acceleration(const SpeedPiece& p, double time_s);
  static double piece_angle(const SpeedPiece& p, double time_s);

  std::string name_, description_, source_;
  double duration_s_ = 0.0;
  std::uint64_t seed_ = 1;
  double sample_rate_hz_ = 10000.0;
  std::string bearing_file_, sensor_file_;
  std::vector<ScenarioPhase> phases_;
  std::vector<SpeedPiece> speed_;  // contiguous from t = 0 to infinity
  Vector5 initial_load_ = Vector5::Zero();
  std::vector<LoadPiece> load_;  // sorted, not overlapping
  struct TemperaturePiece {
    double start_s = 0.0, end_s = 0.0;  // a step has end_s == start_s
    double from_K = 0.0, to_K = 0.0;
  };
  bool has_temperature_ = false;
  double initial_temperature_K_ = 0.0;
  std::vector<TemperaturePiece> temperature_;  // sorted, not overlapping
  Unbalance unbalance_;
  std::vector<ScenarioDefectEvent> defect_events_;
};

}  // namespace bearing_sim
