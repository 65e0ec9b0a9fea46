// Parameter studies over a base bearing file (see sweep.hpp).
#include "bearing_sim/core/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>

#include "bearing_config_reader.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/flexible_bearing.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/symmetric_eigen.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {
// ---------------------------------------------------------------------------
// The one table of sweepable parameters.
// ---------------------------------------------------------------------------
enum class Target { BearingKey, RadialLoad, AxialLoad, AxialLoadRatio, Moment, Speed, ImperfectionScale };

struct ParameterDef {
  const char* name;
  Target target;
  std::vector<const char*> keys;  // bearing-file keys (Target::BearingKey); "a.b" for nested
  bool integer;
  const char* description;
};

const std::vector<ParameterDef>& parameter_table() {
  static const std::vector<ParameterDef> table = {
      {"inner_groove_curvature",
       Target::BearingKey,
       {"inner_groove_curvature"},
       false,
       "fi = r_groove / d, inner race"},
      {"outer_groove_curvature",
       Target::BearingKey,
       {"outer_groove_curvature"},
       false,
       "fo = r_groove / d, outer race"},
      {"groove_curvature",
       Target::BearingKey,
       {"inner_groove_curvature", "outer_groove_curvature"},
       false,
       "fi = fo together"},
      {"balls_per_row", Target::BearingKey, {"balls_per_row"}, true, "Z (waviness orders written with Z follow it)"},
      {"clearance_um",
       Target::BearingKey,
       {"clearance_um"},
       false,
       "g0 per ball along the contact line, um (< 0: preload)"},
      {"contact_angle_deg", Target::BearingKey, {"contact_angle_deg"}, false, "nominal contact angle a0, deg"},
      {"ball_diameter_mm", Target::BearingKey, {"ball_diameter_mm"}, false, "d, mm"},
      {"pitch_diameter_mm", Target::BearingKey, {"pitch_diameter_mm"}, false, "dm, mm"},
      {"row_spacing_mm", Target::BearingKey, {"row_spacing_mm"}, false, "axial distance between the rows, mm"},
      {"rotating_mass_kg", Target::BearingKey, {"rotating_mass_kg"}, false, "moving mass, kg"},
      {"contact_damping_Ns_per_m",
       Target::BearingKey,
       {"damping.contact_damping_Ns_per_m"},
       false,
       "c_n per loaded contact, N*s/m"},
      {"radial_load_N", Target::RadialLoad, {}, false, "Fx (Fy = 0), N"},
      {"axial_load_N", Target::AxialLoad, {}, false, "Fz, N"},
      {"axial_load_ratio", Target::AxialLoadRatio, {}, false, "Fz = ratio * |(Fx, Fy)| (the CT paper's Ca = Fa/Fr)"},
      {"moment_Nm", Target::Moment, {}, false, "My, N*m"},
      {"speed_rpm", Target::Speed, {}, false, "speed of the rotating ring, rpm"},
      {"imperfection_scale",
       Target::ImperfectionScale,
       {},
       false,
       "factor on every waviness amplitude, the roughness and the ball diameter variation"},
  };
  return table;
}

const ParameterDef* find_parameter(const std::string& name) {
  for (const auto& p : parameter_table())
    if (name == p.name) return &p;
  return nullptr;
}

std::string known_parameters() {
  std::string s;
  for (const auto& p : parameter_table()) s += (s.empty() ? "" : ", ") + std::string(p.name);
  return s;
}

// ---------------------------------------------------------------------------
// Reading the definition.
// ---------------------------------------------------------------------------
[[noreturn]] void fail(const std::string& source, const std::string& key, const std::string& what) {
  throw InvalidInputError("sweep definition " + source + ": " + (key.empty() ? "" : "key '" + key + "': ") + what);
}

void check_keys(const YAML::Node& map, const std::string& source, const std::string& prefix,
                const std::vector<std::string>& known) {
  for (const auto& kv : map) {
    if (!kv.first.IsScalar()) fail(source, prefix + "?", "a key must be a plain name, not a list or mapping");
    const std::string k = kv.first.Scalar();
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      std::string list;
      for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
      fail(source, prefix + k, "unknown key (known keys: " + list + ")");
    }
  }
}

