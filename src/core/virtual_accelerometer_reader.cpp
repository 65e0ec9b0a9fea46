// Reading of a sensor file's `sensor:` mapping (sensor_config_yaml.hpp, docs/sensor.md).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/transmission_path.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "sensor_config_yaml.hpp"
#include "virtual_accelerometer_checks.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {

std::vector<PathMode> parse_path_modes(const detail::Reader& r, const YAML::Node& sensor) {
  const YAML::Node node = sensor["path_modes"];
  if (!node.IsSequence() || node.size() == 0)
    r.fail("path_modes", "expected a list of {frequency_Hz, damping_ratio, participation}");
  std::vector<PathMode> modes;
  for (std::size_t i = 0; i < node.size(); ++i) {
    const std::string key = "path_modes[" + std::to_string(i) + "]";
    if (!node[i].IsMap()) r.fail(key, "expected a mapping {frequency_Hz, damping_ratio, participation}");
    detail::Reader m(node[i], r.source(), "sensor." + key + ".");
    m.check_keys({"frequency_Hz", "damping_ratio", "participation"});
    modes.push_back({m.number("frequency_Hz", 0.0, true), m.number("damping_ratio", 0.0, true),
                     m.number("participation", 0.0, true)});
  }
  return modes;
}

Eigen::Vector3d vector3(const detail::Reader& r, const YAML::Node& map, const std::string& key,
                        const Eigen::Vector3d& fallback) {
  const YAML::Node node = map[key];
  if (!node) return fallback;
  if (!node.IsSequence() || node.size() != 3) r.fail(key, "expected a list of three numbers [x, y, z]");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    try {
      if (!node[i].IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      v(i) = node[i].as<double>();
    } catch (const YAML::Exception&) {
      r.fail(key, "expected a list of three numbers [x, y, z]");
    }
    if (!std::isfinite(v(i))) r.fail(key, "must be finite");
  }
  return v;
}

}  // namespace

AccelerometerConfig parse_accelerometer_config(const YAML::Node& sensor, const std::string& source) {
  if (!sensor || !sensor.IsMap()) throw ConfigError(source + ": key 'sensor': expected a YAML mapping of sensor keys");
  detail::Reader r(sensor, source, "sensor.");
  r.check_keys({"name", "mount", "mount_point_mm", "axis", "cross_axis_coupling", "path_resonance_Hz",
                "path_damping_ratio", "path_modes", "mount_resonance_Hz", "mount_damping_ratio", "sensitivity_mV_per_g",
                "noise_density_ug_per_sqrt_Hz", "range_g", "adc_bits", "output_rate_Hz", "anti_alias_cutoff_fraction",
                "anti_alias_order", "seed", "output_unit", "installation"});
  AccelerometerConfig c;
  c.name = r.text("name", c.name);
  const std::string mount = r.text("mount", "housing");
  if (mount == "housing") c.mount = SensorMount::Housing;
  else if (mount == "moving_ring") c.mount = SensorMount::MovingRing;
  else r.fail("mount", "must be housing or moving_ring, got '" + mount + "'");
  c.mount_point_m = vector3(r, sensor, "mount_point_mm", c.mount_point_m * 1e3) * 1e-3;
  c.axis = vector3(r, sensor, "axis", c.axis);
  c.cross_axis_coupling = r.number("cross_axis_coupling", c.cross_axis_coupling);
  c.path_resonance_hz = r.number("path_resonance_Hz", c.path_resonance_hz);
  c.path_damping_ratio = r.number("path_damping_ratio", c.path_damping_ratio);
  if (r.has("path_modes")) {
    if (r.has("path_resonance_Hz") || r.has("path_damping_ratio"))
      r.fail("path_modes", "give either path_modes or path_resonance_Hz / path_damping_ratio (one mode), not both");
    c.path_modes = parse_path_modes(r, sensor);
  }
  c.mount_resonance_hz = r.number("mount_resonance_Hz", c.mount_resonance_hz);
  c.mount_damping_ratio = r.number("mount_damping_ratio", c.mount_damping_ratio);
  if (const YAML::Node installation = r.map("installation"))
    c.installation = parse_installation_config(installation, source, "sensor.installation.");
  c.sensitivity_V_per_m_s2 = r.number("sensitivity_mV_per_g", c.sensitivity_V_per_m_s2 * 1e3 * kStandardGravity_m_s2) *
                             1e-3 / kStandardGravity_m_s2;
  c.noise_density_m_s2_per_sqrt_hz =
      r.number("noise_density_ug_per_sqrt_Hz", c.noise_density_m_s2_per_sqrt_hz / kStandardGravity_m_s2 * 1e6) * 1e-6 *
      kStandardGravity_m_s2;
  c.range_m_s2 = r.number("range_g", c.range_m_s2 / kStandardGravity_m_s2) * kStandardGravity_m_s2;
  c.adc_bits = r.integer("adc_bits", c.adc_bits);
  c.output_rate_hz = r.number("output_rate_Hz", c.output_rate_hz);
  c.anti_alias_cutoff_fraction = r.number("anti_alias_cutoff_fraction", c.anti_alias_cutoff_fraction);
  c.anti_alias_order = r.integer("anti_alias_order", c.anti_alias_order);
  const int seed = r.integer("seed", static_cast<int>(c.seed));
  r.require(seed >= 0, "seed", "must be >= 0");
  c.seed = static_cast<std::uint64_t>(seed);
  const std::string unit = r.text("output_unit", "m_s2");
  if (unit == "m_s2") c.output_unit = SensorOutputUnit::Acceleration_m_s2;
  else if (unit == "V") c.output_unit = SensorOutputUnit::Voltage_V;
  else r.fail("output_unit", "must be m_s2 or V, got '" + unit + "'");
  const detail::AccelerometerProblem p = detail::accelerometer_config_problem(c);
  if (p.any()) r.fail(p.key, p.what);
  if (!c.path_modes.empty()) {
    // What reads the path as one resonance (an envelope band) reads its dominant mode.
    const PathMode& dominant = dominant_mode(c.path_modes);
    c.path_resonance_hz = dominant.frequency_hz;
    c.path_damping_ratio = dominant.damping_ratio;
  }
  // A mounted resonance (participation 1) whose peak stands higher is the band's centre.
  if (c.mount_resonance_hz > 0.0 &&
      (c.path_resonance_hz <= 0.0 ||
       1.0 / c.mount_damping_ratio >
           (c.path_modes.empty() ? 1.0 : dominant_mode(c.path_modes).participation) / c.path_damping_ratio)) {
    c.path_resonance_hz = c.mount_resonance_hz;
    c.path_damping_ratio = c.mount_damping_ratio;
  }
  return c;
}

AccelerometerConfig accelerometer_config_from_string(const std::string& yaml, const std::string& source) {
  const YAML::Node root = detail::load_yaml(yaml, source);
  if (!root || !root.IsMap()) throw ConfigError(source + ": expected a mapping with the key 'sensor'");
  detail::Reader top(root, source, "");
  top.check_keys({"sensor"});
  if (!top.has("sensor")) top.fail("sensor", "is required but missing");
  return parse_accelerometer_config(root["sensor"], source);
}

AccelerometerConfig load_accelerometer_config(const std::string& path) {
  return accelerometer_config_from_string(detail::read_config_file(path, "the sensor file"), path);
}

}  // namespace bearing_sim
