// Reading of a sensor file's `installation:` mapping (sensor_config_yaml.hpp, docs/sensor.md).
#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/machine_background.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "indexed_key.hpp"
#include "sensor_config_yaml.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {

using detail::at;

constexpr double kMg_m_s2 = 1e-3 * kStandardGravity_m_s2;
constexpr double kUgPerSqrtHz = 1e-6 * kStandardGravity_m_s2;

std::vector<double> number_list(const detail::Reader& r, const YAML::Node& map, const std::string& key, double scale) {
  std::vector<double> values;
  const YAML::Node node = map[key];
  if (!node) return values;
  if (!node.IsSequence()) r.fail(key, "expected a list of numbers");
  for (std::size_t i = 0; i < node.size(); ++i) {
    double v = 0.0;
    try {
      if (!node[i].IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      v = node[i].as<double>();
    } catch (const YAML::Exception&) {
      r.fail(at(key, i), "expected a number");
    }
    if (!std::isfinite(v)) r.fail(at(key, i), "must be finite");
    values.push_back(v * scale);
  }
  return values;
}

}  // namespace

InstallationConfig parse_installation_config(const YAML::Node& node, const std::string& source,
                                             const std::string& prefix) {
  detail::Reader r(node, source, prefix);
  r.check_keys({"shaft_harmonics_mg", "half_orders_mg", "speed_locked_orders", "line_frequency_Hz", "line_harmonics_mg",
                "shaft_modulation_depth", "shaft_modulation_phase_deg", "floor", "rolling_noise_ug_per_sqrt_Hz"});
  InstallationConfig c;
  c.shaft_harmonics_m_s2 = number_list(r, node, "shaft_harmonics_mg", kMg_m_s2);
  c.half_orders_m_s2 = number_list(r, node, "half_orders_mg", kMg_m_s2);
  c.line_harmonics_m_s2 = number_list(r, node, "line_harmonics_mg", kMg_m_s2);
  if (const YAML::Node orders = node["speed_locked_orders"]) {
    if (!orders.IsSequence()) r.fail("speed_locked_orders", "expected a list of {order, amplitude_mg}");
    for (std::size_t i = 0; i < orders.size(); ++i) {
      const std::string item = prefix + at("speed_locked_orders", i) + ".";
      if (!orders[i].IsMap()) r.fail(at("speed_locked_orders", i), "expected a mapping {order, amplitude_mg}");
      detail::Reader o(orders[i], source, item);
      o.check_keys({"order", "amplitude_mg"});
      c.speed_locked_orders.push_back({o.number("order", 0.0, true), o.number("amplitude_mg", 0.0, true) * kMg_m_s2});
    }
  }
  c.line_frequency_hz = r.number("line_frequency_Hz", c.line_frequency_hz);
  c.shaft_modulation_depth = r.number("shaft_modulation_depth", c.shaft_modulation_depth);
  c.shaft_modulation_phase_rad = r.number("shaft_modulation_phase_deg", 0.0) * kPi / 180.0;
  c.rolling_noise_m_s2_per_sqrt_hz = r.number("rolling_noise_ug_per_sqrt_Hz", 0.0) * kUgPerSqrtHz;
  if (const YAML::Node floor = r.map("floor")) {
    detail::Reader f(floor, source, prefix + "floor.");
    f.check_keys({"frequencies_Hz", "density_ug_per_sqrt_Hz"});
    if (!f.has("frequencies_Hz")) f.fail("frequencies_Hz", "is required but missing");
    if (!f.has("density_ug_per_sqrt_Hz")) f.fail("density_ug_per_sqrt_Hz", "is required but missing");
    c.floor_frequencies_hz = number_list(f, floor, "frequencies_Hz", 1.0);
    c.floor_density_m_s2_per_sqrt_hz = number_list(f, floor, "density_ug_per_sqrt_Hz", kUgPerSqrtHz);
    if (c.floor_frequencies_hz.empty()) f.fail("frequencies_Hz", "needs at least one point");
  }
  const InstallationProblem p = installation_problem(c);
  if (!p.key.empty()) r.fail(p.key, p.what);
  return c;
}

}  // namespace bearing_sim