double read_number(const YAML::Node& n, const std::string& source, const std::string& key) {
  double v = 0.0;
  try {
    if (!n.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(source, key, "expected a number");
  }
  if (!std::isfinite(v)) fail(source, key, "must be a finite number");
  return v;
}

std::vector<double> read_vector(const YAML::Node& n, std::size_t count, const std::string& source,
                                const std::string& key) {
  if (!n.IsSequence() || n.size() != count)
    fail(source, key, "expected a list of " + std::to_string(count) + " numbers");
  std::vector<double> v;
  for (std::size_t i = 0; i < count; ++i) v.push_back(read_number(n[i], source, key));
  return v;
}

std::vector<double> read_values(const YAML::Node& study, const std::string& source, const std::string& prefix) {
  const bool has_values = static_cast<bool>(study["values"]);
  const bool has_range = static_cast<bool>(study["range"]);
  if (has_values == has_range) fail(source, prefix + "values", "give either 'values' (a list) or 'range'");
  std::vector<double> values;
  if (has_values) {
    const YAML::Node v = study["values"];
    if (!v.IsSequence() || v.size() == 0) fail(source, prefix + "values", "expected a non-empty list of numbers");
    for (std::size_t i = 0; i < v.size(); ++i) values.push_back(read_number(v[i], source, prefix + "values"));
  } else {
    const YAML::Node r = study["range"];
    const std::string rk = prefix + "range";
    if (!r.IsMap()) fail(source, rk, "expected {from, to, step} or {from, to, count}");
    check_keys(r, source, rk + ".", {"from", "to", "step", "count"});
    if (!r["from"] || !r["to"]) fail(source, rk, "needs 'from' and 'to'");
    const double from = read_number(r["from"], source, rk + ".from");
    const double to = read_number(r["to"], source, rk + ".to");
    if (static_cast<bool>(r["step"]) == static_cast<bool>(r["count"]))
      fail(source, rk, "give either 'step' or 'count'");
    if (r["count"]) {
      const double count = read_number(r["count"], source, rk + ".count");
      if (count < 1 || count > 10000 || count != std::floor(count))
        fail(source, rk + ".count", "must be an integer in [1, 10000]");
      const int n = static_cast<int>(count);
      for (int i = 0; i < n; ++i) values.push_back(n == 1 ? from : from + (to - from) * i / (n - 1));
    } else {
      const double step = read_number(r["step"], source, rk + ".step");
      if (!(step > 0.0)) fail(source, rk + ".step", "must be > 0");
      if (to < from) fail(source, rk, "'to' must not be below 'from'");
      const double n = std::floor((to - from) / step + 1e-9);
      if (n > 10000) fail(source, rk, "more than 10000 values");
      for (int i = 0; i <= static_cast<int>(n); ++i) values.push_back(from + i * step);
    }
  }
  return values;
}

std::string dirname_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// "208", "Z", "Z-1", "2Z+1" -> integer for balls per row z: `\s*[0-9]+\s*` or
// `\s*[0-9]*\s*[Zz]\s*([+-]\s*[0-9]+)?\s*`. Scanned by hand: std::regex doubled this file's
// compile time.
bool resolve_order(const std::string& text, int z, int* order) {
  std::size_t i = 0;
  const auto skip_space = [&] {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  };
  const auto digits = [&] {
    const std::size_t start = i;
    while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
    return text.substr(start, i - start);
  };
  skip_space();
  const std::string factor = digits();
  skip_space();
  if (i == text.size()) {
    if (factor.empty()) return false;
    *order = std::stoi(factor);
    return true;
  }
  if (text[i] != 'Z' && text[i] != 'z') return false;
  ++i;
  skip_space();
  char sign = 0;
  std::string term;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) {
    sign = text[i++];
    skip_space();
    term = digits();
    if (term.empty()) return false;
    skip_space();
  }
  if (i != text.size()) return false;
  const int k = factor.empty() ? 1 : std::stoi(factor);
  const int offset = sign ? (sign == '-' ? -1 : 1) * std::stoi(term) : 0;
  *order = k * z + offset;
  return true;
}

