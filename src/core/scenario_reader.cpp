// The scenario file's reader (docs/scenarios.md): Scenario::from_string, section by section.
// Every value is checked as it is read and a bad one named by file and key; what a section
// needs from another (the duration, the bearing) is read before it.
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/thermal_clearance.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {
constexpr double kRpmToRadS = 2.0 * kPi / 60.0;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
namespace fs = std::filesystem;
using detail::format_number;

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

// Fills a Scenario's time lines (a friend of Scenario) from the file's top-level mapping.
class ScenarioReader {
 public:
  ScenarioReader(const YAML::Node& root, const std::string& source, Scenario* scenario)
      : root_(root), source_(source), sc_(*scenario), r_(root_, source_, "") {}

  void read() {
    read_header();
    read_files();
    read_phases();
    read_speed_line();
    read_load_line();
    read_temperature_line();
    read_defect_events();
    check_defects_fit();
  }

 private:
  // name, description, duration_s, seed, sample_rate_hz (and every top-level key known).
  void read_header() {
    r_.check_keys({"name", "description", "duration_s", "seed", "sample_rate_hz", "bearing_file", "sensor_file",
                   "phases", "speed", "load", "ring_temperature_difference", "defects"});
    sc_.name_ = r_.text("name", "");
    r_.require(!sc_.name_.empty(), "name", "is required and must not be empty");
    sc_.description_ = r_.text("description", "");
    sc_.duration_s_ = r_.number("duration_s", 0.0, true);
    r_.require(sc_.duration_s_ > 0.0, "duration_s", "must be > 0, got " + format_number(sc_.duration_s_));
    r_.require(sc_.duration_s_ <= kMaxScenarioDurationS, "duration_s", "must be at most 1e7 s");
    const int seed = r_.integer("seed", 1);
    r_.require(seed >= 0, "seed", "must be >= 0");
    sc_.seed_ = static_cast<std::uint64_t>(seed);
    sc_.sample_rate_hz_ = r_.number("sample_rate_hz", 10000.0);
    r_.require(sc_.sample_rate_hz_ >= 100.0 && sc_.sample_rate_hz_ <= kMaxSampleRateHz, "sample_rate_hz",
               "must be in [100, 1e6] Hz");
  }

  // bearing_file (required: the load and the defects are checked against it), sensor_file.
  void read_files() {
    const fs::path base_dir = fs::path(source_).has_parent_path() ? fs::path(source_).parent_path() : fs::path(".");
    const std::string bearing = r_.text("bearing_file", "");
    r_.require(!bearing.empty(), "bearing_file", "is required (a bearing file, e.g. ct_gantry_lyc.yaml)");
    sc_.bearing_file_ = resolve_file(r_, "bearing_file", bearing, base_dir, "bearings");
    const std::string sensor = r_.text("sensor_file", "");
    if (!sensor.empty()) {
      sc_.sensor_file_ = resolve_file(r_, "sensor_file", sensor, base_dir, "sensors");
      try {
        load_accelerometer_config(sc_.sensor_file_);
      } catch (const ConfigError& e) {
        r_.fail("sensor_file", std::string("the sensor file is invalid: ") + e.what());
      }
    }
    try {
      bearing_ = load_bearing_config(sc_.bearing_file_);
    } catch (const ConfigError& e) {
      r_.fail("bearing_file", std::string("the bearing file is invalid: ") + e.what());
    }
    r_.require(bearing_.has_dynamics(), "bearing_file", "the bearing needs rotating_mass_kg for a scenario");
  }

  void read_phases() {
    if (const YAML::Node phases = root_["phases"]) {
      if (!phases.IsSequence()) r_.fail("phases", "expected a list of {name, start_s}");
      for (std::size_t i = 0; i < phases.size(); ++i) {
        const std::string key = "phases[" + std::to_string(i) + "]";
        if (!phases[i].IsMap()) r_.fail(key, "expected a mapping {name, start_s}");
        detail::Reader p(phases[i], source_, key + ".");
        p.check_keys({"name", "start_s"});
        ScenarioPhase phase{p.text("name", ""), p.number("start_s", 0.0, true)};
        p.require(!phase.name.empty(), "name", "is required and must not be empty");
        p.require(phase.start_s >= 0.0 && phase.start_s < sc_.duration_s_, "start_s", "must be in [0, duration_s)");
        if (!sc_.phases_.empty())
          p.require(phase.start_s > sc_.phases_.back().start_s, "start_s",
                    "phases must be in time order: starts at " + format_number(phase.start_s) + " s, not after '" +
                        sc_.phases_.back().name + "' (" + format_number(sc_.phases_.back().start_s) + " s)");
        sc_.phases_.push_back(phase);
      }
    }
  }

  // Speed: pieces from t = 0 to infinity, holds filling the gaps between segments.
  void read_speed_line() {
    double speed = 0.0, angle = 0.0, cursor = 0.0;
    std::string speed_key;  // the key that set `speed` ("" while it is the default 0)
    auto hold = [&](double start_s, double end_s) {
      Scenario::SpeedPiece p;
      p.kind = Scenario::SpeedPiece::Kind::Hold;
      p.start_s = start_s;
      p.end_s = end_s;
      p.start_speed = speed;
      p.start_key = p.end_key = speed_key;
      return p;
    };
    auto push = [&](Scenario::SpeedPiece p) {
      p.start_angle = angle;
      if (std::isfinite(p.end_s)) {
        angle = Scenario::piece_angle(p, p.end_s);
        speed = Scenario::piece_speed(p, p.end_s);
        cursor = p.end_s;
      }
      sc_.speed_.push_back(p);
    };
    if (const YAML::Node node = r_.map("speed")) {
      detail::Reader s(node, source_, "speed.");
      s.check_keys({"initial_speed_rpm", "initial_speed_rad_s", "segments"});
      const std::string given = read_speed(s, "initial_speed", bearing_.pitch_diameter_m, &speed);
      if (!given.empty()) speed_key = "speed." + given;
      if (const YAML::Node segments = node["segments"]) {
        if (!segments.IsSequence()) s.fail("segments", "expected a list of {type, start_s, end_s, ...}");
        for (std::size_t i = 0; i < segments.size(); ++i) {
          const std::string key = "speed.segments[" + std::to_string(i) + "]";
          if (!segments[i].IsMap()) r_.fail(key, "expected a mapping");
          detail::Reader g(segments[i], source_, key + ".");
          const std::string type = g.text("type", "");
          Scenario::SpeedPiece p;
          if (type == "hold") {
            g.check_keys({"type", "start_s", "end_s", "speed_rpm", "speed_rad_s"});
            p.kind = Scenario::SpeedPiece::Kind::Hold;
          } else if (type == "ramp") {
            g.check_keys({"type", "start_s", "end_s", "to_speed_rpm", "to_speed_rad_s"});
            p.kind = Scenario::SpeedPiece::Kind::Ramp;
          } else if (type == "coast") {
            g.check_keys({"type", "start_s", "end_s", "time_constant_s"});
            p.kind = Scenario::SpeedPiece::Kind::Coast;
          } else {
            g.fail("type", "must be hold, ramp or coast, got '" + type + "'");
          }
          read_interval(g, true, sc_.duration_s_, cursor, &p.start_s, &p.end_s);
          if (p.start_s > cursor) push(hold(cursor, p.start_s));
          p.start_speed = speed;
          p.start_key = p.end_key = speed_key;
          if (p.kind == Scenario::SpeedPiece::Kind::Hold) {  // a step, if given
            const std::string step = read_speed(g, "speed", bearing_.pitch_diameter_m, &p.start_speed);
            if (!step.empty()) p.start_key = p.end_key = key + "." + step;
          }
          if (p.kind == Scenario::SpeedPiece::Kind::Ramp) {
            const std::string target = read_speed(g, "to_speed", bearing_.pitch_diameter_m, &p.end_speed);
            if (target.empty()) g.fail("to_speed_rpm", "a ramp needs its target, to_speed_rpm or to_speed_rad_s");
            p.end_key = key + "." + target;
          }
          if (p.kind == Scenario::SpeedPiece::Kind::Coast) {
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
  }

  void read_load_line() {
    if (const YAML::Node node = r_.map("load")) {
      detail::Reader l(node, source_, "load.");
      l.check_keys({"initial", "segments", "unbalance"});
      if (const YAML::Node initial = l.map("initial")) {
        detail::Reader i(initial, source_, "load.initial.");
        i.check_keys({"force_N", "moment_Nm"});
        read_vector(initial, i, "force_N", 3, sc_.initial_load_.data());
        read_vector(initial, i, "moment_Nm", 2, sc_.initial_load_.data() + 3);
      }
      // Every load the time line holds (the initial one, each step's and ramp's target) must be
      // carried by the bearing: the node refuses a load it cannot carry and runs on at the last
      // good one, so the labels (scenario_state) would say a load the data never had.
      std::optional<BearingModel> carrier;
      const auto require_carried = [&](const detail::Reader& at, const std::string& key, const Vector5& load) {
        if (!carrier) carrier.emplace(bearing_);
        try {
          solve_static(*carrier, load);
        } catch (const std::exception& e) {  // LoadNotCarriedError, InvalidInputError
          std::ostringstream what;
          what << "the bearing cannot carry the load (" << load.transpose() << "): " << e.what();
          at.fail(key, what.str());
        }
      };
      if (l.has("initial")) require_carried(l, "initial", sc_.initial_load_);
      Vector5 current = sc_.initial_load_;
      std::string force_key = "load.initial.force_N", moment_key = "load.initial.moment_Nm";
      double previous_end = 0.0;
      if (const YAML::Node segments = node["segments"]) {
        if (!segments.IsSequence()) l.fail("segments", "expected a list of {type, start_s, ...}");
        for (std::size_t k = 0; k < segments.size(); ++k) {
          const std::string key = "load.segments[" + std::to_string(k) + "]";
          if (!segments[k].IsMap()) r_.fail(key, "expected a mapping");
          detail::Reader g(segments[k], source_, key + ".");
          const std::string type = g.text("type", "");
          if (type == "step") g.check_keys({"type", "start_s", "force_N", "moment_Nm"});
          else if (type == "ramp") g.check_keys({"type", "start_s", "end_s", "force_N", "moment_Nm"});
          else g.fail("type", "must be step or ramp, got '" + type + "'");
          Scenario::LoadPiece p;
          read_interval(g, type == "ramp", sc_.duration_s_, previous_end, &p.start_s, &p.end_s);
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
          sc_.load_.push_back(p);
        }
      }
      if (const YAML::Node unbalance = l.map("unbalance")) {
        detail::Reader u(unbalance, source_, "load.unbalance.");
        u.check_keys({"mass_kg", "radius_m", "phase_deg"});
        sc_.unbalance_.mass_kg = u.number("mass_kg", 0.0, true);
        u.require(sc_.unbalance_.mass_kg > 0.0, "mass_kg", "must be > 0");
        sc_.unbalance_.radius_m = u.number("radius_m", 0.0, true);
        u.require(sc_.unbalance_.radius_m > 0.0, "radius_m", "must be > 0");
        sc_.unbalance_.phase_rad = u.number("phase_deg", 0.0) * kPi / 180.0;
      }
    }
  }

  // Ring temperature difference: a time line like the load's; every value it takes (its
  // extremes are at the segment ends) must leave the bearing a clearance the model allows.
  void read_temperature_line() {
    if (const YAML::Node node = r_.map("ring_temperature_difference")) {
      sc_.has_temperature_ = true;
      detail::Reader tr(node, source_, "ring_temperature_difference.");
      tr.check_keys({"initial_K", "segments"});
      const auto check = [&](const detail::Reader& at, const std::string& key, double dT) {
        BearingConfig hot = bearing_;
        hot.ring_temperature_difference_K = dT;
        try {
          operating_clearance_m(hot);
        } catch (const InvalidInputError& e) {
          at.fail(key, std::string("not possible with the bearing: ") + e.what());
        }
      };
      sc_.initial_temperature_K_ = tr.number("initial_K", 0.0);
      check(tr, "initial_K", sc_.initial_temperature_K_);
      double current = sc_.initial_temperature_K_, previous_end = 0.0;
      if (const YAML::Node segments = node["segments"]) {
        if (!segments.IsSequence()) tr.fail("segments", "expected a list of {type, start_s, ...}");
        for (std::size_t k = 0; k < segments.size(); ++k) {
          const std::string key = "ring_temperature_difference.segments[" + std::to_string(k) + "]";
          if (!segments[k].IsMap()) r_.fail(key, "expected a mapping");
          detail::Reader g(segments[k], source_, key + ".");
          const std::string type = g.text("type", "");
          if (type == "step") g.check_keys({"type", "start_s", "difference_K"});
          else if (type == "ramp") g.check_keys({"type", "start_s", "end_s", "difference_K"});
          else g.fail("type", "must be step or ramp, got '" + type + "'");
          Scenario::TemperaturePiece p;
          read_interval(g, type == "ramp", sc_.duration_s_, previous_end, &p.start_s, &p.end_s);
          p.from_K = current;
          p.to_K = g.number("difference_K", 0.0, true);
          check(g, "difference_K", p.to_K);
          current = p.to_K;
          previous_end = p.end_s;
          sc_.temperature_.push_back(p);
        }
      }
    }
  }

  // Defects, checked against the bearing with the rules of BearingModel::add_spall, at
  // their size when they appear and at their largest (when cleared, or at the end).
  void read_defect_events() {
    if (const YAML::Node defects = root_["defects"]) {
      if (!defects.IsSequence()) r_.fail("defects", "expected a list of {type, at_s, ...}");
      for (std::size_t i = 0; i < defects.size(); ++i) {
        const std::string key = "defects[" + std::to_string(i) + "]";
        if (!defects[i].IsMap()) r_.fail(key, "expected a mapping");
        detail::Reader d(defects[i], source_, key + ".");
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
        d.require(event.time_s >= 0.0 && event.time_s <= sc_.duration_s_, "at_s", "must be in [0, duration_s]");
        if (!sc_.defect_events_.empty())
          d.require(event.time_s >= sc_.defect_events_.back().time_s, "at_s",
                    "defect events must be in time order: " + format_number(event.time_s) +
                        " s is before the previous event (" + format_number(sc_.defect_events_.back().time_s) + " s)");
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
          d.require(
              s.row >= 0 && s.row < bearing_.rows, "row",
              bearing_.rows == 1 ? "must be 0 (the bearing has one row)" : "must be 0 or 1 (the bearing has two rows)");
          s.width_m = d.number("width_mm", 0.0, true) * 1e-3;
          d.require(s.width_m > 0.0, "width_mm", "must be > 0");
          s.depth_m = d.number("depth_um", 0.0, true) * 1e-6;
          d.require(s.depth_m > 0.0, "depth_um", "must be > 0");
          s.width_growth_m_per_s = read_growth(d, "width_growth_mm", 1e-3);
          s.depth_growth_m_per_s = read_growth(d, "depth_growth_um", 1e-6);
          s.created_at_s = event.time_s;
        }
        sc_.defect_events_.push_back(event);
      }
    }
  }

  void check_defects_fit() {
    if (!root_["defects"]) return;
    // The spalls present as the run goes: the bearing file's, then the scenario's until a clear
    // (which clears all), so that at most kMaxSpalls are counted at once, as the run adds them.
    BearingModel model(bearing_);
    for (std::size_t i = 0; i < sc_.defect_events_.size(); ++i) {
      const ScenarioDefectEvent& event = sc_.defect_events_[i];
      if (event.kind != ScenarioDefectEvent::Kind::Spall) {
        model.clear_spalls();
        continue;
      }
      double end = sc_.duration_s_;
      for (std::size_t j = i + 1; j < sc_.defect_events_.size(); ++j)
        if (sc_.defect_events_[j].kind == ScenarioDefectEvent::Kind::Clear) {
          end = sc_.defect_events_[j].time_s;
          break;
        }
      Spall largest = event.spall;
      largest.width_m = Scenario::spall_width_at(event.spall, end);
      largest.depth_m = Scenario::spall_depth_at(event.spall, end);
      const std::string key = "defects[" + std::to_string(i) + "]";
      BearingModel grown = model;  // the largest is checked among the same spalls, not as one more
      try {
        model.add_spall(event.spall);
      } catch (const InvalidInputError& e) {
        r_.fail(key, std::string("does not fit the bearing: ") + e.what());
      }
      try {
        grown.add_spall(largest);
      } catch (const InvalidInputError& e) {
        r_.fail(key, "grows too large for the bearing by t = " + format_number(end) + " s (" +
                         format_number(largest.width_m * 1e3) + " mm wide, " + format_number(largest.depth_m * 1e6) +
                         " um deep): " + e.what());
      }
    }
  }

  const YAML::Node root_;
  const std::string source_;
  Scenario& sc_;
  detail::Reader r_;
  BearingConfig bearing_;
};

Scenario Scenario::load(const std::string& path) {
  return from_string(detail::read_config_file(path, "scenario file"), path);
}

Scenario Scenario::from_string(const std::string& yaml, const std::string& source) {
  const YAML::Node root = detail::load_yaml(yaml, source);
  if (!root.IsMap()) throw ConfigError(source + ": expected a mapping at the top level");
  Scenario sc;
  sc.source_ = source;
  ScenarioReader(root, source, &sc).read();
  return sc;
}

}  // namespace bearing_sim
