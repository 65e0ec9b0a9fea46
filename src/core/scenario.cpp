#include "bearing_sim/core/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/thermal_clearance.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {
constexpr double kRpmToRadS = 2.0 * kPi / 60.0;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
namespace fs = std::filesystem;

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// A speed given either in rpm or in rad/s under `<stem>_rpm` / `<stem>_rad_s`, within the
// bearing's physical limit (max_ring_speed_rad_s of its pitch diameter). Returns the key
// given (without the reader's prefix), "" if neither.
std::string read_speed(const detail::Reader& r, const std::string& stem, double pitch_diameter_m, double* speed_rad_s) {
  const bool rpm = r.has(stem + "_rpm"), rad = r.has(stem + "_rad_s");
  if (rpm && rad) r.fail(stem + "_rpm", "give either " + stem + "_rpm or " + stem + "_rad_s, not both");
  if (rpm) *speed_rad_s = r.number(stem + "_rpm", 0.0) * kRpmToRadS;
  if (rad) *speed_rad_s = r.number(stem + "_rad_s", 0.0);
  const std::string why = ring_speed_refusal(*speed_rad_s, pitch_diameter_m);
  if (!why.empty()) r.fail(stem + (rpm ? "_rpm" : "_rad_s"), why);
  return rpm ? stem + "_rpm" : rad ? stem + "_rad_s" : "";
}

// A growth rate given per hour (as in the bearing file) or per second (compressed time).
double read_growth(const detail::Reader& r, const std::string& stem, double unit_m) {
  const bool per_hour = r.has(stem + "_per_hour"), per_s = r.has(stem + "_per_s");
  if (per_hour && per_s) r.fail(stem + "_per_s", "give either " + stem + "_per_hour or " + stem + "_per_s, not both");
  double rate = 0.0;
  if (per_hour) rate = r.number(stem + "_per_hour", 0.0) * unit_m / 3600.0;
  if (per_s) rate = r.number(stem + "_per_s", 0.0) * unit_m;
  r.require(rate >= 0.0 && std::isfinite(rate), per_s ? stem + "_per_s" : stem + "_per_hour",
            "must be finite and >= 0");
  return rate;
}

// A list of exactly n finite numbers.
bool read_vector(const YAML::Node& map, const detail::Reader& r, const std::string& key, int n, double* out) {
  const YAML::Node node = map[key];
  if (!node) return false;
  if (!node.IsSequence() || static_cast<int>(node.size()) != n)
    r.fail(key, "expected a list of " + std::to_string(n) + " numbers");
  for (int i = 0; i < n; ++i) {
    if (!node[i].IsScalar()) r.fail(key, "expected a list of " + std::to_string(n) + " numbers");
    double v = 0.0;
    try {
      v = node[i].as<double>();
    } catch (const YAML::Exception&) {
      r.fail(key, "expected a number, got '" + node[i].Scalar() + "'");
    }
    if (!std::isfinite(v)) r.fail(key, "must be finite, got '" + node[i].Scalar() + "'");
    out[i] = v;
  }
  return true;
}

// A segment's [start_s, end_s] inside the scenario and after the previous segment.
void read_interval(const detail::Reader& r, bool has_end, double duration_s, double previous_end_s, double* start_s,
                   double* end_s) {
  *start_s = r.number("start_s", 0.0, true);
  r.require(*start_s >= 0.0, "start_s", "must be >= 0");
  r.require(*start_s <= duration_s, "start_s",
            "is after the end of the scenario (duration_s " + format_number(duration_s) + ")");
  r.require(*start_s >= previous_end_s, "start_s",
            "segments must be in time order without overlap: starts at " + format_number(*start_s) +
                " s, before the previous segment ends (" + format_number(previous_end_s) + " s)");
  *end_s = *start_s;
  if (has_end) {
    *end_s = r.number("end_s", 0.0, true);
    r.require(*end_s > *start_s, "end_s", "must be after start_s");
    r.require(*end_s <= duration_s, "end_s",
              "is after the end of the scenario (duration_s " + format_number(duration_s) + ")");
  }
}