// The imperfections section of one case: orders resolved against Z, amplitudes scaled.
YAML::Node resolve_imperfections(const YAML::Node& spec, int z, double scale, const std::string& where) {
  YAML::Node out = YAML::Clone(spec);
  if (!out || out.IsNull()) return out;
  if (!out.IsMap()) throw InvalidInputError(where + ": imperfections must be a mapping");
  if (out["waviness"] && out["waviness"].IsSequence()) {
    for (std::size_t i = 0; i < out["waviness"].size(); ++i) {
      YAML::Node w = out["waviness"][i];
      if (!w.IsMap()) continue;
      if (w["order"] && w["order"].IsScalar()) {
        int order = 0;
        if (!resolve_order(w["order"].as<std::string>(), z, &order))
          throw InvalidInputError(where + ": waviness " + std::to_string(i + 1) + " order '" +
                                  w["order"].as<std::string>() + "': expected an integer or Z, Z-1, 2Z+1, ...");
        w["order"] = order;
      }
      if (scale != 1.0 && w["amplitude_um"] && w["amplitude_um"].IsScalar())
        w["amplitude_um"] = w["amplitude_um"].as<double>() * scale;
    }
  }
  if (scale != 1.0) {
    for (const char* key : {"roughness_rms_um", "ball_diameter_variation_um"})
      if (out[key] && out[key].IsScalar()) out[key] = out[key].as<double>() * scale;
  }
  return out;
}

void set_nested(YAML::Node root, const std::string& dotted, double value, bool integer) {
  const auto dot = dotted.find('.');
  if (dot == std::string::npos) {
    if (integer) root[dotted] = static_cast<long long>(std::llround(value));
    else root[dotted] = value;
    return;
  }
  YAML::Node child = root[dotted.substr(0, dot)];
  set_nested(child, dotted.substr(dot + 1), value, integer);
}

std::string format_value(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

}  // namespace

const std::vector<SweepParameterInfo>& sweep_parameters() {
  static const std::vector<SweepParameterInfo> list = [] {
    std::vector<SweepParameterInfo> l;
    for (const auto& p : parameter_table()) l.push_back({p.name, p.description});
    return l;
  }();
  return list;
}

