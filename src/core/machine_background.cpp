#include "bearing_sim/core/machine_background.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/seeded_gaussian.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "indexed_key.hpp"

namespace bearing_sim {
namespace {

using detail::at;

// Bounds that catch a unit slip, not physics: 100 g is twice the usual sensor's range.
constexpr double kMaxAmplitude_m_s2 = 100.0 * kStandardGravity_m_s2;
constexpr std::size_t kMaxHarmonics = 256, kMaxOrders = 64, kMaxFloorPoints = 64;
constexpr double kMaxOrder = 10000.0;
constexpr double kMaxFloorDensity_m_s2 = 1.0 * kStandardGravity_m_s2;  // 1 g/sqrt(Hz)
// Each group of phases draws from a stream of its own, so adding a line to one list leaves
// the phases of the others (stream 2 is the floor's).
constexpr std::uint32_t kShaftStream = 1, kHalfOrderStream = 3, kOtherOrderStream = 4, kLineStream = 5;
// Other orders' phasors: turned by e^{i q d}, d the ring's increment, as e^{i q d_ref} times
// the second-order series of e^{i q (d - d_ref)} while |q (d - d_ref)| < 1e-4 (a phase error
// below 2e-13 rad per sample), recomputed beyond; set to their exact phases every 4096 samples
// (the drift in between stays below 1e-9 rad).
constexpr double kMaxRotationCorrection_rad = 1e-4;
constexpr int kResyncSamples = 4096;

InstallationProblem amplitudes_problem(const std::vector<double>& a, const std::string& key, std::size_t max_count) {
  if (a.size() > max_count) return {key, "at most " + std::to_string(max_count) + " values"};
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] >= 0.0 && a[i] <= kMaxAmplitude_m_s2)) return {at(key, i), "must be in [0, 1e5] mg"};
  return {};
}

double wrapped(double angle, double period) {
  if (angle >= 0.0 && angle < period) return angle;  // the usual case, without a division
  angle = std::fmod(angle, period);
  return angle < 0.0 ? angle + period : angle;
}

// sum_k Re(c_k first u^k), k = 0 .. terms - 1: a series of lines at the phases of first,
// first u, first u^2, ... by successive powers (no sin or cos per line), in two interleaved
// chains (even and odd k) so that their multiplications overlap.
double series(const std::vector<std::complex<double>>& c, std::size_t terms, std::complex<double> first,
              std::complex<double> u) {
  double even = 0.0, odd = 0.0;
  std::complex<double> z0 = first, z1 = first * u;
  const std::complex<double> u2 = u * u;
  std::size_t k = 0;
  for (; k + 1 < terms; k += 2) {
    even += c[k].real() * z0.real() - c[k].imag() * z0.imag();
    odd += c[k + 1].real() * z1.real() - c[k + 1].imag() * z1.imag();
    z0 *= u2;
    z1 *= u2;
  }
  if (k < terms) even += c[k].real() * z0.real() - c[k].imag() * z0.imag();
  return even + odd;
}

// How many of k = 1 .. size lie below limit (> 0, or infinite).
std::size_t terms_below(double limit, std::size_t size) {
  if (limit > static_cast<double>(size)) return size;
  return static_cast<std::size_t>(std::ceil(limit)) - 1;
}

}  // namespace