// An absolute path: as given, else next to the scenario, else in the sibling config
// directory (config/scenarios/x.yaml -> config/<sibling>/name).
std::string resolve_file(const detail::Reader& r, const std::string& key, const std::string& file,
                         const fs::path& base_dir, const std::string& sibling) {
  std::vector<fs::path> candidates;
  if (fs::path(file).is_absolute()) candidates.push_back(file);
  else {
    candidates.push_back(base_dir / file);
    candidates.push_back(base_dir / ".." / sibling / file);
  }
  std::string looked;
  for (const fs::path& p : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return fs::absolute(p).lexically_normal().string();
    looked += (looked.empty() ? "" : ", ") + p.lexically_normal().string();
  }
  r.fail(key, "cannot find '" + file + "' (looked for " + looked + ")");
}
}  // namespace

Scenario Scenario::load(const std::string& path) {
  return from_string(detail::read_config_file(path, "scenario file"), path);
}

Scenario Scenario::from_string(const std::string& yaml, const std::string& source) {
  const YAML::Node root = detail::load_yaml(yaml, source);
  if (!root.IsMap()) throw ConfigError(source + ": expected a mapping at the top level");
  Scenario sc;
  sc.source_ = source;
  detail::Reader r(root, source, "");
  r.check_keys({"name", "description", "duration_s", "seed", "sample_rate_hz", "bearing_file", "sensor_file", "phases",
                "speed", "load", "ring_temperature_difference", "defects"});
  sc.name_ = r.text("name", "");
  r.require(!sc.name_.empty(), "name", "is required and must not be empty");
  sc.description_ = r.text("description", "");
  sc.duration_s_ = r.number("duration_s", 0.0, true);
  r.require(sc.duration_s_ > 0.0, "duration_s", "must be > 0, got " + format_number(sc.duration_s_));
  r.require(sc.duration_s_ <= kMaxScenarioDurationS, "duration_s", "must be at most 1e7 s");
  const int seed = r.integer("seed", 1);
  r.require(seed >= 0, "seed", "must be >= 0");
  sc.seed_ = static_cast<std::uint64_t>(seed);
  sc.sample_rate_hz_ = r.number("sample_rate_hz", 10000.0);
  r.require(sc.sample_rate_hz_ >= 100.0 && sc.sample_rate_hz_ <= kMaxSampleRateHz, "sample_rate_hz",
            "must be in [100, 1e6] Hz");

  const fs::path base_dir = fs::path(source).has_parent_path() ? fs::path(source).parent_path() : fs::path(".");
  const std::string bearing = r.text("bearing_file", "");
  r.require(!bearing.empty(), "bearing_file", "is required (a bearing file, e.g. ct_gantry_lyc.yaml)");
  sc.bearing_file_ = resolve_file(r, "bearing_file", bearing, base_dir, "bearings");
  const std::string sensor = r.text("sensor_file", "");
  if (!sensor.empty()) {
    sc.sensor_file_ = resolve_file(r, "sensor_file", sensor, base_dir, "sensors");
    try {
      load_accelerometer_config(sc.sensor_file_);
    } catch (const ConfigError& e) {
      r.fail("sensor_file", std::string("the sensor file is invalid: ") + e.what());
    }
  }
  BearingConfig bearing_config;
  try {
    bearing_config = load_bearing_config(sc.bearing_file_);
  } catch (const ConfigError& e) {
    r.fail("bearing_file", std::string("the bearing file is invalid: ") + e.what());
  }
  r.require(bearing_config.has_dynamics(), "bearing_file", "the bearing needs rotating_mass_kg for a scenario");

  // Phases.
  if (const YAML::Node phases = root["phases"]) {
    if (!phases.IsSequence()) r.fail("phases", "expected a list of {name, start_s}");
    for (std::size_t i = 0; i < phases.size(); ++i) {
      const std::string key = "phases[" + std::to_string(i) + "]";
      if (!phases[i].IsMap()) r.fail(key, "expected a mapping {name, start_s}");
      detail::Reader p(phases[i], source, key + ".");
      p.check_keys({"name", "start_s"});
      ScenarioPhase phase{p.text("name", ""), p.number("start_s", 0.0, true)};
      p.require(!phase.name.empty(), "name", "is required and must not be empty");
      p.require(phase.start_s >= 0.0 && phase.start_s < sc.duration_s_, "start_s", "must be in [0, duration_s)");
      if (!sc.phases_.empty())
        p.require(phase.start_s > sc.phases_.back().start_s, "start_s",
                  "phases must be in time order: starts at " + format_number(phase.start_s) + " s, not after '" +
                      sc.phases_.back().name + "' (" + format_number(sc.phases_.back().start_s) + " s)");
      sc.phases_.push_back(phase);
    }
  }

  // Speed: pieces from t = 0 to infinity, holds filling the gaps between segments.
  double speed = 0.0, angle = 0.0, cursor = 0.0;
  std::string speed_key;  // the key that set `speed` ("" while it is the default 0)
  auto hold = [&](double start_s, double end_s) {
    SpeedPiece p;
    p.kind = SpeedPiece::Kind::Hold;
    p.start_s = start_s;
    p.end_s = end_s;
    p.start_speed = speed;
    p.start_key = p.end_key = speed_key;
    return p;
  };
  auto push = [&](SpeedPiece p) {
    p.start_angle = angle;
    if (std::isfinite(p.end_s)) {
      angle = piece_angle(p, p.end_s);
      speed = piece_speed(p, p.end_s);
      cursor = p.end_s;
    }
    sc.speed_.push_back(p);
  };
  if (const YAML::Node node = r.map("speed")) {
    detail::Reader s(node, source, "speed.");
    s.check_keys({"initial_speed_rpm", "initial_speed_rad_s", "segments"});
    const std::string given = read_speed(s, "initial_speed", bearing_config.pitch_diameter_m, &speed);
    if (!given.empty()) speed_key = "speed." + given;
    if (const YAML::Node segments = node["segments"]) {
      if (!segments.IsSequence()) s.fail("segments", "expected a list of {type, start_s, end_s, ...}");
      for (std::size_t i = 0; i < segments.size(); ++i) {
        const std::string key = "speed.segments[" + std::to_string(i) + "]";
        if (!segments[i].IsMap()) r.fail(key, "expected a mapping");
        detail::Reader g(segments[i], source, key + ".");
        const std::string type = g.text("type", "");
        SpeedPiece p;
        if (type == "hold") {
          g.check_keys({"type", "start_s", "end_s", "speed_rpm", "speed_rad_s"});
          p.kind = SpeedPiece::Kind::Hold;
        } else if (type == "ramp") {
          g.check_keys({"type", "start_s", "end_s", "to_speed_rpm", "to_speed_rad_s"});
          p.kind = SpeedPiece::Kind::Ramp;
        } else if (type == "coast") {
          g.check_keys({"type", "start_s", "end_s", "time_constant_s"});
          p.kind = SpeedPiece::Kind::Coast;
        } else {
          g.fail("type", "must be hold, ramp or coast, got '" + type + "'");
        }
        read_interval(g, true, sc.duration_s_, cursor, &p.start_s, &p.end_s);
        if (p.start_s > cursor) push(hold(cursor, p.start_s));
        p.start_speed = speed;
        p.start_key = p.end_key = speed_key;
        if (p.kind == SpeedPiece::Kind::Hold) {  // a step, if given
          const std::string step = read_speed(g, "speed", bearing_config.pitch_diameter_m, &p.start_speed);
          if (!step.empty()) p.start_key = p.end_key = key + "." + step;
        }
        if (p.kind == SpeedPiece::Kind::Ramp) {
          const std::string target = read_speed(g, "to_speed", bearing_config.pitch_diameter_m, &p.end_speed);
          if (target.empty()) g.fail("to_speed_rpm", "a ramp needs its target, to_speed_rpm or to_speed_rad_s");
          p.end_key = key + "." + target;
        }
        if (p.kind == SpeedPiece::Kind::Coast) {
          p.time_constant_s = g.number("time_constant_s", 0.0, true);
          g.require(p.time_constant_s > 0.0, "time_constant_s", "must be > 0");
        }
        push(p);
        // The speed from here on: a hold's or a ramp's target; a coast's is the speed it decays from.
        speed_key = p.end_key;
      }
    }
  }
  push(hold(cursor, kInfinity));

  // Load.
  if (const YAML::Node node = r.map("load")) {
    detail::Reader l(node, source, "load.");
    l.check_keys({"initial", "segments", "unbalance"});
    if (const YAML::Node initial = l.map("initial")) {
      detail::Reader i(initial, source, "load.initial.");
      i.check_keys({"force_N", "moment_Nm"});
      read_vector(initial, i, "force_N", 3, sc.initial_load_.data());
      read_vector(initial, i, "moment_Nm", 2, sc.initial_load_.data() + 3);
    }
    // Every load the time line holds (the initial one, each step's and ramp's target) must be
    // carried by the bearing: the node refuses a load it cannot carry and runs on at the last
    // good one, so the labels (scenario_state) would say a load the data never had.
    std::optional<BearingModel> carrier;
    const auto require_carried = [&](const detail::Reader& at, const std::string& key, const Vector5& load) {
      if (!carrier) carrier.emplace(bearing_config);
      try {
        solve_static(*carrier, load);
      } catch (const std::exception& e) {  // LoadNotCarriedError, InvalidInputError
        std::ostringstream what;
        what << "the bearing cannot carry the load (" << load.transpose() << "): " << e.what();
        at.fail(key, what.str());
      }
    };
    if (l.has("initial")) require_carried(l, "initial", sc.initial_load_);
    Vector5 current = sc.initial_load_;
    std::string force_key = "load.initial.force_N", moment_key = "load.initial.moment_Nm";
    double previous_end = 0.0;
    if (const YAML::Node segments = node["segments"]) {
      if (!segments.IsSequence()) l.fail("segments", "expected a list of {type, start_s, ...}");
      for (std::size_t k = 0; k < segments.size(); ++k) {
        const std::string key = "load.segments[" + std::to_string(k) + "]";
        if (!segments[k].IsMap()) r.fail(key, "expected a mapping");
        detail::Reader g(segments[k], source, key + ".");
        const std::string type = g.text("type", "");
        if (type == "step") g.check_keys({"type", "start_s", "force_N", "moment_Nm"});
        else if (type == "ramp") g.check_keys({"type", "start_s", "end_s", "force_N", "moment_Nm"});
        else g.fail("type", "must be step or ramp, got '" + type + "'");
        LoadPiece p;
        read_interval(g, type == "ramp", sc.duration_s_, previous_end, &p.start_s, &p.end_s);
        p.from = current;
        p.to = current;  // components not given keep their value
        const bool force = read_vector(segments[k], g, "force_N", 3, p.to.data());
        const bool moment = read_vector(segments[k], g, "moment_Nm", 2, p.to.data() + 3);
        g.require(force || moment, "force_N", "a load segment needs force_N and/or moment_Nm");
        require_carried(g, force ? "force_N" : "moment_Nm", p.to);
        p.from_force_key = force_key;
        p.from_moment_key = moment_key;
        if (force) force_key = key + ".force_N";
        if (moment) moment_key = key + ".moment_Nm";
        p.to_force_key = force_key;
        p.to_moment_key = moment_key;
        current = p.to;
        previous_end = p.end_s;
        sc.load_.push_back(p);
      }
    }
    if (const YAML::Node unbalance = l.map("unbalance")) {
      detail::Reader u(unbalance, source, "load.unbalance.");
      u.check_keys({"mass_kg", "radius_m", "phase_deg"});
      sc.unbalance_.mass_kg = u.number("mass_kg", 0.0, true);
      u.require(sc.unbalance_.mass_kg > 0.0, "mass_kg", "must be > 0");
      sc.unbalance_.radius_m = u.number("radius_m", 0.0, true);
      u.require(sc.unbalance_.radius_m > 0.0, "radius_m", "must be > 0");
      sc.unbalance_.phase_rad = u.number("phase_deg", 0.0) * kPi / 180.0;
    }
  }

  // Ring temperature difference: a time line like the load's; every value it takes (its
  // extremes are at the segment ends) must leave the bearing a clearance the model allows.
  if (const YAML::Node node = r.map("ring_temperature_difference")) {
    sc.has_temperature_ = true;
    detail::Reader tr(node, source, "ring_temperature_difference.");
    tr.check_keys({"initial_K", "segments"});
    const auto check = [&](const detail::Reader& at, const std::string& key, double dT) {
      BearingConfig hot = bearing_config;
      hot.ring_temperature_difference_K = dT;
      try {
        operating_clearance_m(hot);
      } catch (const InvalidInputError& e) {
        at.fail(key, std::string("not possible with the bearing: ") + e.what());
      }
    };
    sc.initial_temperature_K_ = tr.number("initial_K", 0.0);
    check(tr, "initial_K", sc.initial_temperature_K_);
    double current = sc.initial_temperature_K_, previous_end = 0.0;
    if (const YAML::Node segments = node["segments"]) {
      if (!segments.IsSequence()) tr.fail("segments", "expected a list of {type, start_s, ...}");
      for (std::size_t k = 0; k < segments.size(); ++k) {
        const std::string key = "ring_temperature_difference.segments[" + std::to_string(k) + "]";
        if (!segments[k].IsMap()) r.fail(key, "expected a mapping");
        detail::Reader g(segments[k], source, key + ".");
        const std::string type = g.text("type", "");
        if (type == "step") g.check_keys({"type", "start_s", "difference_K"});
        else if (type == "ramp") g.check_keys({"type", "start_s", "end_s", "difference_K"});
        else g.fail("type", "must be step or ramp, got '" + type + "'");
        TemperaturePiece p;
        read_interval(g, type == "ramp", sc.duration_s_, previous_end, &p.start_s, &p.end_s);
        p.from_K = current;
        p.to_K = g.number("difference_K", 0.0, true);
        check(g, "difference_K", p.to_K);
        current = p.to_K;
        previous_end = p.end_s;
        sc.temperature_.push_back(p);
      }
    }
  }

  // Defects, checked against the bearing with the rules of BearingModel::add_spall, at
  // their size when they appear and at their largest (when cleared, or at the end).
  if (const YAML::Node defects = root["defects"]) {
    if (!defects.IsSequence()) r.fail("defects", "expected a list of {type, at_s, ...}");
    for (std::size_t i = 0; i < defects.size(); ++i) {
      const std::string key = "defects[" + std::to_string(i) + "]";
      if (!defects[i].IsMap()) r.fail(key, "expected a mapping");
      detail::Reader d(defects[i], source, key + ".");
      ScenarioDefectEvent event;
      const std::string type = d.text("type", "spall");
      if (type == "spall") {
        d.check_keys({"type", "at_s", "surface", "position_deg", "ball", "row", "width_mm", "depth_um",
                      "width_growth_mm_per_hour", "width_growth_mm_per_s", "depth_growth_um_per_hour",
                      "depth_growth_um_per_s"});
      } else if (type == "clear") {
        d.check_keys({"type", "at_s"});
        event.kind = ScenarioDefectEvent::Kind::Clear;
      } else {
        d.fail("type", "must be spall or clear, got '" + type + "'");
      }
      event.time_s = d.number("at_s", 0.0, true);
      d.require(event.time_s >= 0.0 && event.time_s <= sc.duration_s_, "at_s", "must be in [0, duration_s]");
      if (!sc.defect_events_.empty())
        d.require(event.time_s >= sc.defect_events_.back().time_s, "at_s",
                  "defect events must be in time order: " + format_number(event.time_s) +
                      " s is before the previous event (" + format_number(sc.defect_events_.back().time_s) + " s)");
      if (event.kind == ScenarioDefectEvent::Kind::Spall) {
        Spall& s = event.spall;
        try {
          s.surface = parse_surface(d.text("surface", "outer_race"));
        } catch (const InvalidInputError& e) {
          d.fail("surface", e.what());
        }
        s.position_rad = d.number("position_deg", 0.0) * kPi / 180.0;
        s.ball = d.integer("ball", 0);
        // A race spall is on one raceway: row 0 unless given; a ball spall's row is its ball's.
        if (s.surface == Surface::Ball && d.has("row"))
          d.fail("row", "not for a ball spall: the ball index (row-major) gives the row");
        s.row = d.integer("row", 0);
        d.require(s.row >= 0 && s.row < bearing_config.rows, "row",
                  bearing_config.rows == 1 ? "must be 0 (the bearing has one row)"
                                           : "must be 0 or 1 (the bearing has two rows)");
        s.width_m = d.number("width_mm", 0.0, true) * 1e-3;
        d.require(s.width_m > 0.0, "width_mm", "must be > 0");
        s.depth_m = d.number("depth_um", 0.0, true) * 1e-6;
        d.require(s.depth_m > 0.0, "depth_um", "must be > 0");
        s.width_growth_m_per_s = read_growth(d, "width_growth_mm", 1e-3);
        s.depth_growth_m_per_s = read_growth(d, "depth_growth_um", 1e-6);
        s.created_at_s = event.time_s;
      }
      sc.defect_events_.push_back(event);
    }
    // The spalls present as the run goes: the bearing file's, then the scenario's until a clear
    // (which clears all), so that at most kMaxSpalls are counted at once, as the run adds them.
    BearingModel model(bearing_config);
    for (std::size_t i = 0; i < sc.defect_events_.size(); ++i) {
      const ScenarioDefectEvent& event = sc.defect_events_[i];
      if (event.kind != ScenarioDefectEvent::Kind::Spall) {
        model.clear_spalls();
        continue;
      }
      double end = sc.duration_s_;
      for (std::size_t j = i + 1; j < sc.defect_events_.size(); ++j)
        if (sc.defect_events_[j].kind == ScenarioDefectEvent::Kind::Clear) {
          end = sc.defect_events_[j].time_s;
          break;
        }
      Spall largest = event.spall;
      largest.width_m = spall_width_at(event.spall, end);
      largest.depth_m = spall_depth_at(event.spall, end);
      const std::string key = "defects[" + std::to_string(i) + "]";
      BearingModel grown = model;  // the largest is checked among the same spalls, not as one more
      try {
        model.add_spall(event.spall);
      } catch (const InvalidInputError& e) {
        r.fail(key, std::string("does not fit the bearing: ") + e.what());
      }
      try {
        grown.add_spall(largest);
      } catch (const InvalidInputError& e) {
        r.fail(key, "grows too large for the bearing by t = " + format_number(end) + " s (" +
                        format_number(largest.width_m * 1e3) + " mm wide, " + format_number(largest.depth_m * 1e6) +
                        " um deep): " + e.what());
      }
    }
  }
  return sc;
}