namespace {

// The YAML text of a node, emitted once; read back for each case (reloaded_yaml). Empty: none.
std::string emitted_yaml(const YAML::Node& node) { return node ? YAML::Dump(node) : std::string(); }

// The node of such a text, without the marks of its lines, as a copy of the definition's
// node has them (YAML::Clone): an error a case's node throws reads as before.
YAML::Node reloaded_yaml(const std::string& text) { return YAML::Clone(YAML::Load(text)); }

// `bearing:`: the base bearing file (relative to base_dir), valid on its own. Its path and
// text go into the definition; its node is returned.
YAML::Node read_base_bearing(const YAML::Node& root, const std::string& source, const std::string& base_dir,
                             SweepDefinition* d) {
  if (!root["bearing"] || !root["bearing"].IsScalar()) fail(source, "bearing", "required: the base bearing file");
  const std::string b = root["bearing"].as<std::string>();
  d->bearing_path = (!b.empty() && b[0] == '/') ? b : base_dir + "/" + b;
  YAML::Node bearing;
  try {
    d->bearing_yaml = detail::read_config_file(d->bearing_path, "bearing file");
    bearing = detail::load_yaml(d->bearing_yaml, d->bearing_path);
  } catch (const ConfigError& e) {
    fail(source, "bearing", std::string("cannot read the base bearing file: ") + e.what());
  }
  // The base file must be valid on its own.
  try {
    parse_bearing_config(bearing, d->bearing_path);
  } catch (const ConfigError& e) {
    fail(source, "bearing", std::string("the base bearing file is invalid: ") + e.what());
  }
  return bearing;
}

// `operating_point:` (optional), and a dynamic sweep's duration and sample rate in range.
void read_operating_point(const YAML::Node& op, const std::string& source, SweepDefinition* d) {
  if (op) {
    if (!op.IsMap()) fail(source, "operating_point", "expected a mapping");
    check_keys(op, source, "operating_point.", {"force_N", "moment_Nm", "speed_rpm", "duration_s", "sample_rate_hz"});
    if (op["force_N"]) {
      const auto f = read_vector(op["force_N"], 3, source, "operating_point.force_N");
      d->operating_point.load.head<3>() << f[0], f[1], f[2];
    }
    if (op["moment_Nm"]) {
      const auto m = read_vector(op["moment_Nm"], 2, source, "operating_point.moment_Nm");
      d->operating_point.load.tail<2>() << m[0], m[1];
    }
    if (op["speed_rpm"])
      d->operating_point.speed_rpm = read_number(op["speed_rpm"], source, "operating_point.speed_rpm");
    if (op["duration_s"])
      d->operating_point.duration_s = read_number(op["duration_s"], source, "operating_point.duration_s");
    if (op["sample_rate_hz"])
      d->operating_point.sample_rate_hz = read_number(op["sample_rate_hz"], source, "operating_point.sample_rate_hz");
  }
  if (d->dynamic) {
    if (!(d->operating_point.duration_s > 0.0 && d->operating_point.duration_s <= 100.0))
      fail(source, "operating_point.duration_s", "must be in (0, 100] s");
    if (!(d->operating_point.sample_rate_hz >= 100.0 && d->operating_point.sample_rate_hz <= 1e6))
      fail(source, "operating_point.sample_rate_hz", "must be in [100, 1e6] Hz");
  }
}

// `imperfection_sets:`, or a single `imperfections:`, or else the base bearing file's own.
void read_imperfection_sets(const YAML::Node& root, const YAML::Node& bearing, const std::string& source,
                            SweepDefinition* d) {
  if (root["imperfections"] && root["imperfection_sets"])
    fail(source, "imperfections", "give either 'imperfections' or 'imperfection_sets', not both");
  if (root["imperfection_sets"]) {
    const YAML::Node sets = root["imperfection_sets"];
    if (!sets.IsSequence() || sets.size() == 0)
      fail(source, "imperfection_sets", "expected a non-empty list of {name, imperfections}");
    for (std::size_t i = 0; i < sets.size(); ++i) {
      const std::string key = "imperfection_sets[" + std::to_string(i) + "]";
      if (!sets[i].IsMap()) fail(source, key, "expected {name, imperfections}");
      check_keys(sets[i], source, key + ".", {"name", "imperfections"});
      SweepImperfectionSet s;
      s.name = sets[i]["name"] ? sets[i]["name"].as<std::string>() : "set" + std::to_string(i + 1);
      s.imperfections_yaml = emitted_yaml(sets[i]["imperfections"]);
      d->imperfection_sets.push_back(s);
    }
  } else if (root["imperfections"]) {
    d->imperfection_sets.push_back({"imperfections", emitted_yaml(root["imperfections"]), false});
  } else {
    SweepImperfectionSet s;
    s.name = "bearing_file";
    s.imperfections_yaml = emitted_yaml(bearing["imperfections"]);
    s.from_bearing_file = true;
    d->imperfection_sets.push_back(s);
  }
}

// One study: a parameter of the table and its values.
SweepStudy read_study(const YAML::Node& n, const std::string& source, const std::string& prefix) {
  if (!n["parameter"] || !n["parameter"].IsScalar()) fail(source, prefix + "parameter", "required");
  SweepStudy s;
  s.parameter = n["parameter"].as<std::string>();
  if (!find_parameter(s.parameter))
    fail(source, prefix + "parameter", "unknown parameter '" + s.parameter + "' (known: " + known_parameters() + ")");
  s.values = read_values(n, source, prefix);
  return s;
}

// `studies:`, or a single top-level `parameter:` with `values:` or `range:`.
void read_studies(const YAML::Node& root, const std::string& source, SweepDefinition* d) {
  if (root["studies"]) {
    if (root["parameter"] || root["values"] || root["range"])
      fail(source, "studies", "give either 'studies' or a single 'parameter' with 'values'/'range'");
    const YAML::Node studies = root["studies"];
    if (!studies.IsSequence() || studies.size() == 0)
      fail(source, "studies", "expected a non-empty list of {parameter, values | range}");
    for (std::size_t i = 0; i < studies.size(); ++i) {
      const std::string prefix = "studies[" + std::to_string(i) + "].";
      if (!studies[i].IsMap()) fail(source, prefix, "expected {parameter, values | range}");
      check_keys(studies[i], source, prefix, {"parameter", "values", "range"});
      d->studies.push_back(read_study(studies[i], source, prefix));
    }
  } else if (root["parameter"]) {
    d->studies.push_back(read_study(root, source, ""));
  } else {
    fail(source, "studies", "required: a list of {parameter, values | range} (or a top-level 'parameter')");
  }
}

SweepDefinition parse_sweep_definition(const YAML::Node& root, const std::string& source, const std::string& base_dir) {
  if (!root || !root.IsMap()) fail(source, "", "expected a YAML mapping");
  check_keys(root, source, "",
             {"name", "bearing", "analysis", "operating_point", "imperfections", "imperfection_sets", "studies",
              "parameter", "values", "range"});
  SweepDefinition d;
  d.source = source;
  d.name = root["name"] ? root["name"].as<std::string>() : source;
  const YAML::Node bearing = read_base_bearing(root, source, base_dir, &d);
  const std::string analysis = root["analysis"] ? root["analysis"].as<std::string>() : "dynamic";
  if (analysis == "dynamic") d.dynamic = true;
  else if (analysis == "static") d.dynamic = false;
  else fail(source, "analysis", "must be dynamic or static, got '" + analysis + "'");

  read_operating_point(root["operating_point"], source, &d);
  read_imperfection_sets(root, bearing, source, &d);
  read_studies(root, source, &d);
  sweep_cases(d);  // validates every case (throws naming the study and value)
  return d;
}

}  // namespace

