#pragma once
// The machine's broadband vibration floor at the sensor (docs/sensor.md, "Coloured floor"):
// a Gaussian process whose one-sided density is given at points (Hz, m/s^2/sqrt(Hz)) and
// interpolated log-log between them (held at the end values outside).
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/biquad.hpp"
#include "bearing_sim/core/seeded_gaussian.hpp"

namespace bearing_sim {

// The density at f_hz: log-log between the points (frequencies increasing, densities > 0),
// the first or last value outside them.
double interpolated_floor_density(const std::vector<double>& frequencies_hz, const std::vector<double>& densities,
                                  double f_hz);

class ColouredFloor {
 public:
  ColouredFloor() = default;
  // Realised at the output rate, after the anti-alias filter (a linear filter of a Gaussian
  // process: only its density matters): white numbers through a linear-phase FIR whose
  // magnitude is D(f) |H_aa(f)| sqrt(f_out / 2), designed by frequency sampling on ~10 Hz
  // bins (Hann-windowed). anti_alias: the chain's sections at input_rate_hz.
  ColouredFloor(const std::vector<double>& frequencies_hz, const std::vector<double>& densities, double output_rate_hz,
                const std::vector<Biquad>& anti_alias, double input_rate_hz, std::uint64_t seed);

  // The floor's next output sample.
  double next() {
    const double x = gaussian_();
    if (++newest_ == taps_count_) newest_ = 0;
    buffer_[newest_] = buffer_[newest_ + taps_count_] = x;
    // The last taps_count_ inputs lie contiguous from newest_ + 1; the taps are symmetric.
    return Eigen::Map<const Eigen::VectorXd>(buffer_.data() + newest_ + 1, taps_count_).dot(taps_);
  }
  // Restarts the sequence (the filter is filled with noise: stationary from the first sample).
  void reset();
  int taps() const { return taps_count_; }
  // The FIR's magnitude over sqrt(f_out / 2) at f_hz: the density it realises.
  double realised_density(double f_hz) const;

 private:
  double output_rate_hz_ = 1.0;
  int taps_count_ = 0;
  int newest_ = 0;
  Eigen::VectorXd taps_;
  std::vector<double> buffer_;  // the last taps_count_ inputs, written twice
  SeededGaussian gaussian_;
};

}  // namespace bearing_sim