// --- speed ---------------------------------------------------------------------------

double Scenario::piece_speed(const SpeedPiece& p, double t) {
  const double dt = t - p.start_s;
  switch (p.kind) {
    case SpeedPiece::Kind::Hold:
      return p.start_speed;
    case SpeedPiece::Kind::Ramp:
      return p.start_speed + (p.end_speed - p.start_speed) * dt / (p.end_s - p.start_s);
    case SpeedPiece::Kind::Coast:
      return p.start_speed * std::exp(-dt / p.time_constant_s);
  }
  return 0.0;
}

double Scenario::piece_acceleration(const SpeedPiece& p, double t) {
  switch (p.kind) {
    case SpeedPiece::Kind::Hold:
      return 0.0;
    case SpeedPiece::Kind::Ramp:
      return (p.end_speed - p.start_speed) / (p.end_s - p.start_s);
    case SpeedPiece::Kind::Coast:
      return -piece_speed(p, t) / p.time_constant_s;
  }
  return 0.0;
}

// Closed-form integral of the piece's speed from its start.
double Scenario::piece_angle(const SpeedPiece& p, double t) {
  const double dt = t - p.start_s;
  switch (p.kind) {
    case SpeedPiece::Kind::Hold:
      return p.start_angle + p.start_speed * dt;
    case SpeedPiece::Kind::Ramp:
      return p.start_angle + p.start_speed * dt + 0.5 * (p.end_speed - p.start_speed) * dt * dt / (p.end_s - p.start_s);
    case SpeedPiece::Kind::Coast:
      return p.start_angle - p.start_speed * p.time_constant_s * std::expm1(-dt / p.time_constant_s);
  }
  return 0.0;
}