SweepDefinition load_sweep_definition(const std::string& path) {
  std::string text;
  try {
    text = detail::read_config_file(path, "sweep definition");
  } catch (const ConfigError& e) {  // not a readable regular file
    throw InvalidInputError(std::string("sweep definition ") + e.what());
  }
  return sweep_definition_from_string(text, path, dirname_of(path));
}

SweepDefinition sweep_definition_from_string(const std::string& yaml_text, const std::string& source,
                                             const std::string& base_dir) {
  YAML::Node root;
  try {
    root = detail::load_yaml(yaml_text, source);
  } catch (const ConfigError& e) {  // malformed, a key twice
    throw InvalidInputError(std::string("sweep definition ") + e.what());
  }
  try {
    return parse_sweep_definition(root, source, base_dir);
  } catch (const YAML::Exception& e) {  // a mapping where a name or number belongs, ...
    throw InvalidInputError("sweep definition " + source + ": a value of the wrong type: " + e.what());
  }
}

std::vector<SweepCase> sweep_cases(const SweepDefinition& d) {
  std::vector<SweepCase> cases;
  for (std::size_t si = 0; si < d.studies.size(); ++si) {
    const SweepStudy& study = d.studies[si];
    const ParameterDef* p = find_parameter(study.parameter);
    if (!p) fail(d.source, "parameter", "unknown parameter '" + study.parameter + "'");
    for (std::size_t ii = 0; ii < d.imperfection_sets.size(); ++ii) {
      const SweepImperfectionSet& set = d.imperfection_sets[ii];
      for (double value : study.values) {
        const std::string where = "sweep definition " + d.source + ": study " + std::to_string(si + 1) + " (" +
                                  study.parameter + " = " + format_value(value) + ", imperfections '" + set.name + "')";
        SweepCase c;
        c.study = static_cast<int>(si);
        c.parameter = study.parameter;
        c.value = value;
        c.imperfection_set = static_cast<int>(ii);
        c.imperfection_set_name = set.name;
        c.operating_point = d.operating_point;
        YAML::Node bearing = reloaded_yaml(d.bearing_yaml);
        double scale = 1.0;
        Vector5& load = c.operating_point.load;
        switch (p->target) {
          case Target::BearingKey:
            if (p->integer && value != std::floor(value))
              throw InvalidInputError(where + ": " + study.parameter + " must be an integer");
            for (const char* key : p->keys) set_nested(bearing, key, value, p->integer);
            break;
          case Target::RadialLoad:
            load[0] = value;
            load[1] = 0.0;
            break;
          case Target::AxialLoad:
            load[2] = value;
            break;
          case Target::AxialLoadRatio:
            load[2] = value * std::hypot(load[0], load[1]);
            break;
          case Target::Moment:
            load[4] = value;
            break;
          case Target::Speed:
            c.operating_point.speed_rpm = value;
            break;
          case Target::ImperfectionScale:
            if (value < 0.0) throw InvalidInputError(where + ": imperfection_scale must be >= 0");
            scale = value;
            break;
        }
        const int z = bearing["balls_per_row"].as<int>();
        YAML::Node imp = resolve_imperfections(reloaded_yaml(set.imperfections_yaml), z, scale, where);
        if (imp && !imp.IsNull()) bearing["imperfections"] = imp;
        else bearing.remove("imperfections");
        try {
          c.config = parse_bearing_config(bearing, d.bearing_path + " [" + study.parameter + " = " +
                                                       format_value(value) + ", imperfections '" + set.name + "']");
          BearingModel check(c.config);  // imperfections that do not fit the bearing
        } catch (const ConfigError& e) {
          throw InvalidInputError(where + ": the varied bearing is invalid: " + e.what());
        } catch (const InvalidInputError& e) {
          throw InvalidInputError(where + ": the varied bearing is invalid: " + e.what());
        }
        // Every case's speed within the bearing's physical limit, before any case runs.
        const std::string too_fast =
            ring_speed_refusal(c.operating_point.speed_rpm * 2.0 * kPi / 60.0, c.config.pitch_diameter_m);
        if (!too_fast.empty())
          throw InvalidInputError(where + ": speed_rpm " + format_value(c.operating_point.speed_rpm) + ": " + too_fast);
        if (d.dynamic && !c.config.has_dynamics())
          throw InvalidInputError(where + ": a dynamic sweep needs rotating_mass_kg in the bearing file");
        cases.push_back(std::move(c));
      }
    }
  }
  return cases;
}

