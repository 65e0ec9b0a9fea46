#include "bearing_sim/core/transmission_path.hpp"

#include <algorithm>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

std::complex<double> modal_transmissibility(const std::vector<PathMode>& modes, double f_hz) {
  // (1 - sum p) + sum p H_r: the rigid share plus each mode's seismic transmissibility.
  std::complex<double> h = 1.0;
  for (const PathMode& m : modes)
    h += m.participation * (seismic_transmissibility(f_hz, m.frequency_hz, m.damping_ratio) - 1.0);
  return h;
}

const PathMode& dominant_mode(const std::vector<PathMode>& modes) {
  if (modes.empty()) throw InvalidInputError("dominant_mode: no modes");
  return *std::max_element(modes.begin(), modes.end(), [](const PathMode& a, const PathMode& b) {
    return a.participation / a.damping_ratio < b.participation / b.damping_ratio;
  });
}

TransmissionPath::TransmissionPath(const std::vector<PathMode>& modes, double fs_hz)
    : fs_hz_(fs_hz), count_(static_cast<int>(modes.size())) {
  if (count_ > kMaxPathModes) throw InvalidInputError("transmission path: at most 16 modes");
  residual_ = 1.0;
  for (int r = 0; r < count_; ++r) {
    sections_[r] = design_seismic_path(modes[r].frequency_hz, modes[r].damping_ratio, fs_hz);
    participation_[r] = modes[r].participation;
    residual_ -= modes[r].participation;
  }
  single_ = count_ == 1 && participation_[0] == 1.0;
  if (count_ == 0) residual_ = 1.0;
}

void TransmissionPath::reset() {
  for (int r = 0; r < count_; ++r) sections_[r].reset();
}

std::complex<double> TransmissionPath::response(double f_hz) const {
  if (single_) return sections_[0].response(f_hz, fs_hz_);
  std::complex<double> h = residual_;
  for (int r = 0; r < count_; ++r) h += participation_[r] * sections_[r].response(f_hz, fs_hz_);
  return h;
}

}  // namespace bearing_sim