const Scenario::SpeedPiece& Scenario::speed_piece(double t) const {
  if (!(t >= 0.0) || !std::isfinite(t))
    throw InvalidInputError("scenario '" + name_ + "': time must be finite and >= 0, got " + format_number(t));
  // The last piece starting at or before t.
  auto it = std::upper_bound(speed_.begin(), speed_.end(), t,
                             [](double time, const SpeedPiece& p) { return time < p.start_s; });
  return *std::prev(it);
}

double Scenario::ring_speed_at(double t) const { return piece_speed(speed_piece(t), t); }

std::vector<Scenario::InputExtreme> Scenario::input_extremes() const {
  std::vector<double> times{0.0, duration_s_};
  for (const LoadPiece& p : load_) times.insert(times.end(), {p.start_s, p.end_s});
  for (const SpeedPiece& p : speed_) times.insert(times.end(), {p.start_s, p.end_s});
  times.erase(std::remove_if(times.begin(), times.end(), [&](double t) { return !(t >= 0.0 && t <= duration_s_); }),
              times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  const double me = unbalance_.mass_kg * unbalance_.radius_m;
  std::vector<InputExtreme> out;
  // The inputs at `t` from the pieces that hold at `probe` (t itself, or the middle of the
  // stretch t ends or starts: its one-sided value).
  const auto add = [&](double t, double probe) {
    InputExtreme e;
    e.time_s = t;
    Vector5 load = initial_load_;
    e.force_key = "load.initial.force_N";
    e.moment_key = "load.initial.moment_Nm";
    const auto it = std::upper_bound(load_.begin(), load_.end(), probe,
                                     [](double time, const LoadPiece& p) { return time < p.start_s; });
    if (it != load_.begin()) {
      const LoadPiece& p = *std::prev(it);
      const bool at_start = t <= p.start_s && p.end_s > p.start_s;  // a ramp's start: the load it starts from
      if (t >= p.end_s) load = p.to;
      else if (at_start) load = p.from;
      else load = p.from + (p.to - p.from) * ((t - p.start_s) / (p.end_s - p.start_s));
      e.force_key = at_start ? p.from_force_key : p.to_force_key;
      e.moment_key = at_start ? p.from_moment_key : p.to_moment_key;
    }
    const SpeedPiece& s = speed_piece(probe);
    const double w = piece_speed(s, t), alpha = piece_acceleration(s, t);
    e.speed_signed_rad_s = w;
    e.speed_rad_s = std::abs(w);
    e.speed_key = (s.kind == SpeedPiece::Kind::Ramp && t > s.start_s) ? s.end_key : s.start_key;
    e.unbalance_N = me * std::sqrt(w * w * w * w + alpha * alpha);
    e.force_N = std::hypot(std::hypot(load[0], load[1]) + e.unbalance_N, load[2]);
    e.load_force_N = load.head<3>().norm();
    e.moment_Nm = std::hypot(load[3], load[4]);
    out.push_back(e);
  };
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double middle = 0.5 * (times[i] + times[i + 1]);
    add(times[i], middle);
    add(times[i + 1], middle);
  }
  add(times.back(), times.back());
  return out;
}
double Scenario::ring_angle_at(double t) const { return piece_angle(speed_piece(t), t); }

