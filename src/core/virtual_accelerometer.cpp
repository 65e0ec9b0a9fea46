#include "bearing_sim/core/virtual_accelerometer.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "virtual_accelerometer_checks.hpp"

namespace bearing_sim {
namespace {
// The path is a digital biquad at the input rate; above this fraction of it the design
// (exact poles, fitted numerator) no longer resembles the analog path.
constexpr double kMaxPathResonanceFraction = 0.45;
constexpr int kMaxAntiAliasOrder = 16;
// The rolling noise's own stream of the sensor's seed (the installation's are 1-5), so that
// adding it leaves every other sequence as it was.
constexpr std::uint32_t kRollingNoiseStream = 6;
}  // namespace

namespace detail {

AccelerometerProblem accelerometer_config_problem(const AccelerometerConfig& c) {
  if (!c.mount_point_m.allFinite()) return {"mount_point_mm", "must be finite"};
  if (!c.axis.allFinite() || c.axis.norm() < 1e-9) return {"axis", "must be a finite, non-zero vector"};
  if (!(std::abs(c.cross_axis_coupling) <= 1.0)) return {"cross_axis_coupling", "must be in [-1, 1]"};
  if (!(c.path_resonance_hz >= 0.0) || !std::isfinite(c.path_resonance_hz))
    return {"path_resonance_Hz", "must be >= 0 (0: no transmission path)"};
  // Mounts and housings have 0.5-20 % of critical damping; below 1e-4 the resonance never
  // settles and its filter loses its digits (a denormal gave an all-NaN signal).
  if (!(c.path_damping_ratio >= 1e-4 && c.path_damping_ratio < 1.0))
    return {"path_damping_ratio", "must be in [1e-4, 1)"};
  if (!(c.mount_resonance_hz >= 0.0) || !std::isfinite(c.mount_resonance_hz))
    return {"mount_resonance_Hz", "must be >= 0 (0: no mounted resonance)"};
  if (!(c.mount_damping_ratio >= 1e-4 && c.mount_damping_ratio < 1.0))
    return {"mount_damping_ratio", "must be in [1e-4, 1)"};
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
  if (c.path_modes.size() > static_cast<std::size_t>(kMaxPathModes)) return {"path_modes", "at most 16 modes"};
  double participation = 0.0;
  for (std::size_t i = 0; i < c.path_modes.size(); ++i) {
    const PathMode& m = c.path_modes[i];
    const std::string key = "path_modes[" + std::to_string(i) + "].";
    if (!(m.frequency_hz > 0.0) || !std::isfinite(m.frequency_hz)) return {key + "frequency_Hz", "must be > 0"};
    if (!(m.damping_ratio >= 1e-4 && m.damping_ratio < 1.0)) return {key + "damping_ratio", "must be in [1e-4, 1)"};
    if (!(m.participation > 0.0 && m.participation <= kMaxPathParticipation))
      return {key + "participation", "must be in (0, 10]"};
    participation += m.participation;
  }
  // A truncated list of modes may carry more than the whole path at the sensor (sum above 1:
  // the modes above the list then have shapes of the other sign there, the residual
  // 1 - sum p_r is negative). Bounded at 10 against typing errors (docs/sensor.md,
  // "Several modes").
  if (participation > kMaxPathParticipation + 1e-9)
    return {"path_modes", "the participations must add up to at most 10"};
  const InstallationProblem ip = installation_problem(c.installation);
  if (!ip.key.empty()) return {"installation." + ip.key, ip.what};
  return {};
}

}  // namespace detail

VirtualAccelerometer::VirtualAccelerometer(AccelerometerConfig config, double input_rate_hz)
    : config_(std::move(config)), input_rate_hz_(input_rate_hz) {
  const std::string who = "VirtualAccelerometer '" + config_.name + "': ";
  const detail::AccelerometerProblem p = detail::accelerometer_config_problem(config_);
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
  std::vector<PathMode> modes = config_.path_modes;
  if (modes.empty() && config_.path_resonance_hz > 0.0)
    modes.push_back({config_.path_resonance_hz, config_.path_damping_ratio, 1.0});
  for (std::size_t i = 0; i < modes.size(); ++i)
    if (modes[i].frequency_hz > kMaxPathResonanceFraction * input_rate_hz)
      throw InvalidInputError(who +
                              (config_.path_modes.empty() ? std::string("path_resonance_Hz ")
                                                          : "path_modes[" + std::to_string(i) + "].frequency_Hz ") +
                              std::to_string(modes[i].frequency_hz) + " must be below 0.45 x the input rate (" +
                              std::to_string(input_rate_hz) +
                              " Hz): raise the dynamics' sample rate, or 0 for no path");

  if (config_.mount_resonance_hz > kMaxPathResonanceFraction * input_rate_hz)
    throw InvalidInputError(who + "mount_resonance_Hz " + std::to_string(config_.mount_resonance_hz) +
                            " must be below 0.45 x the input rate (" + std::to_string(input_rate_hz) +
                            " Hz): raise the dynamics' sample rate, or 0 for no mounted resonance");

  axis_ = config_.axis.normalized();
  lever_ = config_.mount_point_m.cross(axis_);
  translation_direction_ = axis_ + config_.cross_axis_coupling * Eigen::Vector3d::UnitZ().cross(axis_);
  has_path_ = !modes.empty();
  if (has_path_) path_ = TransmissionPath(modes, input_rate_hz);
  has_mount_ = config_.mount_resonance_hz > 0.0;
  if (has_mount_) mount_ = design_seismic_path(config_.mount_resonance_hz, config_.mount_damping_ratio, input_rate_hz);
  const std::vector<Biquad> aa =
      design_butterworth_lowpass(config_.anti_alias_order, config_.anti_alias_cutoff_fraction * f_out, input_rate_hz);
  anti_alias_sections_ = static_cast<int>(aa.size());
  std::copy(aa.begin(), aa.end(), anti_alias_);
  const InstallationConfig& installation = config_.installation;
  has_background_ = installation.has_lines() || installation.shaft_modulation_depth > 0.0;
  if (has_background_) background_ = MachineBackground(installation, input_rate_hz, config_.seed);
  has_floor_ = installation.has_floor();
  if (has_floor_)
    floor_ = ColouredFloor(installation.floor_frequencies_hz, installation.floor_density_m_s2_per_sqrt_hz, f_out, aa,
                           input_rate_hz, config_.seed);
  // White noise of one-sided density D over 0..fs/2 has variance D^2 fs/2.
  noise_sigma_m_s2_ = config_.noise_density_m_s2_per_sqrt_hz * std::sqrt(0.5 * input_rate_hz);
  rolling_noise_sigma_m_s2_ = installation.rolling_noise_m_s2_per_sqrt_hz * std::sqrt(0.5 * input_rate_hz);
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
  mount_.reset();
  for (int i = 0; i < anti_alias_sections_; ++i) anti_alias_[i].reset();
  decimation_phase_ = 0;
  clipped_samples_ = 0;
  noise_ = SeededGaussian(config_.seed);
  rolling_noise_ = SeededGaussian(config_.seed, kRollingNoiseStream);
  background_.reset();
  if (has_floor_) floor_.reset();
}

std::complex<double> VirtualAccelerometer::path_response(double f_hz) const {
  const std::complex<double> path = has_path_ ? path_.response(f_hz) : std::complex<double>(1.0);
  return has_mount_ ? path * mount_.response(f_hz, input_rate_hz_) : path;
}

double VirtualAccelerometer::ideal_axis_acceleration(const Vector5& a, double ring_angle_rad) const {
  // a_point = a_t + alpha x r, alpha = (theta_x'', theta_y'', 0); (alpha x r).n = alpha.(r x n).
  // The translation is read along n + coupling (z x n): the structure's cross-axis response.
  Eigen::Vector3d n = translation_direction_, lever = lever_;
  if (config_.mount == SensorMount::MovingRing) {
    // The sensor turns with the ring: rotate r and n (hence r x n) by the ring angle about z.
    // The constant centripetal term is left out (an ICP sensor is AC-coupled), as are the
    // Coriolis terms of order ring speed x tilt rate (tiny against the vibration).
    const double c = std::cos(ring_angle_rad), s = std::sin(ring_angle_rad);
    const Eigen::Vector3d& d = translation_direction_;
    n = Eigen::Vector3d(c * d.x() - s * d.y(), s * d.x() + c * d.y(), d.z());
    lever = Eigen::Vector3d(c * lever_.x() - s * lever_.y(), s * lever_.x() + c * lever_.y(), lever_.z());
  }
  return a(0) * n.x() + a(1) * n.y() + a(2) * n.z() + a(3) * lever.x() + a(4) * lever.y();
}

bool VirtualAccelerometer::push(const Vector5& ring_acceleration, double ring_angle_rad, double* output) {
  return push_axis_acceleration(ideal_axis_acceleration(ring_acceleration, ring_angle_rad), ring_angle_rad, output);
}

void VirtualAccelerometer::push_block(const std::vector<DynamicSample>& samples, std::vector<double>* output) {
  double y = 0.0;
  for (const DynamicSample& s : samples)
    if (push(s.acceleration, s.ring_angle_rad, &y)) output->push_back(y);
}

bool VirtualAccelerometer::push_axis_acceleration(double a_m_s2, double ring_angle_rad, double* output) {
  return push_sample(a_m_s2, has_background_ ? background_.step(ring_angle_rad) : MachineBackground::Sample{}, output);
}

bool VirtualAccelerometer::push_axis_acceleration(double a_m_s2, double* output) {
  return push_sample(a_m_s2, has_background_ ? background_.step() : MachineBackground::Sample{}, output);
}

bool VirtualAccelerometer::push_sample(double a_m_s2, const MachineBackground::Sample& background, double* output) {
  // A NaN would stay in the filter states for good: refuse it.
  if (!std::isfinite(a_m_s2)) throw InvalidInputError("VirtualAccelerometer: non-finite input acceleration");
  // The shaft-rate load variation modulates the bearing's own vibration at its source: a
  // spall's strikes follow the load where the spall is.
  if (has_background_) a_m_s2 *= background.bearing_gain;
  // The rolling noise is the bearing's too and takes the path, but not that modulation: it is
  // the random part of every loaded contact round the zone, whose sum a turning load hardly
  // changes (the real CWRU records without a fault signal show none of it; docs/sensor.md).
  if (rolling_noise_sigma_m_s2_ > 0.0) a_m_s2 += rolling_noise_sigma_m_s2_ * rolling_noise_();
  double y = has_path_ ? path_.process(a_m_s2) : a_m_s2;
  // The sensor on its mount: in series with the structure (its lines below are measured
  // through it already).
  if (has_mount_) y = mount_.process(y);
  // The machine's lines reach the sensor by their own paths: given as measured there.
  if (has_background_) y += background.lines_m_s2;
  // Sensor noise after the path: it is electronic, not shaped by the mechanics.
  if (noise_sigma_m_s2_ > 0.0) y += noise_sigma_m_s2_ * noise_();
  for (int i = 0; i < anti_alias_sections_; ++i) y = anti_alias_[i].process(y);
  if (++decimation_phase_ < decimation_ratio_) return false;
  decimation_phase_ = 0;
  // The broadband floor as it leaves the anti-alias filter (coloured_floor.hpp).
  if (has_floor_) y += floor_.next();
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
