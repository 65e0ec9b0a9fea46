#include "bearing_sim/core/virtual_accelerometer.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {
// The path is a digital biquad at the input rate; above this fraction of it the design
// (exact poles, fitted numerator) no longer resembles the analog path.
constexpr double kMaxPathResonanceFraction = 0.45;
constexpr int kMaxAntiAliasOrder = 16;

struct Problem {
  std::string key, what;
  bool any() const { return !key.empty(); }
};

// Checks that do not depend on the input rate; keys as in the YAML file.
Problem config_problem(const AccelerometerConfig& c) {
  if (!c.mount_point_m.allFinite()) return {"mount_point_mm", "must be finite"};
  if (!c.axis.allFinite() || c.axis.norm() < 1e-9) return {"axis", "must be a finite, non-zero vector"};
  if (!(c.path_resonance_hz >= 0.0) || !std::isfinite(c.path_resonance_hz))
    return {"path_resonance_Hz", "must be >= 0 (0: no transmission path)"};
  // Mounts and housings have 0.5-20 % of critical damping; below 1e-4 the resonance never
  // settles and its filter loses its digits (a denormal gave an all-NaN signal).
  if (!(c.path_damping_ratio >= 1e-4 && c.path_damping_ratio < 1.0))
    return {"path_damping_ratio", "must be in [1e-4, 1)"};
  if (!(c.sensitivity_V_per_m_s2 > 0.0) || !std::isfinite(c.sensitivity_V_per_m_s2))
    return {"sensitivity_mV_per_g", "must be > 0"};
  if (!(c.noise_density_m_s2_per_sqrt_hz >= 0.0) || !std::isfinite(c.noise_density_m_s2_per_sqrt_hz))
    return {"noise_density_ug_per_sqrt_Hz", "must be >= 0"};
  if (!(c.range_m_s2 > 0.0) || !std::isfinite(c.range_m_s2)) return {"range_g", "must be > 0"};
  if (c.adc_bits < 8 || c.adc_bits > 32) return {"adc_bits", "must be between 8 and 32"};
  // At least 1 Hz: a vanishing rate made the decimation ratio overflow.
  if (!(c.output_rate_hz >= 1.0 && c.output_rate_hz <= kMaxSensorOutputRate_Hz))
    return {"output_rate_Hz", "must be in [1, 51200] Hz"};
  if (!(c.anti_alias_cutoff_fraction > 0.0 && c.anti_alias_cutoff_fraction < 0.5))
    return {"anti_alias_cutoff_fraction", "must be in (0, 0.5) (a fraction of the output rate)"};
  if (c.anti_alias_order < 2 || c.anti_alias_order > kMaxAntiAliasOrder || c.anti_alias_order % 2 != 0)
    return {"anti_alias_order", "must be even, from 2 to 16"};
  return {};
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
  r.check_keys({"name", "mount", "mount_point_mm", "axis", "path_resonance_Hz", "path_damping_ratio",
                "sensitivity_mV_per_g", "noise_density_ug_per_sqrt_Hz", "range_g", "adc_bits", "output_rate_Hz",
                "anti_alias_cutoff_fraction", "anti_alias_order", "seed", "output_unit"});
  AccelerometerConfig c;
  c.name = r.text("name", c.name);
  const std::string mount = r.text("mount", "housing");
  if (mount == "housing") c.mount = SensorMount::Housing;
  else if (mount == "moving_ring") c.mount = SensorMount::MovingRing;
  else r.fail("mount", "must be housing or moving_ring, got '" + mount + "'");
  c.mount_point_m = vector3(r, sensor, "mount_point_mm", c.mount_point_m * 1e3) * 1e-3;
  c.axis = vector3(r, sensor, "axis", c.axis);
  c.path_resonance_hz = r.number("path_resonance_Hz", c.path_resonance_hz);
  c.path_damping_ratio = r.number("path_damping_ratio", c.path_damping_ratio);
  c.sensitivity_V_per_m_s2 =
      r.number("sensitivity_mV_per_g", c.sensitivity_V_per_m_s2 * 1e3 * kStandardGravity_m_s2) * 1e-3 /
      kStandardGravity_m_s2;
  c.noise_density_m_s2_per_sqrt_hz =
      r.number("noise_density_ug_per_sqrt_Hz", c.noise_density_m_s2_per_sqrt_hz / kStandardGravity_m_s2 * 1e6) *
      1e-6 * kStandardGravity_m_s2;
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
  const Problem p = config_problem(c);
  if (p.any()) r.fail(p.key, p.what);
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

VirtualAccelerometer::VirtualAccelerometer(AccelerometerConfig config, double input_rate_hz)
    : config_(std::move(config)), input_rate_hz_(input_rate_hz) {
  const std::string who = "VirtualAccelerometer '" + config_.name + "': ";
  const Problem p = config_problem(config_);
  if (p.any()) throw InvalidInputError(who + p.key + " " + p.what);
  if (!(input_rate_hz > 0.0) || !std::isfinite(input_rate_hz))
    throw InvalidInputError(who + "input rate must be > 0 Hz");
  const double f_out = config_.output_rate_hz;
  if (f_out > input_rate_hz * (1.0 + 1e-12))
    throw InvalidInputError(who + "output_rate_Hz " + std::to_string(f_out) + " exceeds the input (dynamics) rate " +
                            std::to_string(input_rate_hz) + " Hz; raise the dynamics' sample rate");
  const double ratio = input_rate_hz / f_out;
  decimation_ratio_ = static_cast<int>(std::lround(ratio));
  if (std::abs(ratio - decimation_ratio_) > 1e-9 * ratio)
    throw InvalidInputError(who + "output_rate_Hz " + std::to_string(f_out) + " does not divide the input rate " +
                            std::to_string(input_rate_hz) + " Hz (decimation needs an integer ratio)");
  if (config_.path_resonance_hz > kMaxPathResonanceFraction * input_rate_hz)
    throw InvalidInputError(who + "path_resonance_Hz " + std::to_string(config_.path_resonance_hz) +
                            " must be below 0.45 x the input rate (" + std::to_string(input_rate_hz) +
                            " Hz): raise the dynamics' sample rate, or 0 for no path");

  axis_ = config_.axis.normalized();
  lever_ = config_.mount_point_m.cross(axis_);
  has_path_ = config_.path_resonance_hz > 0.0;
  if (has_path_) path_ = design_seismic_path(config_.path_resonance_hz, config_.path_damping_ratio, input_rate_hz);
  const std::vector<Biquad> aa = design_butterworth_lowpass(
      config_.anti_alias_order, config_.anti_alias_cutoff_fraction * f_out, input_rate_hz);
  anti_alias_sections_ = static_cast<int>(aa.size());
  std::copy(aa.begin(), aa.end(), anti_alias_);
  // White noise of one-sided density D over 0..fs/2 has variance D^2 fs/2.
  noise_sigma_m_s2_ = config_.noise_density_m_s2_per_sqrt_hz * std::sqrt(0.5 * input_rate_hz);
  // Two's-complement ADC over +-range: 2^bits codes, -2^(bits-1) .. 2^(bits-1) - 1.
  const double codes = std::ldexp(1.0, config_.adc_bits);
  quantization_step_m_s2_ = 2.0 * config_.range_m_s2 / codes;
  code_min_ = -0.5 * codes;
  code_max_ = 0.5 * codes - 1.0;
  output_scale_ = config_.output_unit == SensorOutputUnit::Voltage_V ? config_.sensitivity_V_per_m_s2 : 1.0;
  reset();
}

void VirtualAccelerometer::reset() {
  path_.reset();
  for (int i = 0; i < anti_alias_sections_; ++i) anti_alias_[i].reset();
  decimation_phase_ = 0;
  clipped_samples_ = 0;
  rng_.seed(config_.seed);
  has_spare_normal_ = false;
}

double VirtualAccelerometer::gaussian() {
  // Box-Muller on mt19937_64 (fully specified by the standard, unlike normal_distribution):
  // the same seed gives the same noise on every platform.
  if (has_spare_normal_) {
    has_spare_normal_ = false;
    return spare_normal_;
  }
  const double u1 = (static_cast<double>(rng_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
  const double u2 = static_cast<double>(rng_() >> 11) * 0x1.0p-53;          // [0, 1)
  const double radius = std::sqrt(-2.0 * std::log(u1)), angle = 2.0 * kPi * u2;
  spare_normal_ = radius * std::sin(angle);
  has_spare_normal_ = true;
  return radius * std::cos(angle);
}

double VirtualAccelerometer::ideal_axis_acceleration(const Vector5& a, double ring_angle_rad) const {
  // a_point = a_t + alpha x r, alpha = (theta_x'', theta_y'', 0); (alpha x r).n = alpha.(r x n).
  Eigen::Vector3d n = axis_, lever = lever_;
  if (config_.mount == SensorMount::MovingRing) {
    // The sensor turns with the ring: rotate r and n (hence r x n) by the ring angle about z.
    // The constant centripetal term is left out (an ICP sensor is AC-coupled), as are the
    // Coriolis terms of order ring speed x tilt rate (tiny against the vibration).
    const double c = std::cos(ring_angle_rad), s = std::sin(ring_angle_rad);
    n = Eigen::Vector3d(c * axis_.x() - s * axis_.y(), s * axis_.x() + c * axis_.y(), axis_.z());
    lever = Eigen::Vector3d(c * lever_.x() - s * lever_.y(), s * lever_.x() + c * lever_.y(), lever_.z());
  }
  return a(0) * n.x() + a(1) * n.y() + a(2) * n.z() + a(3) * lever.x() + a(4) * lever.y();
}

bool VirtualAccelerometer::push(const Vector5& ring_acceleration, double ring_angle_rad, double* output) {
  return push_axis_acceleration(ideal_axis_acceleration(ring_acceleration, ring_angle_rad), output);
}

void VirtualAccelerometer::push_block(const std::vector<DynamicSample>& samples, std::vector<double>* output) {
  double y = 0.0;
  for (const DynamicSample& s : samples)
    if (push(s.acceleration, s.ring_angle_rad, &y)) output->push_back(y);
}

bool VirtualAccelerometer::push_axis_acceleration(double a_m_s2, double* output) {
  // A NaN would stay in the filter states for good: refuse it.
  if (!std::isfinite(a_m_s2)) throw InvalidInputError("VirtualAccelerometer: non-finite input acceleration");
  double y = has_path_ ? path_.process(a_m_s2) : a_m_s2;
  // Sensor noise after the path: it is electronic, not shaped by the mechanics.
  if (noise_sigma_m_s2_ > 0.0) y += noise_sigma_m_s2_ * gaussian();
  for (int i = 0; i < anti_alias_sections_; ++i) y = anti_alias_[i].process(y);
  if (++decimation_phase_ < decimation_ratio_) return false;
  decimation_phase_ = 0;
  // ADC: round to the nearest code (mid-tread), saturate at the ends of the range.
  double code = std::floor(y / quantization_step_m_s2_ + 0.5);
  if (code > code_max_ || code < code_min_) {
    code = std::clamp(code, code_min_, code_max_);
    ++clipped_samples_;
  }
  *output = code * quantization_step_m_s2_ * output_scale_;
  return true;
}

}  // namespace bearing_sim