// --- load ----------------------------------------------------------------------------

Vector5 Scenario::base_load_at(double t) const {
  speed_piece(t);  // checks t
  auto it =
      std::upper_bound(load_.begin(), load_.end(), t, [](double time, const LoadPiece& p) { return time < p.start_s; });
  if (it == load_.begin()) return initial_load_;
  const LoadPiece& p = *std::prev(it);
  if (t >= p.end_s) return p.to;
  return p.from + (p.to - p.from) * ((t - p.start_s) / (p.end_s - p.start_s));
}

Vector5 Scenario::unbalance_load(double w, double alpha, double ring_angle) const {
  Vector5 f = Vector5::Zero();
  if (unbalance_.mass_kg == 0.0) return f;
  const double me = unbalance_.mass_kg * unbalance_.radius_m;
  const double a = ring_angle + unbalance_.phase_rad;
  const double c = std::cos(a), s = std::sin(a);
  f[0] = me * (w * w * c + alpha * s);
  f[1] = me * (w * w * s - alpha * c);
  return f;
}

Vector5 Scenario::load_at(double t) const {
  const SpeedPiece& p = speed_piece(t);
  return base_load_at(t) + unbalance_load(piece_speed(p, t), piece_acceleration(p, t), piece_angle(p, t));
}

std::string Scenario::phase_at(double t) const {
  speed_piece(t);
  std::string phase;
  for (const ScenarioPhase& p : phases_)
    if (p.start_s <= t) phase = p.name;
  return phase;
}