SweepResult run_sweep_case(const SweepCase& c, bool dynamic) {
  SweepResult r;
  r.c = c;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const BearingModel model(c.config);
    // A flexible ring: its static solution with the ring's modes, the stiffness condensed onto
    // the rigid-body coordinates (what the bearing offers them), so the modes below are the
    // ring's rigid-body modes on its balls with the ring's flexibility in the contacts.
    r.statics = c.config.flexible_ring.present
                    ? solve_flexible_static(FlexibleBearing(model), c.operating_point.load).rigid_coordinates
                    : solve_static(model, c.operating_point.load);
    if (c.config.has_dynamics()) {
      const Matrix5 k = 0.5 * (r.statics.stiffness + r.statics.stiffness.transpose());
      const Matrix5 m = model.mass_matrix();
      const SymmetricEigen5 eig = generalized_symmetric_eigen(k, m, false);
      if (eig.converged)
        for (int i = 0; i < 5; ++i) r.ring_modes_hz[i] = std::sqrt(std::max(eig.eigenvalues[i], 0.0)) / (2.0 * kPi);
    }
    if (dynamic) {
      SimulationRequest req;
      req.load = c.operating_point.load;
      req.ring_speed_rad_s = c.operating_point.speed_rpm * 2.0 * kPi / 60.0;
      req.duration_s = c.operating_point.duration_s;
      req.sample_rate_hz = c.operating_point.sample_rate_hz;
      r.dynamics = run_simulation(model, req);
      r.dynamic = true;
    }
    r.ok = true;
  } catch (const std::exception& e) {
    r.ok = false;
    r.error = e.what();
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::vector<SweepResult> run_sweep(const SweepDefinition& d, int threads,
                                   const std::function<void(const SweepResult&, std::size_t, std::size_t)>& on_done) {
  const std::vector<SweepCase> cases = sweep_cases(d);
  std::vector<SweepResult> results(cases.size());
  int n = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  n = std::max(1, std::min<int>(n, static_cast<int>(cases.size())));
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex mutex;
  auto worker = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= cases.size()) return;
      results[i] = run_sweep_case(cases[i], d.dynamic);  // own model per case
      std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (on_done) on_done(results[i], done, cases.size());
    }
  };
  if (n == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < n; ++t) pool.emplace_back(worker);
    for (auto& t : pool) t.join();
  }
  return results;
}

