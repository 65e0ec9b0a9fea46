#pragma once
// Virtual accelerometer (docs/sensor.md): what a real sensor and its data acquisition
// record from the ideal ring acceleration of BearingDynamics. Per input sample:
//   projection onto the sensing axis at the mounting point -> + the bearing's rolling noise ->
//   shaft-rate modulation ->
//   transmission path (one or several modes) -> the sensor's mounted resonance -> + the
//   machine's lines -> sensor noise ->
//   anti-alias low-pass -> decimation -> + the machine's broadband floor -> clipping to
//   the range -> ADC quantization -> sensitivity (optional volts).
// Cheap and allocation-free per sample, deterministic for a seed.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/biquad.hpp"
#include "bearing_sim/core/coloured_floor.hpp"
#include "bearing_sim/core/machine_background.hpp"
#include "bearing_sim/core/seeded_gaussian.hpp"
#include "bearing_sim/core/transmission_path.hpp"

namespace bearing_sim {

constexpr double kStandardGravity_m_s2 = 9.80665;
constexpr double kMaxSensorOutputRate_Hz = 51200.0;

enum class SensorMount {
  // On the housing of the fixed ring: the point and the axis are fixed in the bearing frame.
  Housing,
  // On the moving (rotating) ring: the point and the axis are given at ring angle 0 and turn
  // with the ring about z.
  MovingRing,
};

enum class SensorOutputUnit { Acceleration_m_s2, Voltage_V };

struct AccelerometerConfig {
  std::string name = "accelerometer";
  SensorMount mount = SensorMount::Housing;
  Eigen::Vector3d mount_point_m = Eigen::Vector3d::Zero();  // bearing frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();          // sensing direction (normalized on use)
  // The structure's response at the sensor to ring acceleration across its axis, in the
  // bearing plane (along z x axis), per unit of the response along it: a housing's modes are
  // not aligned with the sensor, so a horizontal force also moves a vertical sensor. 0: none.
  double cross_axis_coupling = 0.0;
  // Transmission path between the ring and the sensor's seismic element (seismic
  // transmissibility, biquad.hpp). 0 Hz: no path (rigid, stud-mounted on the ring).
  // With path_modes, these are its dominant mode's (an envelope band's centre).
  double path_resonance_hz = 3000.0;
  double path_damping_ratio = 0.05;
  // Several modes (transmission_path.hpp); when not empty, they are the path.
  std::vector<PathMode> path_modes;
  // The sensor's mounted resonance: its seismic mass on the stiffness of its mount (a magnet
  // or an adhesive pad: a few kHz; a stud: tens of kHz, above the band), in series with the
  // path (seismic transmissibility, biquad.hpp). 0 Hz: none (the default).
  double mount_resonance_hz = 0.0;
  double mount_damping_ratio = 0.05;
  // The machine around the bearing (machine_background.hpp); empty: none.
  InstallationConfig installation;
  double sensitivity_V_per_m_s2 = 0.100 / kStandardGravity_m_s2;           // 100 mV/g
  double noise_density_m_s2_per_sqrt_hz = 1.5e-6 * kStandardGravity_m_s2;  // 1.5 ug/sqrt(Hz)
  double range_m_s2 = 50.0 * kStandardGravity_m_s2;                        // +-50 g full scale
  int adc_bits = 24;
  double output_rate_hz = 10000.0;
  double anti_alias_cutoff_fraction = 0.4;  // of the output rate
  int anti_alias_order = 8;                 // Butterworth, even
  std::uint64_t seed = 1;
  SensorOutputUnit output_unit = SensorOutputUnit::Acceleration_m_s2;
};

// A sensor file whose only top-level key is `sensor:` (read by src/core/sensor_config_yaml.hpp's
// parse_accelerometer_config).
AccelerometerConfig load_accelerometer_config(const std::string& path);
AccelerometerConfig accelerometer_config_from_string(const std::string& yaml, const std::string& source);

class VirtualAccelerometer {
 public:
  // input_rate_hz: the rate of the samples pushed (the dynamics' sample rate). Throws
  // InvalidInputError for an inconsistent configuration: output rate above 51.2 kHz or above
  // the input rate or not dividing it, path resonance not below 0.45 x the input rate, ...
  VirtualAccelerometer(AccelerometerConfig config, double input_rate_hz);