ScenarioInputs Scenario::inputs_at(double t) const {
  const SpeedPiece& p = speed_piece(t);
  ScenarioInputs in;
  in.ring_speed_rad_s = piece_speed(p, t);
  in.ring_angle_rad = piece_angle(p, t);
  in.load = load_at(t);
  in.phase = phase_at(t);
  in.ring_temperature_difference_K = ring_temperature_difference_at(t);
  return in;
}

// --- ring temperature difference ---------------------------------------------------

double Scenario::ring_temperature_difference_at(double t) const {
  speed_piece(t);  // checks t
  auto it = std::upper_bound(temperature_.begin(), temperature_.end(), t,
                             [](double time, const TemperaturePiece& p) { return time < p.start_s; });
  if (it == temperature_.begin()) return initial_temperature_K_;
  const TemperaturePiece& p = *std::prev(it);
  if (t >= p.end_s) return p.to_K;
  // Whole steps of kTemperatureStepK from the ramp's start, never past its end value.
  const double exact = (p.to_K - p.from_K) * ((t - p.start_s) / (p.end_s - p.start_s));
  const double steps = std::floor(std::abs(exact) / kTemperatureStepK);
  return p.from_K + std::copysign(steps * kTemperatureStepK, exact);
}

// --- defects -------------------------------------------------------------------------

double Scenario::spall_width_at(const Spall& s, double t) {
  // No cap needed here: the scenario refuses a spall whose size at its end would not fit the
  // bearing (spall_limit via Imperfections::validate), so this law never passes the limit.
  return grown_size(s.width_m, s.width_growth_m_per_s, std::max(0.0, t - s.created_at_s),
                    std::numeric_limits<double>::infinity());
}

double Scenario::spall_depth_at(const Spall& s, double t) {
  return grown_size(s.depth_m, s.depth_growth_m_per_s, std::max(0.0, t - s.created_at_s),
                    std::numeric_limits<double>::infinity());
}

std::vector<Spall> Scenario::spalls_at(double t) const {
  std::vector<Spall> present;
  for (const ScenarioDefectEvent& e : defect_events_) {
    if (e.time_s > t) break;
    if (e.kind == ScenarioDefectEvent::Kind::Clear) present.clear();
    else present.push_back(e.spall);
  }
  return present;
}

}  // namespace bearing_sim