InstallationProblem installation_problem(const InstallationConfig& c) {
  InstallationProblem p = amplitudes_problem(c.shaft_harmonics_m_s2, "shaft_harmonics_mg", kMaxHarmonics);
  if (p.key.empty()) p = amplitudes_problem(c.half_orders_m_s2, "half_orders_mg", kMaxHarmonics);
  if (p.key.empty()) p = amplitudes_problem(c.line_harmonics_m_s2, "line_harmonics_mg", kMaxHarmonics);
  if (!p.key.empty()) return p;
  if (c.speed_locked_orders.size() > kMaxOrders) return {"speed_locked_orders", "at most 64 orders"};
  for (std::size_t i = 0; i < c.speed_locked_orders.size(); ++i) {
    const SpeedLockedOrder& o = c.speed_locked_orders[i];
    if (!(o.order > 0.0 && o.order <= kMaxOrder))
      return {at("speed_locked_orders", i) + ".order", "must be in (0, 10000]"};
    if (!(o.amplitude_m_s2 >= 0.0 && o.amplitude_m_s2 <= kMaxAmplitude_m_s2))
      return {at("speed_locked_orders", i) + ".amplitude_mg", "must be in [0, 1e5] mg"};
  }
  if (!(c.line_frequency_hz >= 1.0 && c.line_frequency_hz <= 1000.0))
    return {"line_frequency_Hz", "must be in [1, 1000] Hz (mains: 50 or 60)"};
  if (!(c.shaft_modulation_depth >= 0.0 && c.shaft_modulation_depth <= 4.0))
    return {"shaft_modulation_depth", "must be in [0, 4] (past 1 the bearing's signal stops for part of each turn)"};
  if (!(std::abs(c.shaft_modulation_phase_rad) <= 2.0 * kPi))
    return {"shaft_modulation_phase_deg", "must be in [-360, 360]"};
  if (!(c.rolling_noise_m_s2_per_sqrt_hz >= 0.0 && c.rolling_noise_m_s2_per_sqrt_hz <= kMaxFloorDensity_m_s2))
    return {"rolling_noise_ug_per_sqrt_Hz", "must be in [0, 1e6] ug/sqrt(Hz)"};
  const std::vector<double>& f = c.floor_frequencies_hz;
  const std::vector<double>& d = c.floor_density_m_s2_per_sqrt_hz;
  if (f.size() != d.size()) return {"floor", "frequencies_Hz and density_ug_per_sqrt_Hz must have the same length"};
  if (f.size() > kMaxFloorPoints) return {"floor.frequencies_Hz", "at most 64 points"};
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!(f[i] > 0.0 && std::isfinite(f[i])) || (i > 0 && !(f[i] > f[i - 1])))
      return {at("floor.frequencies_Hz", i), "must be > 0 and increasing"};
    // Log-log interpolation needs densities above zero.
    if (!(d[i] > 0.0 && d[i] <= kMaxFloorDensity_m_s2))
      return {at("floor.density_ug_per_sqrt_Hz", i), "must be in (0, 1e6] ug/sqrt(Hz)"};
  }
  return {};
}

MachineBackground::MachineBackground(const InstallationConfig& c, double input_rate_hz, std::uint64_t seed)
    : modulation_depth_(c.shaft_modulation_depth), modulation_phase_(c.shaft_modulation_phase_rad) {
  SeededGaussian shaft(seed, kShaftStream), half(seed, kHalfOrderStream), other(seed, kOtherOrderStream),
      line(seed, kLineStream);
  for (double a : c.shaft_harmonics_m_s2) shaft_series_.push_back(std::polar(a, 2.0 * kPi * shaft.uniform()));
  for (double a : c.half_orders_m_s2) half_order_series_.push_back(std::polar(a, 2.0 * kPi * half.uniform()));
  const Eigen::Index others = static_cast<Eigen::Index>(c.speed_locked_orders.size());
  other_orders_.resize(others);
  other_amplitudes_.resize(others);
  other_phase0_.resize(others);
  for (Eigen::Index i = 0; i < others; ++i) {
    other_orders_(i) = c.speed_locked_orders[i].order;
    other_amplitudes_(i) = c.speed_locked_orders[i].amplitude_m_s2;
    other_phase0_(i) = 2.0 * kPi * other.uniform();
  }
  other_phases_ = other_phase0_;
  max_other_order_ = others > 0 ? other_orders_.maxCoeff() : 0.0;
  other_phasors_.resize(others);
  other_rotations_.resize(others);
  // The line family is fixed in frequency: harmonics at or above the input Nyquist are left
  // out (the sampled dynamics cannot carry them).
  for (std::size_t h = 0; h < c.line_harmonics_m_s2.size(); ++h) {
    const double phase = 2.0 * kPi * line.uniform();
    if ((h + 1) * c.line_frequency_hz < 0.5 * input_rate_hz)
      line_series_.push_back(std::polar(c.line_harmonics_m_s2[h], phase));
  }
  line_step_rad_ = 2.0 * kPi * c.line_frequency_hz / input_rate_hz;
  reset();
}