std::string sweep_csv_header() {
  return "study,parameter,value,imperfection_set,status,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,"
         "x_um,y_um,z_um,theta_x_urad,theta_y_urad,"
         "Kxx_N_per_m,Kyy_N_per_m,Kzz_N_per_m,Ktxtx_Nm_per_rad,Ktyty_Nm_per_rad,Kx_ty_N_per_rad,Kz_ty_N_per_rad,"
         "max_ball_load_N,max_pressure_MPa,loaded_balls,f1_Hz,f2_Hz,f3_Hz,f4_Hz,f5_Hz,"
         "a_rms_x_m_s2,a_rms_y_m_s2,a_rms_z_m_s2,L_dB,substeps,wall_s,error";
}

std::string sweep_csv_row(const SweepResult& r) {
  std::ostringstream os;
  os.precision(10);
  auto csv_text = [](const std::string& s) {
    std::string q = "\"";
    for (char ch : s) q += (ch == '"') ? std::string("\"\"") : std::string(1, ch == '\n' ? ' ' : ch);
    return q + "\"";
  };
  os << r.c.study + 1 << ',' << r.c.parameter << ',' << r.c.value << ',' << csv_text(r.c.imperfection_set_name) << ','
     << (r.ok ? "ok" : "error");
  const Vector5& load = r.c.operating_point.load;
  for (int i = 0; i < 5; ++i) os << ',' << load[i];
  if (r.ok) {
    const StaticSolution& s = r.statics;
    for (int i = 0; i < 5; ++i) os << ',' << s.displacement[i] * 1e6;
    os << ',' << s.stiffness(0, 0) << ',' << s.stiffness(1, 1) << ',' << s.stiffness(2, 2) << ',' << s.stiffness(3, 3)
       << ',' << s.stiffness(4, 4) << ',' << s.stiffness(0, 4) << ',' << s.stiffness(2, 4);
    int loaded = 0;
    for (const auto& b : s.balls) loaded += b.load_N > 0.0;
    os << ',' << s.max_ball_load_N << ',' << s.max_contact_pressure_Pa / 1e6 << ',' << loaded;
    for (int i = 0; i < 5; ++i) os << ',' << r.ring_modes_hz[i];
  } else {
    os << std::string(20, ',');
  }
  if (r.ok && r.dynamic) {
    os << ',' << r.dynamics.a_rms_x << ',' << r.dynamics.a_rms_y << ',' << r.dynamics.a_rms_z << ','
       << r.dynamics.level_db << ',' << r.dynamics.substeps;
  } else {
    os << ",,,,,";
  }
  char wall[32];
  std::snprintf(wall, sizeof wall, "%.3f", r.wall_s);
  os << ',' << wall << ',' << (r.ok ? "" : csv_text(r.error));
  return os.str();
}

}  // namespace bearing_sim
