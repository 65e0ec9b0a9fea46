#include "bearing_sim/core/biquad.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {

std::complex<double> Biquad::response(double f_hz, double fs_hz) const {
  const std::complex<double> x = std::polar(1.0, -2.0 * kPi * f_hz / fs_hz);  // z^-1
  return (b0 + x * (b1 + x * b2)) / (1.0 + x * (a1 + x * a2));
}

std::complex<double> seismic_transmissibility(double f_hz, double resonance_hz, double damping_ratio) {
  const std::complex<double> s(0.0, 2.0 * kPi * f_hz);
  const double wn = 2.0 * kPi * resonance_hz;
  return (2.0 * damping_ratio * wn * s + wn * wn) / (s * s + 2.0 * damping_ratio * wn * s + wn * wn);
}

Biquad design_seismic_path(double resonance_hz, double damping_ratio, double fs_hz) {
  if (!(resonance_hz > 0.0 && resonance_hz < 0.5 * fs_hz))
    throw InvalidInputError("seismic path: resonance must lie in (0, fs/2)");
  if (!(damping_ratio > 0.0 && damping_ratio < 1.0))
    throw InvalidInputError("seismic path: damping ratio must lie in (0, 1)");
  const double wn = 2.0 * kPi * resonance_hz, t = 1.0 / fs_hz;
  // Poles: z = exp(p T), p = -zeta wn +- j wn sqrt(1 - zeta^2).
  const std::complex<double> pole =
      std::exp(std::complex<double>(-damping_ratio * wn, wn * std::sqrt(1.0 - damping_ratio * damping_ratio)) * t);
  Biquad q;
  q.a1 = -2.0 * pole.real();
  q.a2 = std::norm(pole);
  // Numerator B(x) = b0 + b1 x + b2 x^2 (x = z^-1): B(1) = A(1) (unity at DC) and
  // B(x_n) = H(j wn) A(x_n) at x_n = exp(-j wn T): three real equations, three unknowns.
  const std::complex<double> xn = std::polar(1.0, -wn * t);
  const std::complex<double> target =
      seismic_transmissibility(resonance_hz, resonance_hz, damping_ratio) * (1.0 + xn * (q.a1 + xn * q.a2));
  Eigen::Matrix3d m;
  m << 1.0, 1.0, 1.0, 1.0, xn.real(), (xn * xn).real(), 0.0, xn.imag(), (xn * xn).imag();
  const Eigen::Vector3d rhs(1.0 + q.a1 + q.a2, target.real(), target.imag());
  const Eigen::Vector3d b = m.fullPivLu().solve(rhs);
  q.b0 = b(0);
  q.b1 = b(1);
  q.b2 = b(2);
  return q;
}

std::vector<Biquad> design_butterworth_lowpass(int order, double cutoff_hz, double fs_hz) {
  if (order < 2 || order % 2 != 0) throw InvalidInputError("Butterworth low-pass: order must be even and >= 2");
  if (!(cutoff_hz > 0.0 && cutoff_hz < 0.5 * fs_hz))
    throw InvalidInputError("Butterworth low-pass: cut-off must lie in (0, fs/2)");
  // Normalized analog sections 1/(s^2 + 2 sin(theta_k) s + 1), theta_k = pi (2k+1)/(2 order),
  // with s = (1/W)(1 - x)/(1 + x), W = tan(pi fc/fs) (pre-warped: the -3 dB point stays at fc).
  const double w = std::tan(kPi * cutoff_hz / fs_hz);
  std::vector<Biquad> sections;
  for (int k = 0; k < order / 2; ++k) {
    const double c = 2.0 * std::sin(kPi * (2.0 * k + 1.0) / (2.0 * order)) * w;
    const double a0 = 1.0 + c + w * w;
    Biquad q;
    q.b0 = w * w / a0;
    q.b1 = 2.0 * w * w / a0;
    q.b2 = w * w / a0;
    q.a1 = (2.0 * w * w - 2.0) / a0;
    q.a2 = (1.0 - c + w * w) / a0;
    sections.push_back(q);
  }
  return sections;
}

}  // namespace bearing_sim