void MachineBackground::reset() {
  started_ = false;
  last_angle_ = shaft_phase_ = line_phase_ = 0.0;
  other_phases_ = other_phase0_;
  other_phasors_.setOnes();
  other_rotations_.setOnes();
  rotation_increment_ = 0.0;
  resync_countdown_ = 0;
}

double MachineBackground::other_orders_lines(double increment, double nyquist_order) {
  other_phases_ += other_orders_ * increment;
  other_phases_ -= (2.0 * kPi) * (other_phases_ * (0.5 / kPi)).floor();
  const double delta = increment - rotation_increment_;
  if (--resync_countdown_ <= 0) {
    other_phasors_ = other_phases_.unaryExpr([](double p) { return std::polar(1.0, p); });
    resync_countdown_ = kResyncSamples;
  } else if (std::abs(max_other_order_ * delta) < kMaxRotationCorrection_rad) {
    // e^{i q delta} ~ 1 - (q delta)^2 / 2 + i q delta (an expression: no temporary array).
    other_phasors_ *= other_rotations_ * (other_orders_ * delta).unaryExpr([](double a) {
      return std::complex<double>(1.0 - 0.5 * a * a, a);
    });
  } else {
    rotation_increment_ = increment;
    other_rotations_ = (other_orders_ * increment).unaryExpr([](double a) { return std::polar(1.0, a); });
    other_phasors_ *= other_rotations_;
  }
  return (other_orders_ < nyquist_order).select(other_amplitudes_ * other_phasors_.real(), 0.0).sum();
}

MachineBackground::Sample MachineBackground::step(double angle) {
  double increment = 0.0;
  if (!started_) {
    // Locked to the ring's angle from the first sample: harmonic k at k theta + its phase.
    started_ = true;
    shaft_phase_ = wrapped(angle, 4.0 * kPi);
    other_phases_ = other_orders_ * angle + other_phase0_;
  } else {
    increment = std::remainder(angle - last_angle_, 2.0 * kPi);
    shaft_phase_ = wrapped(shaft_phase_ + increment, 4.0 * kPi);
  }
  last_angle_ = angle;
  const double step = std::abs(increment);
  Sample s;
  const std::complex<double> half_turn = std::polar(1.0, 0.5 * shaft_phase_);  // e^{i theta / 2}
  const std::complex<double> turn = half_turn * half_turn;                     // e^{i theta}
  // A line at x f_r moves by x step per sample: at or above the input Nyquist (x step >= pi)
  // it cannot be sampled and is left out.
  const double nyquist_order = step > 0.0 ? kPi / step : HUGE_VAL;
  if (!shaft_series_.empty())  // k x f_r, k < nyquist_order
    s.lines_m_s2 += series(shaft_series_, terms_below(nyquist_order, shaft_series_.size()), turn, turn);
  if (!half_order_series_.empty())  // (k - 1/2) x f_r
    s.lines_m_s2 +=
        series(half_order_series_, terms_below(nyquist_order + 0.5, half_order_series_.size()), half_turn, turn);
  if (other_orders_.size() > 0) s.lines_m_s2 += other_orders_lines(increment, nyquist_order);
  if (!line_series_.empty()) {
    line_phase_ += line_step_rad_;
    if (line_phase_ >= 2.0 * kPi) line_phase_ -= 2.0 * kPi;
    const std::complex<double> line_turn = std::polar(1.0, line_phase_);
    s.lines_m_s2 += series(line_series_, line_series_.size(), line_turn, line_turn);
  }
  if (modulation_depth_ > 0.0) {
    // A load that swings past zero leaves the spot unloaded, not pulling: no negative gain.
    s.bearing_gain = std::max(0.0, 1.0 + modulation_depth_ * (turn.real() * std::cos(modulation_phase_) -
                                                              turn.imag() * std::sin(modulation_phase_)));
  }
  return s;
}

}  // namespace bearing_sim
