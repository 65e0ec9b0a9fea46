#pragma once
// The machine around the bearing, as the virtual accelerometer sees it (docs/sensor.md,
// "Installation"): discrete lines locked to the turning ring's angle (shaft harmonics, half
// orders of a loose housing, orders of other components), the electrical line family
// (locked to time), and the shaft-rate modulation of the bearing's own signal (runout,
// unbalance load). The coloured floor is coloured_floor.hpp. Amplitudes are peak values at
// the sensor, SI inside; phases are drawn from the sensor's seed.
#include <complex>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace bearing_sim {

struct SpeedLockedOrder {
  double order = 1.0;           // x the turning ring's rate
  double amplitude_m_s2 = 0.0;  // peak
};

struct InstallationConfig {
  std::vector<double> shaft_harmonics_m_s2;  // 1, 2, ..., N x f_r (peak)
  std::vector<double> half_orders_m_s2;      // 0.5, 1.5, 2.5, ... x f_r (peak)
  std::vector<SpeedLockedOrder> speed_locked_orders;
  double line_frequency_hz = 50.0;
  std::vector<double> line_harmonics_m_s2;  // 1, 2, ..., H x the line frequency (peak)
  // m: the bearing's signal x max(0, 1 + m cos(theta + phase)), in [0, 4]: past m = 1 the load
  // leaves the struck spot for part of each turn and its strikes stop there.
  double shaft_modulation_depth = 0.0;
  double shaft_modulation_phase_rad = 0.0;
  std::vector<double> floor_frequencies_hz;  // increasing; empty: no floor
  std::vector<double> floor_density_m_s2_per_sqrt_hz;
  // The bearing's rolling noise that the contact model leaves out (its roughness is a frozen
  // profile, a line comb; real rolling over rough surfaces, debris and an assembly's damage is
  // random): white acceleration of this one-sided density at the ring, on the
  // sensing axis, passed through the path and the mount like the bearing's own signal but not
  // through the shaft-rate modulation. 0: none.
  double rolling_noise_m_s2_per_sqrt_hz = 0.0;

  bool has_lines() const {
    return !shaft_harmonics_m_s2.empty() || !half_orders_m_s2.empty() || !speed_locked_orders.empty() ||
           !line_harmonics_m_s2.empty();
  }
  bool has_floor() const { return !floor_frequencies_hz.empty(); }
  bool empty() const {
    return !has_lines() && !has_floor() && shaft_modulation_depth == 0.0 && rolling_noise_m_s2_per_sqrt_hz == 0.0;
  }
};

// What is wrong with an installation, as {key below `installation.`, what}; key empty: nothing.
struct InstallationProblem {
  std::string key, what;
};
InstallationProblem installation_problem(const InstallationConfig& c);

// The lines and the modulation, one input sample at a time; allocation-free per sample.
class MachineBackground {
 public:
  MachineBackground() = default;
  MachineBackground(const InstallationConfig& config, double input_rate_hz, std::uint64_t seed);

  struct Sample {
    double lines_m_s2 = 0.0;    // the machine's lines at the sensor
    double bearing_gain = 1.0;  // the factor on the bearing's signal (shaft-rate modulation)
  };
  // The next input sample, the turning ring at ring_angle_rad (wrapped or not: the angle is
  // followed through its increments, which must stay below half a turn per sample).
  Sample step(double ring_angle_rad);
  // The ring standing still at its last angle.
  Sample step() { return step(last_angle_); }
  void reset();

 private:
  // The other orders' lines after the ring turned by `increment`.
  double other_orders_lines(double increment, double nyquist_order);

  // Line series: coefficient k - 1 is A e^{i phase} of the k-th multiple of the base.
  std::vector<std::complex<double>> shaft_series_;       // k x f_r
  std::vector<std::complex<double>> half_order_series_;  // (k - 1/2) x f_r
  // Other orders: exact phases (wrapped to [0, 2 pi)) advance by order x the ring's
  // increment; the lines are read off phasors turned by the cached rotations (below).
  Eigen::ArrayXd other_orders_, other_amplitudes_, other_phase0_, other_phases_;
  Eigen::ArrayXcd other_phasors_, other_rotations_;
  double max_other_order_ = 0.0;
  double rotation_increment_ = 0.0;  // the increment the rotations were computed for
  int resync_countdown_ = 0;
  std::vector<std::complex<double>> line_series_;  // k x the line frequency
  double line_step_rad_ = 0.0, line_phase_ = 0.0;
  double modulation_depth_ = 0.0, modulation_phase_ = 0.0;
  bool started_ = false;
  double last_angle_ = 0.0;
  double shaft_phase_ = 0.0;  // the ring's angle followed through its increments, in [0, 4 pi)
};

}  // namespace bearing_sim
