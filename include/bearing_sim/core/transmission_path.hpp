#pragma once
// Transmission path of the virtual accelerometer (docs/sensor.md, "Transmission path"): the
// structure between the bearing's ring and the sensor as a superposition of base-excited
// modes. Absolute acceleration at the sensor over that of the ring,
//   H(s) = 1 - sum_r p_r s^2 / (s^2 + 2 zeta_r w_r s + w_r^2)
//        = (1 - sum_r p_r) + sum_r p_r H_r(s),
// H_r the seismic transmissibility of mode r (biquad.hpp) and p_r its participation at the
// sensor (mode shape there x participation factor). The modes listed carry sum p_r of the
// path; the rest, 1 - sum p_r, stands for modes above the band (which follow the ring when it
// is positive; negative when the list carries more than the whole path at the sensor, the
// modes above it having shapes of the other sign there).
// One mode with p = 1 is the single seismic resonance, sample for sample.
#include <complex>
#include <vector>

#include "bearing_sim/core/biquad.hpp"

namespace bearing_sim {

struct PathMode {
  double frequency_hz = 3000.0;
  double damping_ratio = 0.05;
  double participation = 1.0;
};

constexpr int kMaxPathModes = 16;
// Largest participation of one mode, and of all listed modes together (a guard against typing
// errors; docs/sensor.md, "Several modes").
constexpr double kMaxPathParticipation = 10.0;

// The analog H(s) above at f_hz (the closed form the digital path approximates).
std::complex<double> modal_transmissibility(const std::vector<PathMode>& modes, double f_hz);

// The mode with the highest peak transmissibility ~ p / (2 zeta): the path's resonance for
// an envelope band.
const PathMode& dominant_mode(const std::vector<PathMode>& modes);

class TransmissionPath {
 public:
  TransmissionPath() = default;
  // Each mode digitised by design_seismic_path at fs_hz (exact poles). Requires what
  // design_seismic_path requires, at most kMaxPathModes modes; no modes: a rigid path.
  TransmissionPath(const std::vector<PathMode>& modes, double fs_hz);

  double process(double x) {
    if (single_) return sections_[0].process(x);
    double y = residual_ * x;
    for (int r = 0; r < count_; ++r) y += participation_[r] * sections_[r].process(x);
    return y;
  }
  void reset();
  // The digital path's response at f_hz.
  std::complex<double> response(double f_hz) const;

 private:
  double fs_hz_ = 1.0;
  int count_ = 0;
  bool single_ = false;  // one mode, p = 1: its section alone
  double residual_ = 1.0;
  Biquad sections_[kMaxPathModes];
  double participation_[kMaxPathModes] = {};
};

}  // namespace bearing_sim
