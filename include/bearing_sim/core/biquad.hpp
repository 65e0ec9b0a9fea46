#pragma once
// Second-order IIR sections for the sensor chain (docs/sensor.md): the transmission-path
// resonance and the Butterworth anti-alias low-pass. Internal helpers of the core library,
// public so that tests and tools can evaluate the same designs.
#include <complex>
#include <vector>

namespace bearing_sim {

// H(z) = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2), transposed direct form II
// (two state values, well conditioned in double precision, no allocation).
struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
  double s1 = 0.0, s2 = 0.0;

  double process(double x) {
    const double y = b0 * x + s1;
    s1 = b1 * x - a1 * y + s2;
    s2 = b2 * x - a2 * y;
    return y;
  }
  void reset() { s1 = s2 = 0.0; }
  // Frequency response at f_hz for the sample rate fs_hz.
  std::complex<double> response(double f_hz, double fs_hz) const;
};

// Closed-form "seismic" transmissibility of a base-excited mass-spring-damper: absolute
// acceleration of the mass over that of the base,
//   H(s) = (2 zeta wn s + wn^2) / (s^2 + 2 zeta wn s + wn^2),  wn = 2 pi fn,
// unity at low frequency, |H(fn)| = sqrt(1 + 4 zeta^2) / (2 zeta) ~ 1/(2 zeta).
std::complex<double> seismic_transmissibility(double f_hz, double resonance_hz, double damping_ratio);

// Digital version of seismic_transmissibility at fs_hz: poles mapped exactly (z = exp(s T),
// so the resonance frequency and the decay of the ringing are exact) and the numerator
// fitted so that H(z) equals H(s) at DC and at fn (magnitude and phase).
// Requires 0 < resonance_hz < fs_hz / 2 and 0 < damping_ratio < 1.
Biquad design_seismic_path(double resonance_hz, double damping_ratio, double fs_hz);

// Butterworth low-pass of even order, bilinear transform with the cut-off pre-warped, as
// order/2 sections. Its magnitude is exactly
//   |H(f)|^2 = 1 / (1 + (tan(pi f/fs) / tan(pi fc/fs))^(2 order)).
std::vector<Biquad> design_butterworth_lowpass(int order, double cutoff_hz, double fs_hz);

}  // namespace bearing_sim