  // One input sample of the moving ring's acceleration (x, y, z, theta_x, theta_y; m/s^2,
  // rad/s^2) at the rotating ring's angle. Returns true, with *output set, when an output
  // sample is due (every decimation_ratio() inputs).
  bool push(const Vector5& ring_acceleration, double ring_angle_rad, double* output);
  bool push(const DynamicSample& sample, double* output) {
    return push(sample.acceleration, sample.ring_angle_rad, output);
  }
  // Appends the outputs of a block; no allocation when *output has the capacity.
  void push_block(const std::vector<DynamicSample>& samples, std::vector<double>* output);
  // The chain after the projection: one sample of the ideal acceleration on the sensing axis,
  // the turning ring at ring_angle_rad (for the installation's speed-locked lines).
  bool push_axis_acceleration(double axis_acceleration_m_s2, double ring_angle_rad, double* output);
  // The same with the ring standing still at its last angle.
  bool push_axis_acceleration(double axis_acceleration_m_s2, double* output);

  // The ideal (noise-free, unfiltered) acceleration at the mounting point along the axis,
  // a.n = a_t.n + alpha.(r x n), alpha = (theta_x'', theta_y'', 0).
  double ideal_axis_acceleration(const Vector5& ring_acceleration, double ring_angle_rad) const;

  // Filter states, noise generator (re-seeded) and decimation phase back to the start.
  void reset();

  const AccelerometerConfig& config() const { return config_; }
  double input_rate_hz() const { return input_rate_hz_; }
  double output_rate_hz() const { return config_.output_rate_hz; }
  int decimation_ratio() const { return decimation_ratio_; }
  // ADC step in the output unit (m/s^2 or V) and in m/s^2.
  double quantization_step() const { return quantization_step_m_s2_ * output_scale_; }
  double quantization_step_m_s2() const { return quantization_step_m_s2_; }
  double noise_sigma_m_s2() const { return noise_sigma_m_s2_; }                  // per input sample
  double rolling_noise_sigma_m_s2() const { return rolling_noise_sigma_m_s2_; }  // per input sample
  std::uint64_t clipped_sample_count() const { return clipped_samples_; }
  // The path as digitised, at f_hz (the analog form: modal_transmissibility), the mounted
  // resonance included.
  std::complex<double> path_response(double f_hz) const;
  // The broadband floor's density as realised, at f_hz (0 without a floor).
  double floor_density(double f_hz) const { return has_floor_ ? floor_.realised_density(f_hz) : 0.0; }

 private:
  bool push_sample(double axis_acceleration_m_s2, const MachineBackground::Sample& background, double* output);

  AccelerometerConfig config_;
  double input_rate_hz_ = 0.0;
  int decimation_ratio_ = 1;
  int decimation_phase_ = 0;
  Eigen::Vector3d axis_ = Eigen::Vector3d::UnitX();
  Eigen::Vector3d translation_direction_ = Eigen::Vector3d::UnitX();  // axis + coupling (z x axis)
  Eigen::Vector3d lever_ = Eigen::Vector3d::Zero();                   // r x n: the tilt pick-up
  bool has_path_ = false;
  TransmissionPath path_;
  bool has_mount_ = false;
  Biquad mount_;
  bool has_background_ = false, has_floor_ = false;
  MachineBackground background_;
  ColouredFloor floor_;
  Biquad anti_alias_[8];
  int anti_alias_sections_ = 0;
  double noise_sigma_m_s2_ = 0.0;
  double rolling_noise_sigma_m_s2_ = 0.0;
  double quantization_step_m_s2_ = 0.0;
  double code_min_ = 0.0, code_max_ = 0.0;
  double output_scale_ = 1.0;  // 1 or the sensitivity
  std::uint64_t clipped_samples_ = 0;
  SeededGaussian noise_;
  SeededGaussian rolling_noise_;
};

}  // namespace bearing_sim
