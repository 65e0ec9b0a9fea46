#include "bearing_sim/core/coloured_floor.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/constants.hpp"

namespace bearing_sim {
namespace {
// Bin width of the design: fine enough for density points a few tens of Hz apart; the cost
// is one multiply-add per tap and output sample (f_out / 10 Hz taps).
constexpr double kDesignBin_Hz = 10.0;
constexpr int kMinTaps = 33, kMaxTaps = 8193;
// The floor's own random stream of the sensor seed: the sensor noise keeps its numbers.
constexpr std::uint32_t kFloorStream = 2;
}  // namespace

double interpolated_floor_density(const std::vector<double>& f, const std::vector<double>& d, double f_hz) {
  if (f_hz <= f.front()) return d.front();
  if (f_hz >= f.back()) return d.back();
  const std::size_t i = std::upper_bound(f.begin(), f.end(), f_hz) - f.begin();  // f[i-1] < f_hz < f[i]
  const double t = std::log(f_hz / f[i - 1]) / std::log(f[i] / f[i - 1]);
  return d[i - 1] * std::pow(d[i] / d[i - 1], t);
}

ColouredFloor::ColouredFloor(const std::vector<double>& frequencies_hz, const std::vector<double>& densities,
                             double output_rate_hz, const std::vector<Biquad>& anti_alias, double input_rate_hz,
                             std::uint64_t seed)
    : output_rate_hz_(output_rate_hz), gaussian_(seed, kFloorStream) {
  const int half = std::clamp(static_cast<int>(std::ceil(0.5 * output_rate_hz / kDesignBin_Hz)), (kMinTaps - 1) / 2,
                              (kMaxTaps - 1) / 2);
  taps_count_ = 2 * half + 1;
  const int n = taps_count_;
  // Target magnitude on the bins k f_out / n: unit-variance white numbers have the one-sided
  // density 2 / f_out, so |H| = D sqrt(f_out / 2) gives the density D. No DC (AC-coupled).
  std::vector<double> magnitude(half + 1, 0.0);
  for (int k = 1; k <= half; ++k) {
    const double f = k * output_rate_hz / n;
    double aa = 1.0;
    for (const Biquad& q : anti_alias) aa *= std::abs(q.response(f, input_rate_hz));
    magnitude[k] = interpolated_floor_density(frequencies_hz, densities, f) * aa * std::sqrt(0.5 * output_rate_hz);
  }
  // Zero-phase impulse response (inverse DFT of a real, even spectrum), centred and
  // Hann-windowed (its ripple between the bins is then a fraction of a percent).
  std::vector<double> cosine(n);
  for (int m = 0; m < n; ++m) cosine[m] = std::cos(2.0 * kPi * m / n);
  taps_.resize(n);
  for (int i = 0; i < n; ++i) {
    const long shift = i - half;
    double sum = magnitude[0];
    for (int k = 1; k <= half; ++k) sum += 2.0 * magnitude[k] * cosine[((k * shift) % n + n) % n];
    const double window = 0.5 - 0.5 * std::cos(2.0 * kPi * (i + 1) / (n + 1));
    taps_(i) = sum / n * window;
  }
  buffer_.assign(2 * n, 0.0);
  reset();
}

void ColouredFloor::reset() {
  gaussian_.restart();
  newest_ = 0;
  for (int i = 0; i < taps_count_; ++i) buffer_[i] = buffer_[i + taps_count_] = gaussian_();
  newest_ = taps_count_ - 1;
}

double ColouredFloor::realised_density(double f_hz) const {
  std::complex<double> h = 0.0;
  for (int i = 0; i < taps_count_; ++i) h += taps_(i) * std::polar(1.0, -2.0 * kPi * f_hz * i / output_rate_hz_);
  return std::abs(h) / std::sqrt(0.5 * output_rate_hz_);
}

}  // namespace bearing_sim
